// The bit-accurate CPU model of every pass of the multipass noise (Hart 2001, section 4), the
// golden model the OpenGL ES executor (testbench/gpu/) is checked against bit for bit.
//
// Each image is 8-bit UNORM, as the paper's RGBA8 framebuffer. Arithmetic follows the GL
// specification's fixed-point data conversions (OpenGL ES 3.2 section 2.3.4 / GL 4.6 2.3.5):
// a byte c reads as the real c / 255; a real x is stored as round(clamp(x, 0, 1) 255), "one of
// the two closest values, rounding to nearest preferred", so a value exactly halfway between
// two bytes is left to the driver. The model computes each pass's exact real value and counts
// how close it came to such a tie (Stats::minTieMargin): the program keeps every value well
// away from ties (program.h, shiftRightBias), so the model's result is the specified one.
// Blends are evaluated as the specification says, "as if carried out in floating point":
// dst src is stored as round(D S / 255) (never a tie: 255 is odd).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "program.h"
#include "tables.h"

namespace pst::multipass {

// A luminance image of bytes, row-major (the paper's R = G = B images).
struct Image8 {
    int width = 0, height = 0;
    std::vector<uint8_t> px;
};

struct Stats {
    // Smallest distance, in LSB, from a stored unclamped value to a rounding tie (0.5 = every
    // value an exact byte). Above ~1e-3 a float32 implementation rounds to the same byte.
    double minTieMargin = 0.5;
};

// The images of a run: the three input coordinate images in, every image of Image after.
struct State {
    std::array<Image8, kImageCount> img;
};

// Runs the program on s, t, r (bytes, b_i.b_f fixed point; equal sizes); returns tex_noise.
// `state`, when given, receives every image after the last pass (the intermediates).
Image8 runCpu(const Program& prog, const Tables& tables, const Image8& s, const Image8& t,
              const Image8& r, Stats* stats = nullptr, State* state = nullptr);

// A solid-texture coordinate as the input byte: floor(x 2^b_f) mod 2^b (the multipass noise
// has period 2^b_i per axis, tables.h). For an atlas of solid texture coordinates.
uint8_t toFixed(double x, const Format& f);

}  // namespace pst::multipass

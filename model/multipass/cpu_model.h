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

// Register-combiner arithmetic (section 5; NV_register_combiners). Assumptions, since neither
// the paper nor NVIDIA's specification gives the bit-level format (the extension says only
// that values lie in [-1, 1] with "at least" 8 bits of precision plus sign):
//  - A register holds a 9-bit signed value k in [-255, 255] meaning k / 255: the paper's
//    "signed byte arithmetic with a full 9 bits per channel" (5.1) on the framebuffer's grid,
//    so a texture byte c enters as k = c exactly and 6.1's expand mapping 2x - 1 (2c - 255) is
//    exact. Every register write clamps to [-1, 1] (the extension's rule), i.e. to +-255.
//  - A product A B is rounded to the nearest k: round(a b / 255), never a tie (255 is odd).
//  - bias_by_negative_one_half subtracts 128/255: -1/2 is not on the grid; 128 is the
//    nearest value at or below it. With it, 5.2's routine 2 (hibit ? c - 1/2 : c) is the
//    exact logical shift left 2c - 256 hibit(c) the paper calls it (with 127/255 it would
//    leave a one in the low bit instead; the bit-serial randomization reads only high bits
//    and would give the same lattice values, the weights would not).
//  - The mux (A B | C D) selects C D when Spare0's alpha >= 1/2, i.e. k >= 128.
//  - The final combiner computes A B + (1 - A) C with each product rounded as above; the
//    result clamps to [0, 1] and is stored as the byte k (8-bit framebuffer: "can only store
//    8 bit results", 5.1).
namespace rc {
inline int clamp9(int k) { return k < -255 ? -255 : k > 255 ? 255 : k; }
// round(a b / 255) for signed a, b in [-255, 255]: the sign apart, floor((2|ab| + 255) / 510)
inline int mul(int a, int b) {
    const int p = a * b, q = ((p < 0 ? -p : p) * 2 + 255) / 510;
    return clamp9(p < 0 ? -q : q);
}
inline int store(int k) { return k < 0 ? 0 : k > 255 ? 255 : k; }
constexpr int kHalf = 128;  // bias_by_negative_one_half, and the mux threshold
// Section 5.2's shift left (two general combiners): stage 1 spare0.a = tex0.b,
// spare0.rgb = tex0 1 - 1/2; stage 2 spare0.rgb = 2 (spare0.a < 1/2 ? tex0 1 : spare0.rgb 1).
inline int shiftLeft(int c) {
    const int spareA = mul(c, 255), spareRgb = clamp9(mul(c, 255) - kHalf);
    return store(clamp9(2 * (spareA < kHalf ? mul(c, 255) : mul(spareRgb, 255))));
}
// The +1 corner with the wrap (one pass): stage 1 rgb spare0 = tex0 1 + const0 1 (const0 =
// k0 = 2^b_f), alpha spare0.a = 4 (tex0 1 - const1 1) (const1 = k1 = 256 - 2^b_f - 32, by
// SIGNED_NEGATE, scale_by_four); stage 2 spare0.rgb = spare0.a < 1/2 ? spare0.rgb 1 : 0 0.
// spare0.a >= 1/2 exactly when c >= k1 + 32 = 256 - 2^b_f, i.e. K = 2^b_i - 1.
inline int incWrap(int c, int k0, int k1) {
    const int sum = clamp9(mul(c, 255) + mul(k0, 255));
    const int alpha = clamp9(4 * (mul(c, 255) - mul(k1, 255)));
    return store(alpha < kHalf ? mul(sum, 255) : mul(0, 0));
}
// Section 5.3's setupblendhibit(rgba0, rgba1) + blend2tex(tex0, tex1): stage 1 spare0.a =
// tex0.b; stage 2 spare0.rgb = spare0.a < 1/2 ? rgba0 1 : rgba1 1; final combiner A = the
// constants' alpha, B = spare0.rgb, C = tex1: A B + (1 - A) C.
inline int blendHiBit(int c, int acc, int k0, int k1, int alpha) {
    const int spareA = mul(c, 255), col = spareA < kHalf ? mul(k0, 255) : mul(k1, 255);
    return store(mul(alpha, col) + mul(255 - alpha, acc));
}
}  // namespace rc

// A luminance image, row-major (the paper's R = G = B images): b-bit UNORM values (bytes at
// the paper's b = 8; Program::b).
struct Image8 {
    int width = 0, height = 0;
    std::vector<uint32_t> px;
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

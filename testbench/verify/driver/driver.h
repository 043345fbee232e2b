// The hardware driver: what a graphics driver does for the texture chip. It turns a texture
// (double parameters, a colour map) into register writes in the profile's formats, builds the
// colour tables (clut, summed-area table, MIP levels) in C++, and converts fragments to the
// fixed-point input formats (round to nearest, saturate).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "pipeline.h"
#include "profile.h"
#include "rasterizer.h"
#include "texture.h"

namespace pst {

using RegWrites = std::vector<std::pair<uint16_t, uint32_t>>;

struct TextureProgram {
    RegWrites writes;           // control, quadric, octaves, tables
    int activeOctaves = 0;      // octaves the hardware evaluates
    int droppedOctaves = 0;     // texture octaves beyond the profile's count (the last ones)
    int filterKind = 3;         // hardware filter code (0 none, 1 mip, 2 mip blended, 3 sat)
    std::string notes;          // what the hardware does differently from the texture's request
};

// The hardware filter code for a texture's filter (box is the reference-only exact integral;
// the hardware's box filter is the SAT).
int hardwareFilterKind(FilterKind k);

// Empty if profile p can run texture tex, else why not, as "FILE:LINE: FIELD: what" when the
// scene file named the field: a profile's noise unit computes one basis (Profile::noise.basis:
// rayshade, or perlin2002 for the quintic / grad12 / perlin256 unit); worley is reference-only.
// The filter option profile p refuses on texture tex because it measured worse than unfiltered
// ("" if none): the colour-table MIP map on a ramp colour map on bases worley and subband
// without its anisotropic filter (docs/HARDWARE.md unit 6, refused combinations).
std::string refusedFilter(const Profile& p, const Texture& tex);
std::string hardwareUnsupported(const Profile& p, const Texture& tex);

// Throws InputError (hardwareUnsupported's message) for a texture the profile cannot run,
// rather than program the profile's own noise in its place.
TextureProgram programTexture(const Profile& p, const Texture& tex);
// Only the control register (wrap, filter kind), e.g. to render the unfiltered image.
std::pair<uint16_t, uint32_t> controlWrite(const Texture& tex, int filterKind);

// Bandlimited octaves (filter.bandlimit profiles): the octave's lg ||M||_2 register (FadeLgFrac
// fraction bits, saturated to FadeLgBits; M = 0 gives the lowest) and fade table entry k,
// round(2^FadeFrac sqrt(noiseBoxGain(noise, nu))) at the entry's centre, lg nu = -FadeLgLo + (k + 1/2) / 4.
int64_t fadeLgNorm(const glm::dmat3& M);
int64_t fadeTableEntry(const NoiseOptions& noise, int k);
// Entry k of the table on a subband unit with its anisotropic filter (noise.subband_orientations):
// the weight h(nu) = exp(-sigma^2 pi^2 nu^2 / 2) (FadeFrac bits) at lg nu = -FadeLgLo + (k + 1/2) / 4
// + kSubbandWeightOffset, 5/16 octave above the entry's centre: a little more filtering than eq. 4
// at the entry's nu (the lg the unit reads, Mitchell's with its mantissa corrected and floored to
// the quarter octave, is up to 0.088 octave above the true lg and up to 0.29 below). The offset
// that brings the unit's still closest to the truth: seascape_subband on reduced_subband_k8 at
// 64 x 64 against a 16 x 16 truth, offsets 1/8, 3/16, 1/4, 5/16, 3/8, 1/2 octave: RMS 0.03826,
// 0.03819, 0.03814, 0.03814, 0.03815, 0.03834 (the reference's exact filter 0.03823); its fly-in
// (16 frames at 48 x 48, 8 x 8 truth) flickers 0.01205, 0.01180, 0.01164, 0.01156, 0.01156, 0.01209
// (unfiltered 0.04872).
constexpr double kSubbandWeightOffset = 0.3125;
int64_t subbandWeightEntry(const NoiseOptions& noise, int k);

// The width cap register (filter.width_cap profiles, register wcap): widthCapOf(tex, octaves) N in
// W's format, floor(cap N 2^WidthFrac) saturated to the largest W (all ones: no cap); all ones
// also when the texture has no width_cap or its quadric varies (widthCapOf infinite).
int64_t widthCapRegister(const Profile& p, const Texture& tex, int octaves);

FragmentFx quantizeFragment(const Profile& p, uint32_t tag, const glm::dvec3& s,
                            const glm::dvec3& dsdx, const glm::dvec3& dsdy);

// Back to numbers: the hardware's colour as RGBA in [0, 1].
glm::dvec4 unpackRgba(const Profile& p, uint32_t rgba);

}  // namespace pst

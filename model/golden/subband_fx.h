// Golden (bit-accurate) model of the subband unit (rtl/noise/pst_subband.sv): the anisotropic-
// noise basis of Goldberg, Zwicker, Durand 2008 (model/subband.h) as the hardware samples it,
// the isotropic band-limited sum of one octave's subbands (section 2; eq. 7 with every
// lambda_ij = 1, gamma_ij = 1 on the octave's scale: no distortion, a plane) read from a tile ROM
// by bilinear, periodic lookups on two lattice axes. Same steps and floors as the RTL; see
// subband_fx.cpp.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "contract.h"
#include "profile.h"

namespace pst {

// ROM pixels per noise unit, as a power of two: SubbandTileLog2 - SubbandPeriodLog2.
constexpr int kSubbandUnitBits = contract::kSubbandTileLog2 - contract::kSubbandPeriodLog2;
constexpr int kSubbandRomSide = 1 << contract::kSubbandTileLog2;
constexpr int kSubbandRomWords = kSubbandRomSide * kSubbandRomSide;

// The tile the ROM holds, in double: the reference's centre-scale isotropic sum
// (subbandTiles(4, SubbandRefTile, SubbandSeed).isoValue[kSubbandCentreScale]) times
// subbandCentreScale, sampled every SubbandRefTile / 2^SubbandTileLog2-th pixel in x and y.
// Word i = y 2^SubbandTileLog2 + x. Built once.
const std::vector<double>& subbandRomTile();
// ROM word i: the tile value rounded to SubbandValueFrac fraction bits, saturated to
// SubbandValueBits signed bits (sim/tools/pst_roms writes the same words to subband64.memh).
int64_t subbandRomWord(int i);

// The profile's two lattice axes (noise.subband xy: 0, 1; xz: 0, 2; yz: 1, 2).
void subbandAxes(const Profile& prof, int* a0, int* a1);

struct SubbandFxTrace {
    int addr[4] = {};      // ROM address of corner c = cx + 2 cy
    int64_t v[4] = {};     // its word
    int64_t wx = 0, wy = 0;  // the bilinear weights' fractions (NoiseLatticeFrac - kSubbandUnitBits bits)
    int64_t accV = 0, accGx = 0, accGy = 0;  // the exact sums (see subband_fx.cpp)
};

// In: lat (0..4095) and frac (NoiseLatticeFrac bits) per axis, as noiseFx. Out: n (Q4.OF) and
// grad = dn/dp (3 x Q6.OF; the axis outside the plane 0). Requires prof.noiseSubband != None
// (throws std::invalid_argument).
void subbandFx(const Profile& prof, const int lat[3], const int64_t frac[3], int64_t* n, int64_t grad[3],
               SubbandFxTrace* trace = nullptr);

// The unit's double reference: the bilinear, periodic lookup of subbandRomTile at uv (noise
// units on the plane's two axes), and its gradient d/duv (the derivative of the bilinear
// interpolant).
double subbandRomReference(const glm::dvec2& uv, glm::dvec2* grad);

// Honest worst-case bounds of |subbandFx - subbandRomReference| at the exact point the unit
// sees (no saturation: |n| < 8, |grad| < 32). Derived in subband_fx.cpp.
struct SubbandFxErrorBound {
    double value = 0;
    double grad = 0;  // each in-plane component
};
SubbandFxErrorBound subbandFxErrorBound(const Profile& prof);

}  // namespace pst

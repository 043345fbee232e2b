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

// The orientations of the profile's unit: 0 (one tile, the isotropic sum) or K = 4, 8 (K oriented
// tiles and the anisotropic filter; noise.subband_orientations). Tiles: max(1, K).
inline int subbandOrientations(const Profile& p) { return p.noiseSubbandOrientations; }
inline int subbandTileCount(int K) { return K == 0 ? 1 : K; }

// The tiles the ROM holds, in double, [t][y][x]: K = 0 the reference's centre-scale isotropic sum
// (subbandTiles(4, SubbandRefTile, SubbandSeed).isoValue[kSubbandCentreScale]); K = 4, 8 its K
// oriented tiles n_{i,jc} (subbandTiles(K, ...).value); each times subbandCentreScale, sampled
// every SubbandRefTile / 2^SubbandTileLog2-th pixel in x and y. Word a = y 2^SubbandTileLog2 + x.
// Built once per K.
const std::vector<double>& subbandRomTile(int K);
// Tile t's part of ROM word a: the tile value rounded to SubbandValueFrac fraction bits, saturated
// to SubbandValueBits signed bits (sim/tools/pst_roms writes the words, tile t at bits
// [t SubbandValueBits +: SubbandValueBits], to subband.memh (K = 0) and subband_kK.memh).
int64_t subbandRomWord(int K, int t, int a);

// The profile's two lattice axes (noise.subband xy: 0, 1; xz: 0, 2; yz: 1, 2).
void subbandAxes(const Profile& prof, int* a0, int* a1);

// The filter's orientation i of K as the direction constants (round(2^8 cos(pi i / K)),
// round(2^8 sin(pi i / K))), SubbandDirFrac fraction bits.
void subbandDirection(int K, int i, int* c, int* s);
// Per pixel (rtl/octave/pst_subband_pixel.sv): for each edge e (x: j[0..2], y: j[3..5]) and
// orientation i, lg |c_i . (j_a0, j_a1)| (the edge on the plane, along the orientation):
// p = floor((C_i j_a0 + S_i j_a1) / 2^SubbandDirFrac), lg[e K + i] = subbandLgCorrectFx(mitchellLgFx(|p|)).
void subbandPixelLgFx(const Profile& prof, const int64_t j[6], int64_t lg[16]);
// Mitchell's lg with its FadeLgFrac mantissa bits m replaced by floor(2^FadeLgFrac lg(1 + (m + 1/2) /
// 2^FadeLgFrac)) (lg |p| is the result + -0.038 .. +0.088 octave; uncorrected + 0 .. 0.149).
int64_t subbandLgCorrectFx(int64_t lg);
// Per octave: lambda_i = octaveFadeFx(lg[i], lg[K + i], lgm, table) (FadeFrac fraction bits, <= 1.0):
// the separable Gaussian of eq. 4, h(nu_x) h(nu_y), h the driver's table exp(-sigma^2 pi^2 nu^2 / 2).
void subbandLambdaFx(const Profile& prof, const int64_t lg[16], int64_t lgm, const int64_t table[contract::kFadeEntries],
                     int64_t lambda[8]);

struct SubbandFxTrace {
    int addr[4] = {};        // ROM address of corner c = cx + 2 cy
    int64_t v[4] = {};       // its word (K = 0) or the weighted sum of its K words (K = 4, 8)
    int64_t wx = 0, wy = 0;  // the bilinear weights' fractions (NoiseLatticeFrac - kSubbandUnitBits bits)
    int64_t accV = 0, accGx = 0, accGy = 0;  // the exact sums (see subband_fx.cpp)
};

// In: lat (0..4095) and frac (NoiseLatticeFrac bits) per axis, as noiseFx; lambda: K = 4, 8 the
// orientations' weights (FadeFrac bits, 0 .. 2^FadeFrac; nullptr: all 1.0), unused for K = 0. Out:
// n (Q4.OF) and grad = dn/dp (3 x Q6.OF; the axis outside the plane 0). Requires
// prof.noiseSubband != None (throws std::invalid_argument).
void subbandFx(const Profile& prof, const int lat[3], const int64_t frac[3], const int64_t* lambda, int64_t* n,
               int64_t grad[3], SubbandFxTrace* trace = nullptr);

// The unit's double reference: the bilinear, periodic lookup of subbandRomTile(K) at uv (noise
// units on the plane's two axes), the tiles weighted by lambda (K values, nullptr: 1), and its
// gradient d/duv (the derivative of the bilinear interpolant).
double subbandRomReference(int K, const glm::dvec2& uv, const double* lambda, glm::dvec2* grad);

// Honest worst-case bounds of |subbandFx - subbandRomReference| at the exact point the unit
// sees, for the profile's K and weights of at most 1.0 (no saturation: |n| < 8, |grad| < 32).
// Derived in subband_fx.cpp.
struct SubbandFxErrorBound {
    double value = 0;
    double grad = 0;  // each in-plane component
};
SubbandFxErrorBound subbandFxErrorBound(const Profile& prof);

}  // namespace pst

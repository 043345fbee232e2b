// Golden (bit-accurate) model of pipeline units 1 and 2 (docs/HARDWARE.md): the octave
// transform p = M s + o and the noise unit n(p), dn/dp. Mirrors rtl/octave/pst_octave_transform.sv
// and rtl/noise/pst_noise.sv step for step; the arithmetic is documented in the SV module headers
// and again in noise_fx.cpp. Every value is an integer: a format's value is integer / 2^frac.
#pragma once

#include <cstdint>

#include "profile.h"

namespace pst {

// Guard bits of the noise unit's internal nodes: corner values, lerp results and their
// derivatives are held at NoiseOutFrac + noise.guard_bits fraction bits (the profile's key;
// rtl/noise/pst_noise.sv parameter NoiseGuardBits).
inline int noiseNodeFrac(const Profile& p) { return p.noiseOutFrac + p.noiseGuardBits; }

// The floor of the noise unit's derivative lanes (noise.grad_frac; rtl/noise/pst_noise.sv parameter
// NoiseGradFrac): every corner and lerp derivative is a multiple of 2^noiseGradFloor at
// noiseNodeFrac fraction bits, i.e. it keeps min(grad_frac, node frac) fraction bits. 0 (the
// default, grad_frac = out_frac + guard_bits) keeps every node bit.
inline int noiseGradFloor(const Profile& p) {
    return p.noiseGradFrac < noiseNodeFrac(p) ? noiseNodeFrac(p) - p.noiseGradFrac : 0;
}

// Unit 1. s: 3 x Coord, M: 9 x Matrix (row-major, M[3 r + c]), o: 3 x Offset, all
// sign-extended integers of their formats. Out per axis: lat = lattice index after Rayshade's
// 1e6 offset, mod 4096 (0..4095); frac = the unsigned NoiseLatticeFrac-bit fraction u.
// Throws std::invalid_argument if MatrixFrac + CoordFrac < NoiseLatticeFrac or < OffsetFrac.
void octaveTransformFx(const Profile& prof, const int64_t s[3], const int64_t M[9], const int64_t o[3],
                       int lat[3], int64_t frac[3]);

// Unit 2. In: lat (0..4095) and frac (0 .. 2^NoiseLatticeFrac - 1) per axis. Out: n
// (Q4.NoiseOutFrac) and grad = dn/dp (3 x Q6.NoiseOutFrac), as sign-extended integers.
void noiseFx(const Profile& prof, const int lat[3], const int64_t frac[3], int64_t* n, int64_t grad[3]);

// The intermediate values of one noiseFx call (to locate a mismatch, and for tests).
// Corner c = bx + 2 by + 4 bz (x fastest, Rayshade's order). A node is (v, dv/dx, dv/dy,
// dv/dz) at noiseNodeFrac fraction bits.
struct NoiseFxTrace {
    int m[8] = {};              // value-table index of each corner (0..255)
    int64_t s[3] = {}, ds[3] = {};  // weight and its derivative per axis, NoiseLatticeFrac bits
    int64_t corner[8][4] = {};  // corner nodes
    int64_t node[7][4] = {};    // lerp outputs: 0..3 x lerps (by + 2 bz), 4..5 y lerps (bz), 6 z
};
void noiseFx(const Profile& prof, const int lat[3], const int64_t frac[3], int64_t* n, int64_t grad[3],
             NoiseFxTrace* trace);

// The value ROM entry i (0..266) at NoiseValueFrac fraction bits: value16 >>> (15 - frac),
// value16 = R[i] * 32768 (sim/tools/pst_roms.cpp writes the same numbers).
int64_t noiseValueRom(const Profile& prof, int i);

// Honest worst-case bounds of |noiseFx - noise(p_q)| (value, and each gradient component) for
// the profile's formats and options, where p_q is the exact point the unit sees (lattice
// index + frac / 2^NoiseLatticeFrac). Derived in noise_fx.cpp from the formats (not tuned).
struct NoiseFxErrorBound {
    double value = 0;
    double grad = 0;
    double gradMax = 0;      // max |dn/dp_k| of the double noise (for input-quantization terms)
    double hessianRow = 0;   // max sum_j |d2n/dp_k dp_j| inside a cell (idem)
};
NoiseFxErrorBound noiseFxErrorBound(const Profile& prof);

}  // namespace pst

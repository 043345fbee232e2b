// The random tables of the SGI multipass noise (Hart 2001, section 4.3): sran, tran, rran,
// uniform random values in [0, 1/3] indexed by the integer parts of s, t, r (their sum stays
// in [0, 1]), and nran, the final randomization of the sum (Figure 6 (d)), uniform in [0, 1].
// Perm and ValuePerm (the exclusive-or variant) are Rayshade's permutation P and the byte of
// 0.5 R[P[m]] + 1/2 (model/noise.h), whatever the seed; at b bits, P[x & 255] and the value
// round((0.5 R + 1/2)(2^b - 1)).
// Entries are stored as the framebuffer stores them: 8-bit UNORM bytes (0..85 and 0..255).
#pragma once

#include <array>
#include <cstdint>

#include "program.h"

namespace pst::multipass {

struct Tables {
    // 256 entries each at b = 8; Perm and ValuePerm 2^b entries at b > 8 (Perm of the low 8
    // bits, the value at b bits; sran .. nran are the b = 8 variants', 256 entries always)
    std::array<std::vector<uint32_t>, kTableCount> t;
    Tables() { for (auto& v : t) v.assign(256, 0); }
    const std::vector<uint32_t>& operator[](int table) const { return t[table]; }
};

// Drawn from the POSIX 48-bit generator (erand48, as Rayshade's tables) seeded by `seed`:
// sran, tran, rran entries floor(u 86) in 0..85 (85/255 = 1/3), nran entries floor(u 256).
// The lattice wraps: entry i of sran/tran/rran equals entry i mod 2^b_i, so the noise is
// periodic with 2^b_i cells per axis (the corner index K + 1 reaches 2^b_i).
Tables makeTables(const Params& params);

}  // namespace pst::multipass

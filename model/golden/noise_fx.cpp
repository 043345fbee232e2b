// Golden model of the octave transform and the noise unit (docs/HARDWARE.md units 1 and 2),
// bit for bit as rtl/octave/pst_octave_transform.sv and rtl/noise/pst_noise.sv (same steps, same floors).
//
// Notation: LF = NoiseLatticeFrac, VF = NoiseValueFrac, OF = NoiseOutFrac,
// NF = OF + noise.guard_bits (internal node fraction bits), F = noiseGradFloor (NF -
// noise.grad_frac when that is > 0, else 0: the derivative lanes' floor). floor = fx::floorShift.
//
// Unit 1 (octave transform), per axis r:
//   acc = sum_j M[r][j] s[j] + (o[r] << (MatrixFrac + CoordFrac - OffsetFrac))   exact
//   p   = floor(acc to LF fraction bits)
//   u   = p mod 2^LF (unsigned fraction), L = (floor(p / 2^LF) + 576) mod 4096.
//
// Unit 2 (noise unit), U = u * 2^LF per axis:
//   weights   scurve: u2 = floor(U U / 2^LF); s = floor(u2 (3 2^LF - 2U) / 2^LF);
//                     ds = 6 (U - u2)            (= 6 u (1 - u), reusing u2: no multiplier)
//             linear: s = U; ds = 2^LF (ds = 1: the own-axis product is b - a, exact)
//             quintic (Perlin 2002's fade 6t^5 - 15t^4 + 10t^3 = t^3 (6t^2 - 15t + 10)):
//                     u2 = floor(U U / 2^LF); t3 = floor(u2 U / 2^LF);
//                     w = 6 u2 - 15 U + 10 2^LF (> 0: shifts and adds, no multiplier);
//                     s = floor(t3 w / 2^LF); a = U - u2 (= u (1 - u), in [0, 2^(LF-2)]);
//                     ds = floor(30 a a / 2^LF)  (fade' = 30 u^2 (1 - u)^2; x30 = x32 - x2)
//   hash      Rayshade: m = T[T[T[X] ^ Y] ^ Z] & 0xff, X in {L_x, L_x + 1 mod 4096}, ...
//             perm256:  m = P[P[P[X] ^ Y] ^ Z],  X in {L_x mod 256, L_x + 1 mod 256}, ...
//             perlin256: m = P[(P[(P[X] + Y) mod 256] + Z) mod 256] with Perlin's P,
//                     X in {(L_x - 64) mod 256, +1} (L = floor(x) + 576 mod 4096 and
//                     576 mod 256 = 64, so X = floor(x) & 255 as in ImprovedNoise.java)
//             (2 + 4 + 8 = 14 lookups, shared between corners as in the RTL)
//   corner    R_k = value16[m + k] >>> (15 - VF) (k = 0..3), d_a = U_a - b_a 2^LF
//             value_gradient: v = R_0 2^(LF-1) + R_1 d_x + R_2 d_y + R_3 d_z   exact, VF+LF bits
//             value:          v = R_0 2^(LF-1)
//             node = (floor(v to NF), floor(R_1 to NF - F), floor(R_2 to NF - F),
//                     floor(R_3 to NF - F)), the derivatives then held at NF bits (multiples
//                     of 2^F; gradient zero for value corners)
//             grad12 (Perlin's grad(m, d)): h = m & 15, axis a = h < 8 ? x : y,
//                     axis b = h < 4 ? y : (h == 12 || h == 14) ? x : z (never a);
//                     v = (h & 1 ? -d_a : d_a) + (h & 2 ? -d_b : d_b)   exact, LF bits;
//                     node = (floor(v to NF), +-2^NF on axes a and b, 0 on the third)
//   lerp on axis k between nodes a (b_k = 0) and b (b_k = 1), s = s_k, ds = ds_k:
//             L(x, y) = x + floor((y - x) s / 2^LF)                 (value)
//             L_F(x, y) = x + 2^F floor(((y - x) / 2^F) s / 2^LF)   (derivatives; x, y and
//                     so y - x are multiples of 2^F: L_0 = L)
//             v' = L(a.v, b.v); g'_j = L_F(a.g_j, b.g_j) for j != k;
//             g'_k = 2^F floor(floor((b.v - a.v) / 2^F) ds / 2^LF) + L_F(a.g_k, b.g_k)
//             (the own-axis product on the value difference floored to 2^F: a narrower
//             product; every derivative stays a multiple of 2^F)
//             four x lerps (corners 2j, 2j+1), two y lerps, one z lerp.
//   out       n = sat(floor(v to OF), Q4.OF), grad_k = sat(floor(g_k to OF), Q6.OF).
// Ranges (proved in rtl/noise/pst_noise.sv): |v| <= 3.5 (Q3.NF), |g| < 10.1 (Q5.NF) at every node,
// so both saturations are no-ops; checked here with exceptions (a design error otherwise).
#include "noise_fx.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "contract.h"
#include "fixed.h"
#include "noise.h"
#include "perlin2002.h"

namespace pst {

using fx::floorShift;
using fx::i128;

namespace {

constexpr int kLatticeMask = (1 << contract::kLatticeBits) - 1;  // Rayshade hashes & 0xfff
static_assert(contract::kLatticeOffset == 1000000 % (1 << contract::kLatticeBits),
              "the contract's lattice offset is Rayshade's 1e6 offset mod 4096");

void checkFits(i128 v, int bits, const char* what) {
    if (v < fx::minSigned(bits) || v > fx::maxSigned(bits))
        throw std::logic_error(std::string("noiseFx: ") + what + " out of its " + std::to_string(bits) +
                               "-bit range");
}

// One lerp node: (v, dv/dx, dv/dy, dv/dz) at NF fraction bits.
struct Node {
    int64_t v[4];
};

}  // namespace

void octaveTransformFx(const Profile& prof, const int64_t s[3], const int64_t M[9], const int64_t o[3],
                       int lat[3], int64_t frac[3]) {
    const int accFrac = prof.matrix.fracBits + prof.coord.fracBits;
    const int LF = prof.noiseLatticeFrac;
    if (accFrac < LF || accFrac < prof.offset.fracBits)
        throw std::invalid_argument("octaveTransformFx: MatrixFrac + CoordFrac must be >= NoiseLatticeFrac and "
                                    ">= OffsetFrac");
    // The hardware sees only the bits of each format.
    int64_t sw[3], ow[3], Mw[9];
    for (int k = 0; k < 3; ++k) {
        sw[k] = fx::wrapSigned(s[k], prof.coord.width());
        ow[k] = fx::wrapSigned(o[k], prof.offset.width());
    }
    for (int k = 0; k < 9; ++k) Mw[k] = fx::wrapSigned(M[k], prof.matrix.width());
    for (int r = 0; r < 3; ++r) {
        i128 acc = floorShift(i128(ow[r]), -(accFrac - prof.offset.fracBits));  // exact left shift
        for (int j = 0; j < 3; ++j) acc += i128(Mw[3 * r + j]) * sw[j];
        const i128 p = floorShift(acc, accFrac - LF);
        frac[r] = int64_t(p & ((i128(1) << LF) - 1));
        lat[r] = int((floorShift(p, LF) + contract::kLatticeOffset) & kLatticeMask);
    }
}

int64_t noiseValueRom(const Profile& prof, int i) {
    const double r = NoiseTables::get().value.at(size_t(i));
    const int64_t v16 = std::lround(r * 32768.0);  // exact (checked by pst_roms and the tests)
    return int64_t(floorShift(v16, 15 - prof.noiseValueFrac));
}

void noiseFx(const Profile& prof, const int lat[3], const int64_t frac[3], int64_t* n, int64_t grad[3]) {
    noiseFx(prof, lat, frac, n, grad, nullptr);
}

void noiseFx(const Profile& prof, const int lat[3], const int64_t frac[3], int64_t* n, int64_t grad[3],
             NoiseFxTrace* trace) {
    const int LF = prof.noiseLatticeFrac;
    const int VF = prof.noiseValueFrac;
    const int OF = prof.noiseOutFrac;
    const int NF = noiseNodeFrac(prof);
    const int F = noiseGradFloor(prof);
    const bool scurve = prof.noiseInterp == NoiseInterp::Scurve;
    const bool quintic = prof.noiseInterp == NoiseInterp::Quintic;
    const bool valueGradient = prof.noiseCorner == NoiseCorner::ValueGradient;
    const bool grad12 = prof.noiseCorner == NoiseCorner::Grad12;
    const int valueW = 3 + NF;  // Q3.NF node values
    const int gradW = 5 + NF;   // Q5.NF node derivatives

    int L[3];
    int64_t U[3], s[3], ds[3];
    for (int k = 0; k < 3; ++k) {
        L[k] = lat[k] & kLatticeMask;
        U[k] = frac[k] & ((int64_t(1) << LF) - 1);
        // Weights.
        if (scurve) {
            const int64_t u2 = int64_t(floorShift(i128(U[k]) * U[k], LF));
            s[k] = int64_t(floorShift(i128(u2) * ((int64_t(3) << LF) - 2 * U[k]), LF));
            ds[k] = 6 * (U[k] - u2);
        } else if (quintic) {
            const int64_t u2 = int64_t(floorShift(i128(U[k]) * U[k], LF));
            const int64_t t3 = int64_t(floorShift(i128(u2) * U[k], LF));
            const int64_t w = 6 * u2 - 15 * U[k] + (int64_t(10) << LF);
            s[k] = int64_t(floorShift(i128(t3) * w, LF));
            const int64_t a = U[k] - u2;
            ds[k] = int64_t(floorShift(30 * (i128(a) * a), LF));
        } else {
            s[k] = U[k];
            ds[k] = int64_t(1) << LF;
        }
    }

    // Hash: 2 + 4 + 8 lookups, corner c = bx + 2 by + 4 bz.
    const NoiseTables& tables = NoiseTables::get();
    const bool perm = prof.noiseHash == NoiseHash::Perm256;
    const bool perlin = prof.noiseHash == NoiseHash::Perlin256;
    const int idxMask = perm || perlin ? 0xff : kLatticeMask;
    const int idxBias = perlin ? -(contract::kLatticeOffset & 0xff) : 0;  // X = floor(x) & 255
    const auto& perlinP = perlin2002Permutation();
    auto T = [&](int i) {
        return perlin ? int(perlinP[size_t(i)]) : perm ? int(tables.perm[size_t(i)]) : int(tables.hash[size_t(i)]);
    };
    // The chain's combining step: XOR (Rayshade, perm256) or an 8-bit add (perlin256).
    auto chain = [&](int h, int x) { return perlin ? (h + x) & 0xff : h ^ x; };
    int X[3][2];
    for (int k = 0; k < 3; ++k) {
        X[k][0] = (L[k] + idxBias) & idxMask;
        X[k][1] = (L[k] + idxBias + 1) & idxMask;
    }
    int h1[2], h2[4], m[8];
    for (int bx = 0; bx < 2; ++bx) h1[bx] = T(X[0][bx]);
    for (int by = 0; by < 2; ++by)
        for (int bx = 0; bx < 2; ++bx) h2[bx + 2 * by] = T(chain(h1[bx], X[1][by]));
    for (int c = 0; c < 8; ++c) m[c] = T(chain(h2[c & 3], X[2][c >> 2])) & 0xff;

    // Corner nodes.
    Node corner[8];
    for (int c = 0; c < 8; ++c) {
        const int b[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
        Node& nd = corner[c];
        if (grad12) {
            const int h = m[c] & 15;
            const int a = h < 8 ? 0 : 1, bb = h < 4 ? 1 : (h == 12 || h == 14) ? 0 : 2;
            int64_t d[3];
            for (int k = 0; k < 3; ++k) d[k] = U[k] - (int64_t(b[k]) << LF);
            const int64_t v = ((h & 1) ? -d[a] : d[a]) + ((h & 2) ? -d[bb] : d[bb]);
            nd.v[0] = int64_t(floorShift(i128(v), LF - NF));
            for (int k = 0; k < 3; ++k) nd.v[k + 1] = 0;
            // (+-2^NF: multiples of 2^F, F <= NF - 1)
            nd.v[a + 1] = (h & 1) ? -(int64_t(1) << NF) : (int64_t(1) << NF);
            nd.v[bb + 1] = (h & 2) ? -(int64_t(1) << NF) : (int64_t(1) << NF);
            checkFits(nd.v[0], valueW, "corner value");
            continue;
        }
        int64_t R[4];
        for (int k = 0; k < 4; ++k) R[k] = noiseValueRom(prof, m[c] + k);
        i128 v = floorShift(i128(R[0]), -(LF - 1));  // 0.5 R_0 at VF + LF fraction bits
        if (valueGradient)
            for (int k = 0; k < 3; ++k) v += i128(R[k + 1]) * (U[k] - (int64_t(b[k]) << LF));
        nd.v[0] = int64_t(floorShift(v, VF + LF - NF));
        for (int k = 0; k < 3; ++k)
            nd.v[k + 1] = valueGradient ? int64_t(floorShift(floorShift(i128(R[k + 1]), VF - (NF - F)), -F)) : 0;
        checkFits(nd.v[0], valueW, "corner value");
    }

    // L_f(x, y) = x + 2^f floor(((y - x) / 2^f) s / 2^LF); x, y multiples of 2^f (f = 0: the value).
    auto lerp1 = [&](int64_t a, int64_t b, int64_t w, int f) {
        if ((a | b) & ((int64_t(1) << f) - 1)) throw std::logic_error("noiseFx: derivative below its floor");
        return a + int64_t(floorShift(floorShift(i128(b - a) * w, LF + f), -f));  // (x 2^f)
    };
    auto lerp = [&](const Node& a, const Node& b, int k) {
        Node out;
        out.v[0] = lerp1(a.v[0], b.v[0], s[k], 0);
        for (int j = 0; j < 3; ++j) {
            out.v[j + 1] = lerp1(a.v[j + 1], b.v[j + 1], s[k], F);
            if (j == k)
                out.v[j + 1] += int64_t(floorShift(floorShift(floorShift(i128(b.v[0] - a.v[0]), F) * ds[k], LF), -F));
        }
        checkFits(out.v[0], valueW, "lerp value");
        for (int j = 1; j < 4; ++j) checkFits(out.v[j], gradW, "lerp derivative");
        return out;
    };
    Node node[7];
    for (int j = 0; j < 4; ++j) node[j] = lerp(corner[2 * j], corner[2 * j + 1], 0);
    for (int j = 0; j < 2; ++j) node[4 + j] = lerp(node[2 * j], node[2 * j + 1], 1);
    node[6] = lerp(node[4], node[5], 2);

    const int G = NF - OF;
    *n = fx::satSigned(floorShift(node[6].v[0], G), 4 + OF);
    for (int k = 0; k < 3; ++k) grad[k] = fx::satSigned(floorShift(node[6].v[k + 1], G), 6 + OF);

    if (trace) {
        for (int c = 0; c < 8; ++c) {
            trace->m[c] = m[c];
            for (int j = 0; j < 4; ++j) trace->corner[c][j] = corner[c].v[j];
        }
        for (int k = 0; k < 3; ++k) {
            trace->s[k] = s[k];
            trace->ds[k] = ds[k];
        }
        for (int i = 0; i < 7; ++i)
            for (int j = 0; j < 4; ++j) trace->node[i][j] = node[i].v[j];
    }
}

// Worst-case error of the fixed-point unit against the double noise at the same point
// (p_q = L + U / 2^LF). Derivation (q = 2^-LF, e = 2^-NF, o = 2^-OF):
//  - weights: scurve s_fx in (s - 4q, s] (u2 floor times (3 - 2u) <= 3, then a floor);
//    ds_fx in [ds, ds + 6q) (6 (U - floor(U^2 / 2^LF))); ds_fx <= 1.5 + 6q. linear: exact.
//  - R: value16 >>> (15 - VF) is exact at VF = 15, else in (R - 2^-VF, R] (call it ER).
//  - corner: |v| error <= 3.5 ER (value_gradient: 0.5 |e_0| + |d| (|e_1|+|e_2|+|e_3|), |d| <= 1;
//    value: 0.5 ER) + e (floor to NF). Corner gradient: ER (+ e if VF > NF).
//  - derivatives floored to 2^F (noise.grad_frac): e becomes eg = 2^F e in every derivative
//    floor, and the own-axis product on floor((b - a) / 2^F) adds eg ds_fx,max.
//  - a lerp x + floor((y - x) s_fx) against x + (y - x) s errs by at most
//    max(err x, err y) + |y - x| |ds_w| + e (s_fx in [0, 1): a convex combination).
//  - value differences |b - a| < D = 6 (value_gradient: 0.5 |Rb - Ra| < 1, |R u| + |R (u-1)|
//    <= 1, 2 |d| < 2 twice) or 1 (value); a y or z lerp's difference is a convex combination of
//    such corner differences, so D holds at every level.
//  - own-axis term floor((b - a)_fx ds_fx): error <= 2 Ev ds_fx,max + D |ds error| + e.
//  - derivatives: the own-axis derivative before its own lerp is a lerp of R's: differences
//    < 2 (value_gradient) or 0. After its own lerp |g| <= Gmax = ds_max D + 1 (10 scurve, 7
//    linear; value corners: 1.5 or 1), so later lerps see differences < 2 Gmax.
//  - the final floors to OF add o each.
NoiseFxErrorBound noiseFxErrorBound(const Profile& prof) {
    const int LF = prof.noiseLatticeFrac, VF = prof.noiseValueFrac, OF = prof.noiseOutFrac;
    const int NF = noiseNodeFrac(prof);
    const bool scurve = prof.noiseInterp == NoiseInterp::Scurve;
    const bool quintic = prof.noiseInterp == NoiseInterp::Quintic;
    const bool vg = prof.noiseCorner == NoiseCorner::ValueGradient;
    const bool g12 = prof.noiseCorner == NoiseCorner::Grad12;
    const double q = std::ldexp(1.0, -LF), e = std::ldexp(1.0, -NF), o = std::ldexp(1.0, -OF);
    // The derivative lanes' floor (noise.grad_frac): eg = 2^F e per derivative floor, and the
    // own-axis product's value difference floored to 2^F (F > 0) errs by < eg ds_fx more.
    const int F = noiseGradFloor(prof);
    const double eg = std::ldexp(1.0, F - NF);
    // Weights. quintic: t3 in (t^3 - 2q, t^3], w in (w - 6q, w], so t^3 w - t3 w_fx <
    // 6q t^3 + w (t + 1) q <= 10q (max at t = 0), plus the floor: s_fx in (s - 11q, s].
    // ds: a_fx in [a, a + q), a <= 1/4, 30 (a_fx^2 - a^2) < 30 q (0.5 + q), then the floor:
    // ds_fx in (ds - q, ds + 15q + 30q^2); max ds = 30/16 = 1.875.
    const double dS = scurve ? 4 * q : quintic ? 11 * q : 0.0;                  // |s_fx - s|
    const double dDs = scurve ? 6 * q : quintic ? 15 * q + 30 * q * q : 0.0;    // |ds_fx - ds|
    const double dsMaxTrue = scurve ? 1.5 : quintic ? 1.875 : 1.0;
    const double dsMaxFx = dsMaxTrue + dDs;
    // Corner value differences: 6 (value_gradient), 1 (value), 4 (grad12: |+-d_a +-d_b| <= 2).
    const double D = vg ? 6.0 : g12 ? 4.0 : 1.0;
    // Corner gradient differences: R's (< 2) or grad12's components in {-1, 0, 1}.
    const double DgOwn = vg || g12 ? 2.0 : 0.0;
    const double gMax = dsMaxTrue * D + DgOwn / 2;
    const double DgOther = 2 * gMax;
    const double ER = g12 || VF >= 15 ? 0.0 : std::ldexp(1.0, -VF);
    // grad12 corners are exact at LF bits (only the floor to NF), their gradients exact.
    const double Ec = g12 ? (LF > NF ? e : 0.0) : (vg ? 3.5 : 0.5) * ER + (VF + LF > NF ? e : 0.0);
    const double Ecg = vg ? ER + (VF > NF - F ? eg : 0.0) : 0.0;
    auto Ev = [&](int levels) { return Ec + levels * (D * dS + e); };

    NoiseFxErrorBound b;
    b.value = Ev(3) + o;
    for (int k = 1; k <= 3; ++k) {
        const double g = Ecg + (k - 1) * (DgOwn * dS + eg)           // lerps before its own
                         + 2 * Ev(k - 1) * dsMaxFx + D * dDs + eg    // (b - a) ds
                         + (F > 0 ? eg * dsMaxFx : 0.0)              //   on floor((b - a) / 2^F)
                         + DgOwn * dS + eg                           // its own lerp
                         + (3 - k) * (DgOther * dS + eg)             // lerps after
                         + o;
        b.grad = std::max(b.grad, g);
    }
    b.gradMax = gMax;
    // Inside a cell: |d2n/dp_k^2| <= max|s''| D + 2 ds_max DgOwn (s'' = 6 - 12u for scurve,
    // 60u - 180u^2 + 120u^3 for quintic, |.| <= 5.78 at u = (3 - sqrt 3) / 6; 0 linear);
    // |d2n/dp_k dp_j| <= ds_max^2 2D + 2 ds_max DgOwn.
    const double s2 = scurve ? 6.0 : quintic ? 5.78 : 0.0;
    const double hkk = s2 * D + 2 * dsMaxTrue * DgOwn;
    const double hkj = dsMaxTrue * dsMaxTrue * 2 * D + 2 * dsMaxTrue * DgOwn;
    b.hessianRow = hkk + 2 * hkj;
    return b;
}

}  // namespace pst

// Golden model of units 3-5 (docs/HARDWARE.md); mirrors rtl/octave/pst_quadric.sv,
// rtl/octave/pst_octave_term.sv, rtl/width/pst_filter_width.sv and rtl/common/pst_isqrt.sv step for step.
//
// i128 budget. Widths below are signed bit counts of the exact intermediates, with the
// largest formats profile.cpp accepts (Coord, Jacobian <= 40 bits; Quadric, Amplitude,
// GradMatrix <= 32; Grad <= 48; NoiseOutFrac <= 24; Log2Clut + 2 + WidthFrac <= 38):
//   quadric  v: QW + CW + 1 <= 73;   q: QW + 2 CW + 3 <= 115            (< 127)
//   term     a n: AW + NW <= 60;     GM . g: GMW + NGW + 2 <= 64
//   width    gx: GW + JW + 2 <= 90;  ax^2 + ay^2: 2 WW + 1 <= 77 (unsigned)
// A left shift (a format with more fraction bits than the exact value) is handled by
// shiftSatSigned without overflowing: a value that would pass 126 bits saturates first.
#include "arith_fx.h"

#include <algorithm>

#include "contract.h"

namespace pst {
namespace {

using fx::i128;

// Number of bits of |v| (0 for 0).
int magnitudeBits(i128 v) {
    unsigned __int128 m = v < 0 ? (unsigned __int128)(-(v + 1)) + 1 : (unsigned __int128)v;
    int b = 0;
    while (m) {
        ++b;
        m >>= 1;
    }
    return b;
}

}  // namespace

int quadricSerialSteps(const Profile& p) {
    return contract::quadric_serial_steps(p.quadric.width(), p.coord.width(), contract::term_regs(p.octaveRegs));
}

int filterWidthSerialSteps(const Profile& p) {
    return contract::width_serial_steps(int(p.filterNorm), p.log2Clut, p.widthFrac);
}

int64_t shiftSatSigned(i128 v, int sh, int bits) {
    if (sh >= 0) return fx::satSigned(fx::floorShift(v, sh), bits);
    // Left shift: exact. Anything at or above 2^(bits - 1) after the shift saturates anyway,
    // so the product is formed only when it stays under 2^126.
    if (magnitudeBits(v) - sh > 126) return v < 0 ? fx::minSigned(bits) : fx::maxSigned(bits);
    return fx::satSigned(fx::floorShift(v, sh), bits);
}

void quadricFx(const Profile& p, const int64_t s[3], const int64_t coef[10], int64_t* q, int64_t gradq[3]) {
    const int cf = p.coord.fracBits, qf = p.quadric.fracBits;
    // Q of eq. 4, row-major from A..J = coef[0..9]:
    //   [A B C D; B E F G; C F H I; D G I J]
    const int64_t A = coef[0], B = coef[1], C = coef[2], D = coef[3], E = coef[4];
    const int64_t F = coef[5], G = coef[6], H = coef[7], I = coef[8], J = coef[9];
    const int64_t row[3][4] = {{A, B, C, D}, {B, E, F, G}, {C, F, H, I}};
    const int64_t lin[3] = {D, G, I};

    // Step 1: v = (Q [s 1])_xyz at qf + cf fraction bits (QW + CW + 1 bits).
    i128 v[3];
    for (int r = 0; r < 3; ++r) {
        v[r] = i128(row[r][0]) * s[0] + i128(row[r][1]) * s[1] + i128(row[r][2]) * s[2] +
               fx::floorShift(row[r][3], -cf);
    }
    // Step 2: q = s . v + ((D s + G t + I r) << cf) + (J << 2 cf) at qf + 2 cf (QW + 2 CW + 3 bits).
    i128 sv = 0, ls = 0;
    for (int k = 0; k < 3; ++k) {
        sv += i128(s[k]) * v[k];
        ls += i128(lin[k]) * s[k];
    }
    const i128 qx = sv + fx::floorShift(ls, -cf) + fx::floorShift(J, -2 * cf);
    // Step 3: bring q to F, grad q = 2 v to Grad (floor, then saturate).
    *q = shiftSatSigned(qx, qf + 2 * cf - p.f.fracBits, p.f.width());
    for (int r = 0; r < 3; ++r)
        gradq[r] = shiftSatSigned(2 * v[r], qf + cf - p.grad.fracBits, p.grad.width());
}

void octaveTermFx(const Profile& p, int64_t n, const int64_t g[3], int64_t a, const int64_t gm[9],
                  int64_t* fterm, int64_t gterm[3]) {
    const int nf = p.noiseOutFrac;
    // a n at AmplitudeFrac + NoiseOutFrac (AW + NW bits).
    *fterm = shiftSatSigned(i128(a) * n, p.amplitude.fracBits + nf - p.f.fracBits, p.f.width());
    // (GM g)_r at GradMatrixFrac + NoiseOutFrac (GMW + NGW + 2 bits).
    for (int r = 0; r < 3; ++r) {
        const i128 acc = i128(gm[3 * r + 0]) * g[0] + i128(gm[3 * r + 1]) * g[1] + i128(gm[3 * r + 2]) * g[2];
        gterm[r] = shiftSatSigned(acc, p.gradMatrix.fracBits + nf - p.grad.fracBits, p.grad.width());
    }
}

int64_t fadeLgFx(const Profile& p, const int64_t e[3]) {
    namespace c = contract;
    uint64_t v[3], mx = 0, sum = 0;
    for (int k = 0; k < 3; ++k) {
        v[k] = uint64_t(e[k] < 0 ? -e[k] : e[k]);  // <= 2^(JW-1)
        mx = std::max(mx, v[k]);
        sum += v[k];
    }
    const uint64_t r = sum - mx, len = std::max<uint64_t>(1, mx + (r >> 2) + (r >> 3));  // < 2^JW
    return mitchellLgFx(p, len);
}

int64_t mitchellLgFx(const Profile& p, uint64_t len) {
    namespace c = contract;
    len = std::max<uint64_t>(1, len);
    int lead = 63;
    while (!((len >> lead) & 1u)) --lead;
    // The FadeLgFrac bits below the leading one (zeros shifted in below bit 0).
    const uint64_t below = len & ((uint64_t(1) << lead) - 1);
    const int64_t mant = lead >= c::kFadeLgFrac ? int64_t(below >> (lead - c::kFadeLgFrac))
                                                : int64_t(below << (c::kFadeLgFrac - lead));
    return int64_t(lead - p.jacobian.fracBits) * (int64_t(1) << c::kFadeLgFrac) + mant;
}

int64_t octaveFadeFx(int64_t lgx, int64_t lgy, int64_t lgm, const int64_t table[contract::kFadeEntries]) {
    namespace c = contract;
    auto index = [&](int64_t lg) {
        // floor((lg nu + FadeLgLo) * 4) with lg nu at FadeLgFrac fraction bits: an arithmetic shift.
        const int64_t t = (lg + lgm + (int64_t(c::kFadeLgLo) << c::kFadeLgFrac)) >> (c::kFadeLgFrac - 2);
        return int(std::clamp<int64_t>(t, 0, c::kFadeEntries - 1));
    };
    const int64_t one = int64_t(1) << c::kFadeFrac;
    return std::min((table[index(lgx)] * table[index(lgy)]) >> c::kFadeFrac, one);
}

int64_t fadeScaleFx(int64_t v, int64_t alpha) { return int64_t((i128(v) * alpha) >> contract::kFadeFrac); }

int64_t fadeToMeanFx(const Profile& p, int64_t fterm, int64_t fm, int64_t alpha) {
    // fm + alpha (fterm - fm): the fade toward the term's mean, not toward 0 (a basis whose mean is
    // not 0, worley's, would otherwise lose its mean with the fade). The difference needs FW + 1
    // bits; the result, a convex combination floored, at most 1 LSB outside F: saturated.
    return fx::satSigned(i128(fadeScaleFx(fterm - fm, alpha)) + fm, p.f.width());
}

int64_t accumulateF(const Profile& p, int64_t q, const std::vector<int64_t>& terms) {
    i128 sum = q;
    for (int64_t t : terms) sum += t;
    return fx::satSigned(sum, p.f.width());
}

int64_t accumulateGrad(const Profile& p, int64_t gradq, const std::vector<int64_t>& terms) {
    i128 sum = gradq;
    for (int64_t t : terms) sum += t;
    return fx::satSigned(sum, p.grad.width());
}

uint64_t isqrtFx(unsigned __int128 x) {
    // Restoring digit-by-digit square root: 63 steps, two input bits each, from the top.
    // Invariant after a step: root^2 <= x's leading bits and rem = those bits - root^2.
    unsigned __int128 rem = 0, root = 0;
    for (int i = 62; i >= 0; --i) {
        rem = (rem << 2) | ((x >> (2 * i)) & 3u);
        const unsigned __int128 trial = (root << 2) | 1u;
        if (rem >= trial) {
            rem -= trial;
            root = (root << 1) | 1u;
        } else {
            root <<= 1;
        }
    }
    return uint64_t(root);
}

int64_t filterWidthFx(const Profile& p, const int64_t grad[3], const int64_t j[6]) {
    const int ww = p.widthBits();
    const int64_t wmax = fx::maxUnsigned(ww);
    // Step 1: gx = grad . dsdx, gy = grad . dsdy at GradFrac + JacobianFrac (GW + JW + 2 bits).
    i128 gx = 0, gy = 0;
    for (int k = 0; k < 3; ++k) {
        gx += i128(grad[k]) * j[k];
        gy += i128(grad[k]) * j[3 + k];
    }
    // Step 2: to entries at WidthFrac: floor(g * 2^Log2Clut / 2^(GradFrac + JacobianFrac - WidthFrac)).
    const int sh = p.grad.fracBits + p.jacobian.fracBits - p.log2Clut - p.widthFrac;
    // Step 3: |Wx|, |Wy| clamped to WMax (the exact floor is formed in the RTL at full width;
    // shiftSatSigned's saturation at ww + 2 bits is far above WMax and only keeps the value
    // in range, it does not change min(|Wx|, WMax)).
    const int64_t wx = shiftSatSigned(gx, sh, ww + 2), wy = shiftSatSigned(gy, sh, ww + 2);
    const int64_t ax = std::min<int64_t>(wx < 0 ? -wx : wx, wmax);
    const int64_t ay = std::min<int64_t>(wy < 0 ? -wy : wy, wmax);
    // Step 4: the norm (at most ww + 1 bits), then saturate to ww bits.
    int64_t w = 0;
    switch (p.filterNorm) {
    case GradNorm::Euclid:
        w = int64_t(isqrtFx((unsigned __int128)ax * ax + (unsigned __int128)ay * ay));
        break;
    case GradNorm::MaxHalfMin:
        w = std::max(ax, ay) + (std::min(ax, ay) >> 1);
        break;
    case GradNorm::L1:
        w = ax + ay;
        break;
    }
    return std::min(w, wmax);
}

int64_t widthCapFx(const Profile& p, int64_t w, int64_t wcap) {
    return std::min(w, int64_t(fx::wrapUnsigned(uint64_t(wcap), p.widthBits())));
}

}  // namespace pst

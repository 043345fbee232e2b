// Golden model of the subband unit (rtl/noise/pst_subband.sv). See subband_fx.h.
//
// Notation: LF = NoiseLatticeFrac, OF = NoiseOutFrac, UB = kSubbandUnitBits (ROM pixels per
// noise unit 2^UB), WF = LF - UB (the bilinear weights' fraction bits), TL = SubbandTileLog2,
// VF = SubbandValueFrac. (a0, a1) the profile's plane.
//
// 1. Tile pixel and weights per in-plane axis a: x_a = ((lat_a mod 2^SubbandPeriodLog2) << UB) |
//    (frac_a >> WF) (TL bits; Rayshade's lattice offset 576 is a multiple of the period 16),
//    w_a = frac_a mod 2^WF.
// 2. Corner c = cx + 2 cy (one per noise step on the reduced schedule): ROM address
//    ((x_a1 + cy) mod 2^TL) 2^TL + (x_a0 + cx) mod 2^TL, word v_c (signed, VF fraction bits);
//    weights u_0 = 2^WF - w, u_1 = w per axis.
//    With K = 4, 8 oriented tiles the corner's value is the weighted sum of its K words, v_c =
//    sum_i lambda_i v_c,i (eq. 7, lambda_i FadeFrac bits: VF' = VF + FadeFrac); K = 0: VF' = VF.
// 3. Exact sums over the corners (the bilinear interpolant, and its derivative along each axis,
//    per ROM pixel):
//      V  = sum v_c u_cx(w_a0) u_cy(w_a1)          VF' + 2 WF fraction bits
//      Gx = sum v_c (cx ? 1 : -1) u_cy(w_a1)       VF' + WF
//      Gy = sum v_c (cy ? 1 : -1) u_cx(w_a0)       VF' + WF
// 4. n = sat(floor(V / 2^(VF' + 2 WF - OF)), Q4.OF); per noise unit the derivative is 2^UB times
//    the per-pixel one: grad_a0 = sat(floor(Gx / 2^(VF' + WF - UB - OF)), Q6.OF), grad_a1 from
//    Gy, the third axis 0.
// The weights (K = 4, 8; eq. 4 with the paper's heuristic lambda_ij = the Gaussian at the
// subband's centre w_i = (pi/16) c_i per tile pixel, 16 tile pixels per noise unit): lambda_i =
// exp(-sigma^2/2 |J^T w_i|^2) = h(c_i . J_x) h(c_i . J_y), h(nu) = exp(-sigma^2 pi^2 nu^2 / 2), J in
// noise units per screen pixel. The hardware bounds c_i . J of the octave by ||M|| (c_i . J_s on
// the plane), exact for M a multiple of the identity, and reads h from the fade table at the
// quarter octave of lg |c_i . J_s| + lg ||M|| (subbandPixelLgFx, subbandLambdaFx), Mitchell's lg
// with its mantissa corrected (subbandLgCorrectFx).
#include "subband_fx.h"

#include <cmath>
#include <mutex>
#include <stdexcept>

#include "arith_fx.h"
#include "fixed.h"
#include "subband.h"

namespace pst {

namespace c = contract;

const std::vector<double>& subbandRomTile(int K) {
    if (K != 0 && K != 4 && K != 8) throw std::invalid_argument("subbandRomTile: orientations must be 0, 4 or 8");
    static std::mutex mu;
    static std::vector<double> tiles[3];
    std::lock_guard<std::mutex> lock(mu);
    std::vector<double>& r = tiles[K / 4];
    if (!r.empty()) return r;
    const int N = c::kSubbandRefTile, step = N / kSubbandRomSide;
    static_assert(c::kSubbandRefTile % kSubbandRomSide == 0);
    static_assert(double(c::kSubbandRefTile) / kSubbandUnitPx == double(1 << c::kSubbandPeriodLog2),
                  "the ROM's period is the reference tile's, in noise units");
    // K = 0: orientations 4; the isotropic sum of a scale does not depend on K (sum_i G_i = 1, eq. 1).
    const SubbandTiles& t = subbandTiles(K == 0 ? 4 : K, N, c::kSubbandSeed);
    const double scale = subbandCentreScale(t);
    const int T = subbandTileCount(K);
    r.assign(size_t(T) * kSubbandRomWords, 0.0);
    for (int i = 0; i < T; ++i) {
        const float* src = K == 0 ? &t.isoValue[size_t(kSubbandCentreScale) * N * N]
                                  : &t.value[size_t(kSubbandCentreScale * K + i) * N * N];
        for (int y = 0; y < kSubbandRomSide; ++y)
            for (int x = 0; x < kSubbandRomSide; ++x)
                r[size_t(i) * kSubbandRomWords + size_t(y) * kSubbandRomSide + x] =
                    scale * double(src[size_t(y * step) * N + x * step]);
    }
    return r;
}

int64_t subbandRomWord(int K, int t, int a) {
    const double v = std::ldexp(subbandRomTile(K).at(size_t(t) * kSubbandRomWords + size_t(a)), c::kSubbandValueFrac);
    return fx::satSigned(fx::i128(std::llround(v)), c::kSubbandValueBits);
}

void subbandDirection(int K, int i, int* cc, int* ss) {
    const double a = 3.141592653589793 * i / K, one = double(1 << c::kSubbandDirFrac);
    *cc = int(std::lround(one * std::cos(a)));
    *ss = int(std::lround(one * std::sin(a)));
}

int64_t subbandLgCorrectFx(int64_t lg) {
    // Mitchell's lg(1 + x) ~ x is low by up to 0.086 octave; the mantissa's FadeLgFrac bits m (x
    // truncated to m / 2^FadeLgFrac) become floor(2^FadeLgFrac lg(1 + (m + 1/2) / 2^FadeLgFrac)), the
    // lg at the centre of the mantissa's step (a 16-entry constant table in the RTL).
    static_assert(c::kFadeLgFrac == 4, "the RTL's correction table has 16 entries");
    static constexpr int64_t kCorr[16] = {0, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 14, 15};
    const int64_t mask = (int64_t(1) << c::kFadeLgFrac) - 1;
    return (lg & ~mask) | kCorr[lg & mask];
}

void subbandPixelLgFx(const Profile& prof, const int64_t j[6], int64_t lg[16]) {
    int a0, a1;
    subbandAxes(prof, &a0, &a1);
    const int K = subbandOrientations(prof);
    for (int e = 0; e < 2; ++e)
        for (int i = 0; i < K; ++i) {
            int cc, ss;
            subbandDirection(K, i, &cc, &ss);
            const int64_t p = int64_t(fx::floorShift(fx::i128(cc) * j[3 * e + a0] + fx::i128(ss) * j[3 * e + a1],
                                                     c::kSubbandDirFrac));
            lg[e * K + i] = subbandLgCorrectFx(mitchellLgFx(prof, uint64_t(p < 0 ? -p : p)));
        }
}

void subbandLambdaFx(const Profile& prof, const int64_t lg[16], int64_t lgm, const int64_t table[c::kFadeEntries],
                     int64_t lambda[8]) {
    const int K = subbandOrientations(prof);
    for (int i = 0; i < K; ++i) lambda[i] = octaveFadeFx(lg[i], lg[K + i], lgm, table);
}

void subbandAxes(const Profile& prof, int* a0, int* a1) {
    switch (prof.noiseSubband) {
    case NoiseSubband::Xy: *a0 = 0, *a1 = 1; return;
    case NoiseSubband::Xz: *a0 = 0, *a1 = 2; return;
    case NoiseSubband::Yz: *a0 = 1, *a1 = 2; return;
    case NoiseSubband::None: break;
    }
    throw std::invalid_argument("subbandFx: the profile has no subband unit (noise.subband = none)");
}

void subbandFx(const Profile& prof, const int lat[3], const int64_t frac[3], const int64_t* lambda, int64_t* n,
               int64_t grad[3], SubbandFxTrace* trace) {
    int a0, a1;
    subbandAxes(prof, &a0, &a1);
    const int K = subbandOrientations(prof), T = subbandTileCount(K);
    const int LF = prof.noiseLatticeFrac, OF = prof.noiseOutFrac, UB = kSubbandUnitBits, WF = LF - UB;
    const int VF = c::kSubbandValueFrac + (K == 0 ? 0 : c::kFadeFrac), TL = c::kSubbandTileLog2;
    const int TM = kSubbandRomSide - 1;
    if (WF < 1) throw std::invalid_argument("subbandFx: noise.lattice_frac must exceed SubbandTileLog2 - SubbandPeriodLog2");
    const int64_t one = int64_t(1) << WF, wmask = one - 1;
    const int pmask = (1 << c::kSubbandPeriodLog2) - 1;
    // Step 1: the tile pixel and the weights' fractions.
    const int x = ((lat[a0] & pmask) << UB) | int(frac[a0] >> WF);
    const int y = ((lat[a1] & pmask) << UB) | int(frac[a1] >> WF);
    const int64_t wx = frac[a0] & wmask, wy = frac[a1] & wmask;
    // Steps 2-3: the corners (K = 4, 8: the weighted sum of their words) and the exact sums.
    int64_t V = 0, Gx = 0, Gy = 0;
    for (int k = 0; k < 4; ++k) {
        const int cx = k & 1, cy = k >> 1;
        const int addr = (((y + cy) & TM) << TL) | ((x + cx) & TM);
        int64_t v = 0;
        if (K == 0) {
            v = subbandRomWord(0, 0, addr);
        } else {
            for (int i = 0; i < T; ++i)
                v += (lambda ? lambda[i] : int64_t(1) << c::kFadeFrac) * subbandRomWord(K, i, addr);
        }
        const int64_t ux = cx ? wx : one - wx, uy = cy ? wy : one - wy;
        V += v * ux * uy;
        Gx += (cx ? v : -v) * uy;
        Gy += (cy ? v : -v) * ux;
        if (trace) trace->addr[k] = addr, trace->v[k] = v;
    }
    // Step 4: floor and saturate to the unit's output formats.
    const int NW = c::kNoiseIntBits + OF, NGW = c::kNoiseGradIntBits + OF;
    *n = fx::satSigned(fx::floorShift(V, VF + 2 * WF - OF), NW);
    grad[0] = grad[1] = grad[2] = 0;
    grad[a0] = fx::satSigned(fx::floorShift(Gx, VF + WF - UB - OF), NGW);
    grad[a1] = fx::satSigned(fx::floorShift(Gy, VF + WF - UB - OF), NGW);
    if (trace) trace->wx = wx, trace->wy = wy, trace->accV = V, trace->accGx = Gx, trace->accGy = Gy;
}

double subbandRomReference(int K, const glm::dvec2& uv, const double* lambda, glm::dvec2* grad) {
    const std::vector<double>& t = subbandRomTile(K);
    const double px = double(1 << kSubbandUnitBits);
    const glm::dvec2 q = px * uv;
    const double fx0 = std::floor(q.x), fy0 = std::floor(q.y), tx = q.x - fx0, ty = q.y - fy0;
    const int64_t m = kSubbandRomSide - 1;
    const int x0 = int(int64_t(fx0) & m), y0 = int(int64_t(fy0) & m), x1 = int((x0 + 1) & m), y1 = int((y0 + 1) & m);
    auto at = [&](int xx, int yy) {
        double v = 0;
        for (int i = 0; i < subbandTileCount(K); ++i)
            v += (lambda && K != 0 ? lambda[i] : 1.0) * t[size_t(i) * kSubbandRomWords + size_t(yy) * kSubbandRomSide + xx];
        return v;
    };
    const double a = at(x0, y0), b = at(x1, y0), cc = at(x0, y1), d = at(x1, y1);
    if (grad) *grad = px * glm::dvec2((b - a) * (1 - ty) + (d - cc) * ty, (cc - a) * (1 - tx) + (d - b) * tx);
    return (a * (1 - tx) + b * tx) * (1 - ty) + (cc * (1 - tx) + d * tx) * ty;
}

SubbandFxErrorBound subbandFxErrorBound(const Profile& prof) {
    // The words are the tile rounded to VF bits: |v_c - t_c| <= 2^-(VF+1) (the tile stays inside
    // the word's range; golden_test SubbandFx.RomWords checks it). The point is exact (the
    // weights are the unit's bits), and the sums are exact, so:
    // - value: a convex combination of the words (weights >= 0, sum 1): error <= 2^-(VF+1);
    //   the floor to OF bits adds < 2^-OF.
    // - gradient: per ROM pixel (1 - t)(v_1 - v_0) + t (v_3 - v_2): error <= 2 2^-(VF+1) =
    //   2^-VF, times 2^UB per noise unit; the floor adds < 2^-OF.
    // - K = 4, 8: each corner is sum_i lambda_i v_i with lambda_i <= 1 exact: its error is at most
    //   sum_i lambda_i 2^-(VF+1) <= K 2^-(VF+1), and both bounds scale by K.
    SubbandFxErrorBound b;
    const int VF = c::kSubbandValueFrac, OF = prof.noiseOutFrac, T = subbandTileCount(subbandOrientations(prof));
    b.value = T * std::ldexp(1.0, -(VF + 1)) + std::ldexp(1.0, -OF);
    b.grad = T * std::ldexp(1.0, kSubbandUnitBits - VF) + std::ldexp(1.0, -OF);
    return b;
}

}  // namespace pst

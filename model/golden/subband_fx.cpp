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
// 3. Exact sums over the corners (the bilinear interpolant, eq. 7 with unit weights, and its
//    derivative along each axis, per ROM pixel):
//      V  = sum v_c u_cx(w_a0) u_cy(w_a1)          VF + 2 WF fraction bits
//      Gx = sum v_c (cx ? 1 : -1) u_cy(w_a1)       VF + WF
//      Gy = sum v_c (cy ? 1 : -1) u_cx(w_a0)       VF + WF
// 4. n = sat(floor(V / 2^(VF + 2 WF - OF)), Q4.OF); per noise unit the derivative is 2^UB times
//    the per-pixel one: grad_a0 = sat(floor(Gx / 2^(VF + WF - UB - OF)), Q6.OF), grad_a1 from
//    Gy, the third axis 0.
#include "subband_fx.h"

#include <cmath>
#include <mutex>
#include <stdexcept>

#include "fixed.h"
#include "subband.h"

namespace pst {

namespace c = contract;

const std::vector<double>& subbandRomTile() {
    static const std::vector<double> tile = [] {
        const int N = c::kSubbandRefTile, step = N / kSubbandRomSide;
        static_assert(c::kSubbandRefTile % kSubbandRomSide == 0);
        static_assert(double(c::kSubbandRefTile) / kSubbandUnitPx == double(1 << c::kSubbandPeriodLog2),
                      "the ROM's period is the reference tile's, in noise units");
        // Orientations 4: the isotropic sum of a scale does not depend on K (sum_i G_i = 1, eq. 1).
        const SubbandTiles& t = subbandTiles(4, N, c::kSubbandSeed);
        const double scale = subbandCentreScale(t);
        const float* iso = &t.isoValue[size_t(kSubbandCentreScale) * N * N];
        std::vector<double> r(kSubbandRomWords);
        for (int y = 0; y < kSubbandRomSide; ++y)
            for (int x = 0; x < kSubbandRomSide; ++x)
                r[size_t(y) * kSubbandRomSide + x] = scale * double(iso[size_t(y * step) * N + x * step]);
        return r;
    }();
    return tile;
}

int64_t subbandRomWord(int i) {
    const double v = std::ldexp(subbandRomTile().at(size_t(i)), c::kSubbandValueFrac);
    return fx::satSigned(fx::i128(std::llround(v)), c::kSubbandValueBits);
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

void subbandFx(const Profile& prof, const int lat[3], const int64_t frac[3], int64_t* n, int64_t grad[3],
               SubbandFxTrace* trace) {
    int a0, a1;
    subbandAxes(prof, &a0, &a1);
    const int LF = prof.noiseLatticeFrac, OF = prof.noiseOutFrac, UB = kSubbandUnitBits, WF = LF - UB;
    const int VF = c::kSubbandValueFrac, TL = c::kSubbandTileLog2, TM = kSubbandRomSide - 1;
    if (WF < 1) throw std::invalid_argument("subbandFx: noise.lattice_frac must exceed SubbandTileLog2 - SubbandPeriodLog2");
    const int64_t one = int64_t(1) << WF, wmask = one - 1;
    const int pmask = (1 << c::kSubbandPeriodLog2) - 1;
    // Step 1: the tile pixel and the weights' fractions.
    const int x = ((lat[a0] & pmask) << UB) | int(frac[a0] >> WF);
    const int y = ((lat[a1] & pmask) << UB) | int(frac[a1] >> WF);
    const int64_t wx = frac[a0] & wmask, wy = frac[a1] & wmask;
    // Steps 2-3: the corners and the exact sums.
    int64_t V = 0, Gx = 0, Gy = 0;
    for (int k = 0; k < 4; ++k) {
        const int cx = k & 1, cy = k >> 1;
        const int addr = (((y + cy) & TM) << TL) | ((x + cx) & TM);
        const int64_t v = subbandRomWord(addr);
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

double subbandRomReference(const glm::dvec2& uv, glm::dvec2* grad) {
    const std::vector<double>& t = subbandRomTile();
    const double px = double(1 << kSubbandUnitBits);
    const glm::dvec2 q = px * uv;
    const double fx0 = std::floor(q.x), fy0 = std::floor(q.y), tx = q.x - fx0, ty = q.y - fy0;
    const int64_t m = kSubbandRomSide - 1;
    const int x0 = int(int64_t(fx0) & m), y0 = int(int64_t(fy0) & m), x1 = int((x0 + 1) & m), y1 = int((y0 + 1) & m);
    auto at = [&](int xx, int yy) { return t[size_t(yy) * kSubbandRomSide + xx]; };
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
    SubbandFxErrorBound b;
    const int VF = c::kSubbandValueFrac, OF = prof.noiseOutFrac;
    b.value = std::ldexp(1.0, -(VF + 1)) + std::ldexp(1.0, -OF);
    b.grad = std::ldexp(1.0, kSubbandUnitBits - VF) + std::ldexp(1.0, -OF);
    return b;
}

}  // namespace pst

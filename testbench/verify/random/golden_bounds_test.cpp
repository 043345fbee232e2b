// Golden model against the double reference, end to end: for random textures and fragments
// inside the formats' ranges, the golden pipeline's f, grad_s f and W stay within an error bound
// derived from the profile's formats. The RTL equals the golden model bit for bit, so this is
// what keeps a precision regression in the golden model (and with it the RTL) from hiding.
//
// Inputs. The texture is drawn with register-exact values (each parameter already a number of
// its format), programmed by the driver (programTexture) and given to the reference as the
// same numbers; the fragment likewise (s, J exact in Coord, Jacobian). So input quantization is
// not part of the error, except GM = a M^T, which the driver rounds on its own (GradMatrix).
// Samples whose reference values come near a saturation point are skipped (counted).
//
// Derivation (e_X = 2^-XFrac; every product and sum inside a unit is exact, docs/HARDWARE.md):
//
//   f = sat_F(q_fx + sum_i fterm_i), no saturation for the kept samples.
//   q_fx = floor(q to FFrac) of the exact q (unit 3):           q - e_F < q_fx <= q.
//   p_i = M_i s + o_i exact; the transform floors it to LF bits: 0 <= p_i - p_q < e_LF per axis,
//     and p_q stays in p's lattice cell (cell walls are integers, on the LF grid).
//   noise: |n_fx(p_q) - n(p_q)| <= Bv, |g_fx - grad n(p_q)|_k <= Bg (noiseFxErrorBound,
//     derived in model/golden/noise_fx.cpp from LF, VF, OF and the guard bits);
//     |n(p_q) - n(p)| <= Gmax * 3 e_LF (mean value theorem inside the cell, |dn/dp_k| <= Gmax);
//     |d_k n(p_q) - d_k n(p)| <= H e_LF (H = max_k sum_j |d2n/dp_k dp_j| inside a cell).
//   fterm_i = floor(a_i n_fx to FFrac):  |fterm_i - a_i n(p_i)| <= |a_i| (Bv + 3 Gmax e_LF) + e_F.
//   => |f_gold - f_ref| <= e_F + sum_i (|a_i| (Bv + 3 Gmax e_LF) + e_F).
//
//   grad_k = sat_G(floor(2 v_k to GradFrac) + sum_i gterm_ik):     quadric part within e_G.
//   gterm_ik = floor(sum_c GM_i[k][c] g_fx_c to GradFrac), GM_i[k][c] = round(a_i M_i[c][k]):
//     sum_c GM g_fx - sum_c a M[c][k] d_c n(p) =
//        sum_c (GM - a M)[k][c] g_fx_c                |GM - aM| <= e_GM / 2, |g_fx_c| <= Gmax + Bg
//      + sum_c a M[c][k] (g_fx_c - d_c n(p_q))        <= |a M[c][k]| Bg
//      + sum_c a M[c][k] (d_c n(p_q) - d_c n(p))      <= |a M[c][k]| H e_LF
//   => |grad_k gold - ref| <= Eg_k = e_G + sum_i (sum_c (e_GM / 2 (Gmax + Bg) + |a_i M_i[c][k]| (Bg + H e_LF)) + e_G).
//
//   W (entries, LSB e_W = 2^-WidthFrac; filterWidthFx): Wx = floor(N gx to WidthFrac) with
//   gx = grad_gold . dsdx exact. Against the reference N |grad_ref . dsdx| each component is off by
//   dx = N sum_k Eg_k |dsdx_k| / e_W + 1 LSB (the grad error, then the floor), dy likewise; the
//   norm is Lipschitz (euclid: sqrt(dx^2 + dy^2); max_half_min: 1.5 max(dx, dy); l1: dx + dy),
//   then its own floor (euclid's isqrt: 1 LSB; max_half_min's floor(min / 2): 0.5; l1: none).
//   (With exact grad, dx = dy = 1 gives model/golden/arith_fx_test.cpp's 1 + sqrt 2, 2, 2.)
//
//   The reference itself is double: each bound gets 1e-12 (1 + the sum of the magnitudes of the
//   terms it adds, including Gmax |p| for the rounding of p = M s + o), far below every
//   format LSB here.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "driver.h"
#include "fixed.h"
#include "noise.h"
#include "noise_fx.h"
#include "worley_fx.h"
#include "random_regress.h"
#include "rtl_model.h"

namespace pst {
namespace {

// A register-exact value of format f: log-uniform magnitude up to 2^maxExp (sometimes 0).
double exactValue(RandomStream& r, const FixedFormat& f, double maxExp) {
    if (r.chance(0.1)) return 0.0;
    const double v = (r.chance(0.5) ? -1 : 1) * std::exp2(r.uniform(-f.fracBits - 1.0, maxExp));
    return fx::toDouble(fx::quantize(v, f.intBits, f.fracBits), f.fracBits);
}

struct Stats {
    long kept = 0, skipped = 0, wKept = 0;
    double worstF = 0, worstG = 0, worstW = 0;   // largest error / bound
    double maxErrF = 0, maxBoundF = 0;
};

void checkProfile(const Profile& p, uint64_t seed, int textures, int perTexture, Stats* st) {
    RandomStream r(seed);
    const bool worley = p.noise.basis == NoiseBasis::Worley;
    NoiseFxErrorBound bn = worley ? NoiseFxErrorBound{} : noiseFxErrorBound(p);
    const double eF = std::ldexp(1.0, -p.f.fracBits), eG = std::ldexp(1.0, -p.grad.fracBits);
    const double eGM = std::ldexp(1.0, -p.gradMatrix.fracBits), eLF = std::ldexp(1.0, -p.noiseLatticeFrac);
    const double eW = std::ldexp(1.0, -p.widthFrac), N = double(p.clutSize());
    const double fMax = std::ldexp(1.0, p.f.intBits - 1), gMaxFmt = std::ldexp(1.0, p.grad.intBits - 1);
    const double gmMax = std::ldexp(1.0, p.gradMatrix.intBits - 1);
    const double wMax = double(fx::maxUnsigned(p.widthBits()));
    const double gNoise = bn.gradMax + bn.grad;  // |g_fx| bound

    for (int t = 0; t < textures; ++t) {
        const int se = int(r.range(-2, p.coord.intBits - 2));        // |s| up to 2^se
        const double qe = std::min<double>(p.quadric.intBits - 1, p.f.intBits - 4 - 2.0 * std::max(se, 0));
        Texture tex;
        tex.name = "bounds";
        tex.noise = p.noise;
        tex.norm = p.filterNorm;
        if (worley) {
            // Register-exact coefficients C_k (k < worley_order). n = sum C_k F_k is Lipschitz
            // with constant sum |C_k| (each F_k is a distance to a point set, and p, p_q share
            // the cube and the octant, so the same set): Gmax = sum |C_k|; the unit's error at
            // p_q is worleyFxErrorBound (model/golden/worley_fx.cpp). grad F_k jumps at the cell
            // walls (and turns without bound near a point), so grad and W have no such bound:
            // they are checked for the lattice bases only (the worley unit's gradient is checked
            // at the point it sees by golden_test WorleyFx.*).
            const FixedFormat cf{contract::kWorleyCoefInt, contract::kWorleyCoefFrac};
            double sumAbs = 0;
            for (int k = 0; k < 4; ++k) {
                // sum |C_k| <= 2 keeps |n| <= 2 sqrt(12) < 8, inside Q4.OF (no saturation).
                tex.noise.coef[size_t(k)] = k < p.noiseWorleyOrder ? exactValue(r, cf, std::log2(2.0 / p.noiseWorleyOrder)) : 0.0;
                sumAbs += std::abs(tex.noise.coef[size_t(k)]);
            }
            const WorleyFxErrorBound wb = worleyFxErrorBound(p, sumAbs);
            bn.value = wb.value;
            bn.grad = wb.gradN;
            bn.gradMax = sumAbs;
        }
        double* coef[10] = {&tex.quadric.A, &tex.quadric.B, &tex.quadric.C, &tex.quadric.D, &tex.quadric.E,
                            &tex.quadric.F, &tex.quadric.G, &tex.quadric.H, &tex.quadric.I, &tex.quadric.J};
        for (double* c : coef) *c = exactValue(r, p.quadric, qe);
        const int n = int(r.range(0, p.octaves));
        bool gmSaturates = false;
        for (int i = 0; i < n; ++i) {
            Octave o;
            const double me = r.uniform(-4, std::min(p.matrix.intBits - 1, 5));
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 3; ++k) o.M[c][k] = exactValue(r, p.matrix, me);
            for (int k = 0; k < 3; ++k) o.offset[k] = exactValue(r, p.offset, p.offset.intBits - 2);
            o.amplitude = exactValue(r, p.amplitude, p.amplitude.intBits - 1);
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 3; ++k) gmSaturates = gmSaturates || std::abs(o.amplitude * o.M[c][k]) >= gmMax - eGM;
            tex.octaves.push_back(o);
        }
        tex.clut = ColorMap(std::vector<glm::dvec4>(size_t(p.clutSize()), glm::dvec4(0.5)), WrapMode::Mod);
        if (gmSaturates) {
            st->skipped += perTexture;
            continue;
        }
        GoldenPipeline golden(p);
        for (const auto& [a, d] : programTexture(p, tex).writes) golden.write(a, d);

        // The texture's parts of the bounds (GLM is column-major: o.M[k][c] is M[c][k] of the
        // derivation, the entry that multiplies d_c n in grad_k).
        double boundF = eF;
        glm::dvec3 boundG(eG);
        for (const Octave& o : tex.octaves) {
            boundF += std::abs(o.amplitude) * (bn.value + 3 * bn.gradMax * eLF) + eF;
            for (int k = 0; k < 3; ++k) {
                double b = eG;
                for (int c = 0; c < 3; ++c)
                    b += eGM / 2 * gNoise + std::abs(o.amplitude * o.M[k][c]) * (bn.grad + bn.hessianRow * eLF);
                boundG[k] += b;
            }
        }

        const double je = r.uniform(-p.jacobian.fracBits / 2.0, p.jacobian.intBits - 2);
        for (int i = 0; i < perTexture; ++i) {
            glm::dvec3 s, dx, dy;
            for (int k = 0; k < 3; ++k) {
                s[k] = exactValue(r, p.coord, se);
                dx[k] = exactValue(r, p.jacobian, je);
                dy[k] = exactValue(r, p.jacobian, je);
            }
            // The reference, and the magnitudes of its terms (for the double's own rounding and
            // to skip samples near a saturation point).
            glm::dvec3 gRef;
            const double fRef = evalF(tex, s, &gRef);
            const Quadric& q = tex.quadric;
            const glm::dvec3 a = glm::abs(s);
            const double qMag = std::abs(q.A) * a.x * a.x + 2 * std::abs(q.B) * a.x * a.y + 2 * std::abs(q.C) * a.x * a.z +
                                2 * std::abs(q.D) * a.x + std::abs(q.E) * a.y * a.y + 2 * std::abs(q.F) * a.y * a.z +
                                2 * std::abs(q.G) * a.y + std::abs(q.H) * a.z * a.z + 2 * std::abs(q.I) * a.z + std::abs(q.J);
            const glm::dvec3 gq = q.gradient(s);
            double fMag = qMag, gMag = 2 * (std::abs(q.A) + std::abs(q.B) + std::abs(q.C) + std::abs(q.E) + std::abs(q.F) +
                                            std::abs(q.H)) * (a.x + a.y + a.z) + 2 * (std::abs(q.D) + std::abs(q.G) + std::abs(q.I));
            // (fMag, gMag: sums of the magnitudes the double adds up, for its own rounding)
            bool nearSat = std::abs(q.value(s)) > 0.9 * fMax || std::abs(fRef) > 0.9 * fMax;
            for (int k = 0; k < 3; ++k)
                nearSat = nearSat || std::abs(gq[k]) > 0.9 * gMaxFmt || std::abs(gRef[k]) > 0.9 * gMaxFmt;
            for (const Octave& o : tex.octaves) {
                // The double's p = M s + o is off by ~2^-52 |p|; n moves by Gmax that much per axis.
                double pMag = 0;
                for (int k = 0; k < 3; ++k) {
                    double m = std::abs(o.offset[k]);
                    for (int c = 0; c < 3; ++c) m += std::abs(o.M[c][k]) * a[c];
                    pMag = std::max(pMag, m);
                }
                fMag += std::abs(o.amplitude) * ((worley ? 7.0 : 3.5) + 3 * bn.gradMax * pMag);
                for (int k = 0; k < 3; ++k) {
                    double gt = 0;
                    for (int c = 0; c < 3; ++c) gt += std::abs(o.amplitude * o.M[k][c]) * gNoise;
                    gMag += gt * (1 + bn.hessianRow * pMag);
                    nearSat = nearSat || gt > 0.9 * gMaxFmt;
                }
            }
            if (nearSat) {
                ++st->skipped;
                continue;
            }
            ++st->kept;
            FragmentFx in = quantizeFragment(p, 0, s, dx, dy);
            const PixelFx px = golden.eval(in);

            const double bF = boundF + 1e-12 * (1 + fMag);
            const double errF = std::abs(fx::toDouble(px.f, p.f.fracBits) - fRef);
            ASSERT_LE(errF, bF) << p.name << " texture " << t << " sample " << i << " f gold "
                                << fx::toDouble(px.f, p.f.fracBits) << " ref " << fRef;
            st->worstF = std::max(st->worstF, errF / bF);
            if (errF > st->maxErrF) {
                st->maxErrF = errF;
                st->maxBoundF = bF;
            }
            if (worley) continue;  // grad, W: see above
            glm::dvec3 bG;
            for (int k = 0; k < 3; ++k) {
                bG[k] = boundG[k] + 1e-12 * (1 + gMag);
                const double errG = std::abs(fx::toDouble(px.grad[k], p.grad.fracBits) - gRef[k]);
                if (errG > bG[k] && std::getenv("PST_BOUNDS_DEBUG")) {
                    UnitTrace tr;
                    golden.eval(in, &tr);
                    std::printf("k %d gradq %.9g ref %.9g\n", k, fx::toDouble(tr.gradq[k], p.grad.fracBits), tex.quadric.gradient(s)[k]);
                    for (int i = 0; i < tr.octaves; ++i) {
                        const Octave& o = tex.octaves[size_t(i)];
                        glm::dvec3 gn;
                        const double nn = noise(o.M * s + o.offset, tex.noise, &gn);
                        const glm::dvec3 gt = o.amplitude * (glm::transpose(o.M) * gn);
                        std::printf(" oct %d a %g gterm %.9g ref %.9g  n %.9g ref %.9g g (%.6g %.6g %.6g) ref (%.6g %.6g %.6g) p (%.9g %.9g %.9g)\n", i, o.amplitude,
                                    fx::toDouble(tr.gterm[i][k], p.grad.fracBits), gt[k], fx::toDouble(tr.n[i], p.noiseOutFrac), nn,
                                    fx::toDouble(tr.g[i][0], p.noiseOutFrac), fx::toDouble(tr.g[i][1], p.noiseOutFrac), fx::toDouble(tr.g[i][2], p.noiseOutFrac), gn.x, gn.y, gn.z,
                                    (o.M * s + o.offset).x, (o.M * s + o.offset).y, (o.M * s + o.offset).z);
                    }
                }
                ASSERT_LE(errG, bG[k]) << p.name << " texture " << t << " sample " << i << " grad " << k;
                st->worstG = std::max(st->worstG, errG / bG[k]);
            }

            // W in LSBs of WidthFrac.
            const double wRef = filterWidth(gRef, dx, dy, p.filterNorm) * N / eW;
            const double ex = N * (bG.x * std::abs(dx.x) + bG.y * std::abs(dx.y) + bG.z * std::abs(dx.z)) / eW + 1;
            const double ey = N * (bG.x * std::abs(dy.x) + bG.y * std::abs(dy.y) + bG.z * std::abs(dy.z)) / eW + 1;
            double bW = 0;
            switch (p.filterNorm) {
                case GradNorm::Euclid: bW = std::sqrt(ex * ex + ey * ey) + 1; break;
                case GradNorm::MaxHalfMin: bW = 1.5 * std::max(ex, ey) + 0.5; break;
                case GradNorm::L1: bW = ex + ey; break;
            }
            bW += 1e-12 * (1 + wRef);
            if (wRef + bW < wMax) {
                ++st->wKept;
                const double errW = std::abs(double(px.w) - wRef);
                ASSERT_LE(errW, bW) << p.name << " texture " << t << " sample " << i << " W gold " << px.w << " ref "
                                    << wRef;
                st->worstW = std::max(st->worstW, errW / bW);
            }
        }
    }
}

TEST(GoldenBounds, FGradAndWWithinTheFormatsBound) {
    for (const std::string& name : rtlProfiles()) {
        const Profile p = loadProfile(rtlProfilePath(name));
        // The subband unit's reference (evalF: model/subband.h, the 256-pixel tile) differs from
        // what the unit interpolates (the 128-pixel ROM tile) by more than a format bound: the
        // unit is checked against its own double reference within the derived bound, and that
        // against the reference basis, by golden_test SubbandFx.*.
        if (p.noise.basis == NoiseBasis::Subband) continue;
        Stats st;
        checkProfile(p, 1234, 600, 100, &st);
        std::printf("[ bounds ] %-13s %ld samples (%ld near saturation skipped, %ld with W): worst error / bound "
                    "f %.3f grad %.3f W %.3f (largest f error %.3g of bound %.3g)\n",
                    name.c_str(), st.kept, st.skipped, st.wKept, st.worstF, st.worstG, st.worstW, st.maxErrF,
                    st.maxBoundF);
        EXPECT_GT(st.kept, 20000);
        if (p.noise.basis != NoiseBasis::Worley) {
            EXPECT_GT(st.wKept, 10000);
        }
    }
}

}  // namespace
}  // namespace pst

// Tests of the golden arithmetic units (arith_fx.cpp) against the double reference
// (model/texture.h) on quantized inputs, with error bounds derived from the steps, plus exact
// identities (eq. 3 expanded), the integer square root, and the saturation cases.
#include "arith_fx.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "texture.h"
#include "source_dir.h"

namespace pst {
namespace {

using fx::i128;
using u128 = unsigned __int128;

Profile load(const char* name) { return loadNamedProfile(name, sourceDir()); }

// The shipped profiles, and a "narrow" variant of each whose F and Grad formats have few
// integer bits, so that saturation is common in the reference comparisons.
std::vector<Profile> profiles() {
    std::vector<Profile> out;
    for (const char* n : {"full", "reduced", "balanced"}) {
        Profile p = load(n);
        out.push_back(p);
        p.name += "-narrow";
        p.f.intBits = 3;
        p.grad.intBits = 4;
        p.log2Clut = 2;
        out.push_back(p);
    }
    return out;
}

constexpr double kEps = 0x1p-53;

// A double of log-uniform magnitude in [2^lo, 2^hi), random sign.
double logUniform(std::mt19937_64& g, double lo, double hi) {
    std::uniform_real_distribution<double> u(lo, hi);
    return std::ldexp((g() & 1) ? -1.0 : 1.0, 0) * std::exp2(u(g));
}

// ------------------------------------------------------------------------------------------
TEST(ArithFx, IsqrtIsFloorSqrt) {
    auto check = [](u128 x) {
        const u128 r = isqrtFx(x);
        ASSERT_LE(r * r, x);
        ASSERT_GT((r + 1) * (r + 1), x);
    };
    for (u128 x = 0; x < 200000; ++x) check(x);
    std::mt19937_64 g(7);
    for (int i = 0; i < 200000; ++i) {
        // Perfect squares of roots up to 2^63 - 1 (x < 2^126) and their neighbours.
        const int b = int(g() % 64);
        const uint64_t k = b == 0 ? 0 : ((uint64_t(1) << (b - 1)) | (g() & ((uint64_t(1) << (b - 1)) - 1)));
        const u128 k2 = u128(k) * k;
        EXPECT_EQ(isqrtFx(k2), k);
        if (k2 > 0) {
            EXPECT_EQ(isqrtFx(k2 - 1), k - 1);
        }
        check(k2 + 1);
        // Random x of any size below 2^126.
        const int xb = int(g() % 127);
        u128 x = (u128(g()) << 64) | g();
        x = xb == 0 ? 0 : (x & ((u128(1) << xb) - 1)) | (u128(1) << (xb - 1));
        if (xb <= 126) check(x);
    }
    const u128 top = (u128(1) << 126) - 1;
    EXPECT_EQ(isqrtFx(top), (uint64_t(1) << 63) - 1);
}

TEST(ArithFx, ShiftSatSigned) {
    EXPECT_EQ(shiftSatSigned(-1, 4, 8), -1);  // floor, not truncation
    EXPECT_EQ(shiftSatSigned(-16, 4, 8), -1);
    EXPECT_EQ(shiftSatSigned(-17, 4, 8), -2);
    EXPECT_EQ(shiftSatSigned(15, 4, 8), 0);
    EXPECT_EQ(shiftSatSigned(127 * 16 + 15, 4, 8), 127);  // just in range
    EXPECT_EQ(shiftSatSigned(128 * 16, 4, 8), 127);       // just saturates
    EXPECT_EQ(shiftSatSigned(-128 * 16, 4, 8), -128);
    EXPECT_EQ(shiftSatSigned(-128 * 16 - 1, 4, 8), -128);
    EXPECT_EQ(shiftSatSigned(3, -2, 8), 12);  // left shift, exact
    EXPECT_EQ(shiftSatSigned(32, -2, 8), 127);
    EXPECT_EQ(shiftSatSigned(-32, -2, 8), -128);
    EXPECT_EQ(shiftSatSigned(-33, -2, 8), -128);
    EXPECT_EQ(shiftSatSigned(i128(1) << 100, -60, 40), fx::maxSigned(40));  // no i128 overflow
    EXPECT_EQ(shiftSatSigned(-(i128(1) << 100), -60, 40), fx::minSigned(40));
}

// Eq. 3 evaluated term by term in i128 (an independent expansion of s . v + linear part).
i128 quadricEq3(const Profile& p, const int64_t s[3], const int64_t c[10]) {
    const int cf = p.coord.fracBits;
    const i128 x = s[0], y = s[1], z = s[2];
    const i128 A = c[0], B = c[1], C = c[2], D = c[3], E = c[4], F = c[5], G = c[6], H = c[7], I = c[8],
               J = c[9];
    return A * x * x + 2 * B * x * y + 2 * C * x * z + E * y * y + 2 * F * y * z + H * z * z +
           (2 * D * x + 2 * G * y + 2 * I * z) * (i128(1) << cf) + J * (i128(1) << (2 * cf));  // no << of a negative (UB)
}

TEST(ArithFx, QuadricMatchesEq3Exactly) {
    for (const Profile& p : profiles()) {
        std::mt19937_64 g(11);
        const int cw = p.coord.width(), qw = p.quadric.width();
        auto sval = [&](int w) {
            const int b = int(g() % w);
            const int64_t m = b == 0 ? 0 : int64_t((uint64_t(1) << (b - 1)) | (g() & ((uint64_t(1) << (b - 1)) - 1)));
            return (g() & 1) ? -m : m;
        };
        for (int i = 0; i < 100000; ++i) {
            int64_t s[3], c[10], q, gq[3];
            for (auto& v : s) v = sval(cw);
            for (auto& v : c) v = sval(qw);
            if (i < 64) {  // format extremes
                for (int k = 0; k < 3; ++k) s[k] = (i >> k) & 1 ? fx::maxSigned(cw) : fx::minSigned(cw);
                for (int k = 0; k < 10; ++k) c[k] = (i >> (3 + k % 3)) & 1 ? fx::maxSigned(qw) : fx::minSigned(qw);
            }
            quadricFx(p, s, c, &q, gq);
            const int qsh = p.quadric.fracBits + 2 * p.coord.fracBits - p.f.fracBits;
            ASSERT_EQ(q, fx::satSigned(fx::floorShift(quadricEq3(p, s, c), qsh), p.f.width())) << p.name;
            const int64_t row[3][4] = {{c[0], c[1], c[2], c[3]}, {c[1], c[4], c[5], c[6]}, {c[2], c[5], c[7], c[8]}};
            for (int r = 0; r < 3; ++r) {
                const i128 d = 2 * (i128(row[r][0]) * s[0] + i128(row[r][1]) * s[1] + i128(row[r][2]) * s[2] +
                                    i128(row[r][3]) * (i128(1) << p.coord.fracBits));
                const int gsh = p.quadric.fracBits + p.coord.fracBits - p.grad.fracBits;
                ASSERT_EQ(gq[r], fx::satSigned(fx::floorShift(d, gsh), p.grad.width())) << p.name;
            }
        }
    }
}

// quadricFx against Quadric::value / gradient on the same (quantized) inputs. The golden
// value is the exact q floored: ref 2^FFrac - golden in [0, 1) up to the double's own
// rounding, bounded by 16 eps (sum of |terms|) 2^FFrac (10 terms, at most 3 roundings each,
// plus the summation). Outside the F range (by more than the bound) golden is the clamp.
TEST(ArithFx, QuadricWithinBoundOfReference) {
    for (const Profile& p : profiles()) {
        std::mt19937_64 g(12);
        long inRange = 0, saturated = 0;
        double worstQ = 0, worstG = 0;
        for (int i = 0; i < 100000; ++i) {
            const double sr = std::exp2(std::uniform_real_distribution<double>(-6, p.coord.intBits - 1)(g));
            const double cr = std::exp2(std::uniform_real_distribution<double>(-8, p.quadric.intBits - 1)(g));
            int64_t s[3], c[10], q, gq[3];
            double sd[3], cd[10];
            for (int k = 0; k < 3; ++k) {
                s[k] = fx::quantize(std::uniform_real_distribution<double>(-sr, sr)(g), p.coord.intBits, p.coord.fracBits);
                sd[k] = fx::toDouble(s[k], p.coord.fracBits);
            }
            for (int k = 0; k < 10; ++k) {
                c[k] = fx::quantize(std::uniform_real_distribution<double>(-cr, cr)(g), p.quadric.intBits,
                                    p.quadric.fracBits);
                cd[k] = fx::toDouble(c[k], p.quadric.fracBits);
            }
            quadricFx(p, s, c, &q, gq);
            const Quadric Q{cd[0], cd[1], cd[2], cd[3], cd[4], cd[5], cd[6], cd[7], cd[8], cd[9]};
            const glm::dvec3 sv(sd[0], sd[1], sd[2]);
            const double x = sd[0], y = sd[1], z = sd[2];
            const double terms = std::abs(cd[0] * x * x) + 2 * std::abs(cd[1] * x * y) + 2 * std::abs(cd[2] * x * z) +
                                 2 * std::abs(cd[3] * x) + std::abs(cd[4] * y * y) + 2 * std::abs(cd[5] * y * z) +
                                 2 * std::abs(cd[6] * y) + std::abs(cd[7] * z * z) + 2 * std::abs(cd[8] * z) +
                                 std::abs(cd[9]);
            const double dq = 16 * kEps * terms * std::ldexp(1.0, p.f.fracBits);
            const double refQ = std::ldexp(Q.value(sv), p.f.fracBits);
            const double fmax = double(fx::maxSigned(p.f.width())), fmin = double(fx::minSigned(p.f.width()));
            if (refQ > fmin + dq && refQ < fmax + 1 - dq) {
                ++inRange;
                const double e = refQ - double(q);
                ASSERT_GE(e, -dq) << p.name << " q " << q << " ref " << refQ;
                ASSERT_LT(e, 1 + dq) << p.name << " q " << q << " ref " << refQ;
                worstQ = std::max(worstQ, std::abs(e));
            } else if (refQ >= fmax + 1 + dq) {
                ++saturated;
                ASSERT_EQ(q, fx::maxSigned(p.f.width())) << p.name;
            } else if (refQ <= fmin - dq) {
                ++saturated;
                ASSERT_EQ(q, fx::minSigned(p.f.width())) << p.name;
            }
            // grad q: 2 (Q [s 1])_xyz, 4 terms per component.
            const glm::dvec3 rg = Q.gradient(sv);
            const double rows[3][4] = {{cd[0], cd[1], cd[2], cd[3]}, {cd[1], cd[4], cd[5], cd[6]}, {cd[2], cd[5], cd[7], cd[8]}};
            for (int r = 0; r < 3; ++r) {
                const double t = 2 * (std::abs(rows[r][0] * x) + std::abs(rows[r][1] * y) + std::abs(rows[r][2] * z) +
                                      std::abs(rows[r][3]));
                const double dg = 8 * kEps * t * std::ldexp(1.0, p.grad.fracBits);
                const double ref = std::ldexp(rg[r], p.grad.fracBits);
                const double gmax = double(fx::maxSigned(p.grad.width())), gmin = double(fx::minSigned(p.grad.width()));
                if (ref > gmin + dg && ref < gmax + 1 - dg) {
                    const double e = ref - double(gq[r]);
                    ASSERT_GE(e, -dg) << p.name;
                    ASSERT_LT(e, 1 + dg) << p.name;
                    worstG = std::max(worstG, std::abs(e));
                } else if (ref >= gmax + 1 + dg) {
                    ASSERT_EQ(gq[r], fx::maxSigned(p.grad.width())) << p.name;
                } else if (ref <= gmin - dg) {
                    ASSERT_EQ(gq[r], fx::minSigned(p.grad.width())) << p.name;
                }
            }
        }
        std::printf("quadric vs reference [%s]: %ld in range (worst |err| %.3f LSB of F, grad %.3f LSB), "
                    "%ld saturated\n", p.name.c_str(), inRange, worstQ, worstG, saturated);
        EXPECT_GT(inRange, 10000);
        EXPECT_GT(saturated, 1000);
    }
}

TEST(ArithFx, QuadricSaturates) {
    for (const Profile& p : profiles()) {
        const int cw = p.coord.width(), qw = p.quadric.width();
        int64_t s[3] = {fx::maxSigned(cw), 0, 0}, c[10] = {fx::maxSigned(qw), 0, 0, 0, 0, 0, 0, 0, 0, 0};
        int64_t q, gq[3];
        quadricFx(p, s, c, &q, gq);  // A s^2 > 0, huge
        EXPECT_EQ(q, fx::maxSigned(p.f.width())) << p.name;
        EXPECT_EQ(gq[0], fx::maxSigned(p.grad.width())) << p.name;
        c[0] = fx::minSigned(qw);
        quadricFx(p, s, c, &q, gq);
        EXPECT_EQ(q, fx::minSigned(p.f.width())) << p.name;
        EXPECT_EQ(gq[0], fx::minSigned(p.grad.width())) << p.name;
        EXPECT_EQ(gq[1], 0);
        // J alone: q = J exactly (brought to FFrac).
        int64_t z[3] = {0, 0, 0}, cj[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, int64_t(1) << p.quadric.fracBits};
        quadricFx(p, z, cj, &q, gq);
        EXPECT_EQ(q, int64_t(1) << p.f.fracBits) << p.name;  // J = 1.0 -> q = 1.0
    }
}

// octaveTermFx: floor of the exact products, so the error to the double product is in [0, 1)
// LSB (the double products of these small integers are exact).
TEST(ArithFx, OctaveTermWithinOneLsb) {
    for (const Profile& p : profiles()) {
        std::mt19937_64 g(13);
        const int nf = p.noiseOutFrac;
        for (int i = 0; i < 100000; ++i) {
            const int64_t n = fx::quantize(std::uniform_real_distribution<double>(-3.5, 3.5)(g), 4, nf);
            int64_t gv[3], gm[9], ft, gt[3];
            for (auto& v : gv) v = fx::quantize(std::uniform_real_distribution<double>(-20, 20)(g), 6, nf);
            const int64_t a = fx::quantize(std::uniform_real_distribution<double>(-1.5, 1.5)(g), p.amplitude.intBits,
                                           p.amplitude.fracBits);
            for (auto& v : gm)
                v = fx::quantize(logUniform(g, -6, p.gradMatrix.intBits - 1), p.gradMatrix.intBits, p.gradMatrix.fracBits);
            octaveTermFx(p, n, gv, a, gm, &ft, gt);
            const double rf = std::ldexp(fx::toDouble(a, p.amplitude.fracBits) * fx::toDouble(n, nf), p.f.fracBits);
            const double fmax = double(fx::maxSigned(p.f.width())), fmin = double(fx::minSigned(p.f.width()));
            ASSERT_EQ(ft, fx::satSigned(i128(std::floor(rf)), p.f.width())) << p.name;
            if (rf > fmin && rf < fmax) {
                ASSERT_GE(rf - double(ft), 0.0);
                ASSERT_LT(rf - double(ft), 1.0);
            }
            for (int r = 0; r < 3; ++r) {
                double d = 0;
                for (int c = 0; c < 3; ++c) d += fx::toDouble(gm[3 * r + c], p.gradMatrix.fracBits) * fx::toDouble(gv[c], nf);
                const double rg = std::ldexp(d, p.grad.fracBits);
                const double tol = 8 * kEps * std::abs(rg) + 1e-9;
                const double gmax = double(fx::maxSigned(p.grad.width())), gmin = double(fx::minSigned(p.grad.width()));
                if (rg > gmin + tol && rg < gmax + 1 - tol) {
                    ASSERT_GE(rg - double(gt[r]), -tol) << p.name;
                    ASSERT_LT(rg - double(gt[r]), 1 + tol) << p.name;
                } else if (rg >= gmax + 1 + tol) {
                    ASSERT_EQ(gt[r], fx::maxSigned(p.grad.width())) << p.name;
                } else if (rg <= gmin - tol) {
                    ASSERT_EQ(gt[r], fx::minSigned(p.grad.width())) << p.name;
                }
            }
        }
    }
}

TEST(ArithFx, AccumulateSaturatesOnceAtTheEnd) {
    for (const Profile& p : profiles()) {
        const int64_t fmax = fx::maxSigned(p.f.width()), fmin = fx::minSigned(p.f.width());
        const int64_t gmax = fx::maxSigned(p.grad.width()), gmin = fx::minSigned(p.grad.width());
        EXPECT_EQ(accumulateF(p, 5, {}), 5);
        EXPECT_EQ(accumulateF(p, 5, {-7, 3}), 1);
        EXPECT_EQ(accumulateF(p, fmax, std::vector<int64_t>(16, fmax)), fmax);  // 17 x max: no wrap
        EXPECT_EQ(accumulateF(p, fmin, std::vector<int64_t>(16, fmin)), fmin);
        // An intermediate excursion past the range does not saturate: only the final sum does.
        EXPECT_EQ(accumulateF(p, fmax, {fmax, -fmax}), fmax);
        EXPECT_EQ(accumulateF(p, fmax - 1, {fmax, -fmax}), fmax - 1);
        EXPECT_EQ(accumulateF(p, fmax, {1}), fmax);
        EXPECT_EQ(accumulateF(p, fmin, {-1}), fmin);
        EXPECT_EQ(accumulateGrad(p, gmax, std::vector<int64_t>(16, gmax)), gmax);
        EXPECT_EQ(accumulateGrad(p, gmin, std::vector<int64_t>(16, gmin)), gmin);
        EXPECT_EQ(accumulateGrad(p, gmin + 2, {gmin, -gmin, -1}), gmin + 1);
    }
}

// filterWidthFx against pst::filterWidth(...) N 2^WidthFrac on the same quantized inputs.
// Wx = floor(gx N 2^WF) differs from the exact value by < 1, so |Wx| by < 1 per component:
//   euclid: the norm is 1-Lipschitz: < sqrt(2), then floor: < 1 + sqrt(2)
//   max_half_min: max < 1, min / 2 < 0.5, floor(min / 2) < 0.5 more: < 2
//   l1: < 2
// plus the double's rounding (relative 1e-12). Above WMax by that bound, W is WMax.
TEST(ArithFx, FilterWidthWithinBoundOfReference) {
    const GradNorm norms[3] = {GradNorm::Euclid, GradNorm::MaxHalfMin, GradNorm::L1};
    const double bounds[3] = {1 + std::sqrt(2.0), 2, 2};
    for (Profile p : profiles()) {
        for (int ni = 0; ni < 3; ++ni) {
            p.filterNorm = norms[ni];
            std::mt19937_64 g(14 + ni);
            const double wmax = double(fx::maxUnsigned(p.widthBits()));
            const double scale = std::ldexp(1.0, p.log2Clut + p.widthFrac);
            long inRange = 0, saturated = 0;
            double worst = 0;
            for (int i = 0; i < 100000; ++i) {
                int64_t gr[3], j[6];
                glm::dvec3 gd, dx, dy;
                const double gScale = std::uniform_real_distribution<double>(-4, p.grad.intBits - 1)(g);
                const double jScale = std::uniform_real_distribution<double>(-14, p.jacobian.intBits - 2)(g);
                for (int k = 0; k < 3; ++k) {
                    gr[k] = fx::quantize(logUniform(g, gScale - 4, gScale), p.grad.intBits, p.grad.fracBits);
                    gd[k] = fx::toDouble(gr[k], p.grad.fracBits);
                }
                for (int k = 0; k < 6; ++k) {
                    j[k] = fx::quantize(logUniform(g, jScale - 6, jScale), p.jacobian.intBits, p.jacobian.fracBits);
                    (k < 3 ? dx : dy)[k % 3] = fx::toDouble(j[k], p.jacobian.fracBits);
                }
                const int64_t w = filterWidthFx(p, gr, j);
                const double ref = filterWidth(gd, dx, dy, p.filterNorm) * scale;
                const double b = bounds[ni] + 1e-12 * ref;
                ASSERT_GE(w, 0);
                ASSERT_LE(w, int64_t(wmax));
                if (ref < wmax - b) {
                    ++inRange;
                    ASSERT_LE(std::abs(double(w) - ref), b) << p.name << " " << toString(p.filterNorm);
                    worst = std::max(worst, std::abs(double(w) - ref));
                } else if (ref > wmax + b) {
                    ++saturated;
                    ASSERT_EQ(w, int64_t(wmax)) << p.name << " " << toString(p.filterNorm);
                }
            }
            std::printf("filter width vs reference [%s, %s]: %ld in range (worst |err| %.3f LSB, bound %.3f), "
                        "%ld saturated\n", p.name.c_str(), toString(p.filterNorm), inRange, worst, bounds[ni],
                        saturated);
            EXPECT_GT(inRange, 10000);
            EXPECT_GT(saturated, 1000);
        }
    }
}

// Small exact cases: grad = (1, 0, 0), ds/dx = (Wx / (N 2^WF), ...): the 3-4-5 triangle, the
// floor-before-abs rule, and the clamp of a huge component.
TEST(ArithFx, FilterWidthExactCases) {
    for (Profile p : profiles()) {
        const int sh = p.jacobian.fracBits - p.log2Clut - p.widthFrac;  // j LSBs per W LSB (log2)
        ASSERT_GE(sh, 0) << p.name;
        const int64_t one = int64_t(1) << p.grad.fracBits;
        const int64_t wmax = fx::maxUnsigned(p.widthBits());
        auto w = [&](GradNorm n, int64_t jx, int64_t jy) {
            p.filterNorm = n;
            const int64_t gr[3] = {one, 0, 0}, j[6] = {jx, 0, 0, jy, 0, 0};
            return filterWidthFx(p, gr, j);
        };
        const int64_t u = int64_t(1) << sh;  // one W LSB
        EXPECT_EQ(w(GradNorm::Euclid, 3 * u, 4 * u), 5);
        EXPECT_EQ(w(GradNorm::Euclid, -3 * u, 4 * u), 5);
        EXPECT_EQ(w(GradNorm::Euclid, 3 * u, 5 * u), 5);  // sqrt(34) = 5.83 -> 5
        EXPECT_EQ(w(GradNorm::MaxHalfMin, 3 * u, -4 * u), 5);  // 4 + floor(3 / 2)
        EXPECT_EQ(w(GradNorm::L1, 3 * u, -4 * u), 7);
        EXPECT_EQ(w(GradNorm::Euclid, 0, 0), 0);
        // Floor before the absolute value: gx of -1 LSB of the exact product is Wx = -1 -> 1.
        if (sh > 0) {
            EXPECT_EQ(w(GradNorm::L1, -1, 0), 1);
            EXPECT_EQ(w(GradNorm::L1, 1, 0), 0);
        }
        // Clamp: a huge component saturates every norm, whatever the other.
        const int64_t big = fx::maxSigned(p.jacobian.width());
        for (GradNorm n : {GradNorm::Euclid, GradNorm::MaxHalfMin, GradNorm::L1}) {
            if ((double(big) / double(u)) > double(wmax)) {
                EXPECT_EQ(w(n, big, 0), wmax) << p.name;
                EXPECT_EQ(w(n, -big, 3 * u), wmax) << p.name;
            }
        }
        // Just below and at the saturation point of one axis.
        EXPECT_EQ(w(GradNorm::L1, wmax * u, 0), wmax);
        EXPECT_EQ(w(GradNorm::Euclid, (wmax - 1) * u, 0), wmax - 1);
        EXPECT_EQ(w(GradNorm::MaxHalfMin, (wmax - 1) * u, 1 * u), wmax - 1);
        EXPECT_EQ(w(GradNorm::MaxHalfMin, (wmax - 1) * u, 2 * u), wmax);
        EXPECT_EQ(w(GradNorm::L1, (wmax - 1) * u, 2 * u), wmax);
    }
}

}  // namespace
}  // namespace pst

namespace pst {
namespace {

// Bandlimited octaves: the golden fade (fadeLgFx, octaveFadeFx) against the reference's exact
// form octaveIsotropic, on quantized Jacobians. The golden lg nu per edge is below the exact
// one by at most Mitchell's 0.0861 + the truncated mantissa 1/16, lg ||M|| rounds by 1/32, the
// integer L = mx + floor(r/4) + floor(r/8) is up to 2 LSB under the exact max + 3/8 r, and the
// table holds h at its entry's centre (1/8 from any lg nu in it, and from the range's ends for
// the clamped ones): the entry is h at some lg nu within E of the reference's (clamped) one, rounded to 1/2^FadeFrac; alpha = the product
// floored, clamped to 1.
// The width cap (filter.width_cap): min(W, wcap) with wcap's low w_width bits (all ones: no cap).
TEST(ArithFx, WidthCapIsTheMinimum) {
    const Profile p = load("reduced");
    const int64_t wmax = fx::maxUnsigned(p.widthBits());
    for (int64_t w : {int64_t(0), int64_t(1), int64_t(77), wmax - 1, wmax}) {
        EXPECT_EQ(widthCapFx(p, w, wmax), w);
        EXPECT_EQ(widthCapFx(p, w, -1), w);   // the reset value: all ones
        EXPECT_EQ(widthCapFx(p, w, 0), 0);
        EXPECT_EQ(widthCapFx(p, w, 40), std::min<int64_t>(w, 40));
        EXPECT_EQ(widthCapFx(p, w, (int64_t(1) << p.widthBits()) + 40), std::min<int64_t>(w, 40));  // high bits dropped
    }
}

TEST(ArithFx, FadeWithinBoundOfReferenceIsotropic) {
    namespace c = contract;
    const double one = double(1 << c::kFadeFrac);
    for (const char* name : {"full", "reduced"}) {
        const Profile p = load(name);
        NoiseOptions noise = p.noise;
        int64_t table[c::kFadeEntries];
        for (int k = 0; k < c::kFadeEntries; ++k)
            table[k] = std::min<int64_t>(int64_t(one), std::llround(one * std::sqrt(noiseBoxGain(
                                                           noise, std::exp2(-c::kFadeLgLo + (k + 0.5) / 4.0)))));
        auto h = [&](double lg) { return std::sqrt(noiseBoxGain(noise, std::exp2(lg))); };
        std::mt19937_64 g(29);
        std::uniform_real_distribution<double> u(-1, 1);
        int checked = 0;
        for (int i = 0; i < 4000; ++i) {
            Octave o;
            for (int col = 0; col < 3; ++col)
                for (int k = 0; k < 3; ++k) o.M[col][k] = u(g) * std::exp2(4 * u(g) + 1);
            const double m = spectralNorm(o.M);
            const int64_t lgm = std::llround(std::log2(m) * (1 << c::kFadeLgFrac));
            glm::dvec3 e[2];
            int64_t j[6];
            int64_t lint[2];
            bool ok = true;
            for (int d = 0; d < 2; ++d) {
                const double len = std::exp2(5 * u(g) - 3);
                for (int k = 0; k < 3; ++k) {
                    j[3 * d + k] = fx::quantize(len * u(g), p.jacobian.intBits, p.jacobian.fracBits);
                    e[d][k] = fx::toDouble(j[3 * d + k], p.jacobian.fracBits);
                }
                lint[d] = int64_t(std::ldexp(footprintNorm(e[d]), p.jacobian.fracBits));
                ok = ok && lint[d] >= 64;  // the integer L within 3 % of the exact
            }
            if (!ok) continue;
            ++checked;
            const int64_t lgx = fadeLgFx(p, j), lgy = fadeLgFx(p, j + 3);
            const int64_t alpha = octaveFadeFx(lgx, lgy, lgm, table);
            double lo = 1, hi = 1;
            for (int d = 0; d < 2; ++d) {
                // The reference clamps lg nu to the table's range; the entry's centre is within E of that.
                const double lg = std::clamp(std::log2(m * footprintNorm(e[d])), kIsoLgLo, kIsoLgHi);
                const double E = 0.0861 + 1.0 / 16 + 1.0 / 32 + 1.0 / 8 + std::log2(1 + 2.0 / double(lint[d])) + 1e-9;
                double hmin = 2, hmax = 0;
                for (int s = 0; s <= 64; ++s) {
                    const double v = h(lg - E + 2 * E * s / 64.0);
                    hmin = std::min(hmin, v);
                    hmax = std::max(hmax, v);
                }
                lo *= std::max(0.0, hmin - 0.5 / one);
                hi *= std::min(1.0, hmax + 0.5 / one);
            }
            const double a = double(alpha) / one;
            ASSERT_GE(a, lo - 1 / one) << name << " i " << i;
            ASSERT_LE(a, std::min(1.0, hi)) << name << " i " << i << " lgx " << lgx << " lgy " << lgy << " lgm " << lgm
                                            << " ref lg " << std::log2(m * footprintNorm(e[0])) << " "
                                            << std::log2(m * footprintNorm(e[1])) << " L " << lint[0] << " " << lint[1];
            ASSERT_NEAR(a, octaveIsotropic(o, noise, e[0], e[1]), hi - lo + 1 / one) << name;
        }
        EXPECT_GT(checked, 1000) << name;
        // The scale: exact at 1, floored, never above |v|.
        EXPECT_EQ(fadeScaleFx(-12345, int64_t(one)), -12345);
        EXPECT_EQ(fadeScaleFx(-1, int64_t(one) / 2), -1);
        EXPECT_EQ(fadeScaleFx(7, int64_t(one) / 2), 3);
        EXPECT_EQ(fadeScaleFx(7, 0), 0);
    }
}

// The fade toward the term's mean: the term at alpha = 1, the mean at alpha = 0, fadeScaleFx with
// mean 0, halfway between (floored) at 1/2, saturated at the format's ends.
TEST(ArithFx, FadeGoesToTheTermsMean) {
    const Profile p = load("reduced");
    const int64_t one = int64_t(1) << contract::kFadeFrac;
    const int64_t hi = fx::maxSigned(p.f.width()), lo = fx::minSigned(p.f.width());
    for (int64_t f : {int64_t(-3000), int64_t(0), int64_t(77), hi, lo})
        for (int64_t m : {int64_t(-1418), int64_t(0), int64_t(1418), hi, lo}) {
            EXPECT_EQ(fadeToMeanFx(p, f, m, one), f) << f << " " << m;
            EXPECT_EQ(fadeToMeanFx(p, f, m, 0), m) << f << " " << m;
            if (m == 0) EXPECT_EQ(fadeToMeanFx(p, f, 0, one / 4), fadeScaleFx(f, one / 4));
            const int64_t d = f - m, half = (d >= 0 ? d : d - 1) / 2;  // floor(d / 2)
            EXPECT_EQ(fadeToMeanFx(p, f, m, one / 2), std::clamp(m + half, lo, hi)) << f << " " << m;
        }
    EXPECT_EQ(fadeToMeanFx(p, lo, hi, 1), lo + ((hi - lo) * 255 >> 8) + 0);  // 255/256 of the way to hi
}

// fadeLgFx on exact powers of two and Mitchell's mantissa.
TEST(ArithFx, FadeLgIsMitchellsLog) {
    const Profile p = load("reduced");
    const int jf = p.jacobian.fracBits;
    const int64_t unit[3] = {int64_t(1) << jf, 0, 0};
    EXPECT_EQ(fadeLgFx(p, unit), 0);                                  // |e| = 1
    const int64_t half[3] = {0, -(int64_t(1) << (jf - 1)), 0};
    EXPECT_EQ(fadeLgFx(p, half), -(1 << contract::kFadeLgFrac));      // 1/2
    const int64_t three[3] = {3 << jf, 0, 0};                          // 3 = 2 (1 + 1/2): 1 + 8/16
    EXPECT_EQ(fadeLgFx(p, three), (1 << contract::kFadeLgFrac) + 8);
    const int64_t diag[3] = {int64_t(1) << jf, int64_t(1) << jf, int64_t(1) << jf};  // L = 1.75
    EXPECT_EQ(fadeLgFx(p, diag), 12);
    const int64_t zero[3] = {0, 0, 0};                                  // counts as one LSB
    EXPECT_EQ(fadeLgFx(p, zero), -jf * (1 << contract::kFadeLgFrac));
}

}  // namespace
}  // namespace pst

// Tests of the golden subband unit (subband_fx.h): the ROM words against the tile they round, the
// golden unit against its double reference at the exact point the unit sees (within the bound
// derived in subband_fx.cpp), the ROM tile against the reference model's basis (model/subband.h)
// on the ROM's pixels (exact sampling), and between them (the bilinear interpolation on the
// ROM's coarser grid, within the tolerance derived below).
#include "subband_fx.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "arith_fx.h"
#include "contract.h"
#include "fixed.h"
#include "noise_fx.h"
#include "source_dir.h"
#include "unit_point_test.h"
#include "subband.h"

namespace pst {
namespace {

Profile reducedSubband() { return loadProfile(sourceDir() + "/sim/test_profiles/reduced_subband.toml"); }
// The full formats (LF 16) with a subband unit on the plane given.
Profile fullSubband(NoiseSubband plane, int K = 0) {
    Profile p = loadNamedProfile("full", sourceDir());
    p.noiseSubband = plane;
    p.noiseSubbandOrientations = K;
    p.noise = hardwareNoise(p);
    p.name = "full formats, subband";
    return p;
}

TEST(SubbandFx, RomWordsRoundTheTile) {
    // Every word is the tile rounded to VF bits, inside the word's range without saturating, so
    // |word - tile| <= 2^-(VF+1) holds everywhere (the bound's premise).
    const std::vector<double>& t = subbandRomTile(0);
    ASSERT_EQ(int(t.size()), kSubbandRomWords);
    const double lsb = std::ldexp(1.0, -contract::kSubbandValueFrac);
    const int64_t hi = fx::maxSigned(contract::kSubbandValueBits), lo = fx::minSigned(contract::kSubbandValueBits);
    double sum2 = 0;
    for (int i = 0; i < kSubbandRomWords; ++i) {
        const int64_t w = subbandRomWord(0, 0, i);
        ASSERT_LT(w, hi) << "word " << i << " saturates";
        ASSERT_GT(w, lo) << "word " << i << " saturates";
        ASSERT_LE(std::abs(double(w) * lsb - t[size_t(i)]), 0.5 * lsb) << "word " << i;
        sum2 += t[size_t(i)] * t[size_t(i)];
    }
    // The tile's standard deviation is Rayshade noise's (subbandCentreScale), within the sampling
    // of a 128 x 128 field (0.255 for the reference's seed 1).
    const double sd = std::sqrt(sum2 / kSubbandRomWords);
    EXPECT_NEAR(sd, 0.255, 0.01);
}

// The ROM tile is the reference model's basis at the ROM's pixels: subbandNoise (unfiltered, a
// plane) there is a bilinear lookup at a 256-pixel tile's pixel, exact (float tiles).
TEST(SubbandFx, RomTileIsTheReferenceOnItsPixels) {
    const Profile p = reducedSubband();
    const double px = double(1 << kSubbandUnitBits);
    for (int y = -3; y < kSubbandRomSide + 3; y += 5)
        for (int x = -2; x < kSubbandRomSide + 2; x += 3) {
            const glm::dvec2 uv(x / px, y / px);
            const double ref = noise(glm::dvec3(uv.x, 0.37 * x, uv.y), p.noise);  // param xz: y is not seen
            ASSERT_NEAR(subbandRomReference(0, uv, nullptr, nullptr), ref, 1e-6) << "pixel " << x << ", " << y;
        }
}

void checkProfile(const Profile& prof, uint64_t seed, int count) {
    const int OF = prof.noiseOutFrac, K = subbandOrientations(prof);
    int a0, a1;
    subbandAxes(prof, &a0, &a1);
    const SubbandFxErrorBound b = subbandFxErrorBound(prof);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-60.0, 60.0);
    double worst[2] = {0, 0};
    for (int t = 0; t < count; ++t) {
        // Every fourth point on a ROM pixel or a lattice plane (weights 0 and 2^WF).
        glm::dvec3 p(u(rng), u(rng), u(rng));
        if (t % 4 == 1) p = glm::floor(p * 4.0) / 4.0;
        if (t % 4 == 2) p = glm::floor(p);
        const UnitPoint pt = unitPoint(prof, p);
        // K = 4, 8: random weights in [0, 1.0] (0 and 1.0 among them).
        int64_t lamI[8];
        double lamD[8];
        const int64_t one = int64_t(1) << contract::kFadeFrac;
        for (int i = 0; i < 8; ++i) {
            lamI[i] = t % 7 == 3 ? (i % 2 ? one : 0) : int64_t(rng() % uint64_t(one + 1));
            lamD[i] = std::ldexp(double(lamI[i]), -contract::kFadeFrac);
        }
        const int64_t* lam = K == 0 ? nullptr : lamI;
        int64_t n, g[3];
        subbandFx(prof, pt.lat, pt.frac, lam, &n, g);
        glm::dvec2 gref;
        const double nref = subbandRomReference(K, glm::dvec2(pt.pq[a0], pt.pq[a1]), lamD, &gref);
        const std::string at = "at " + std::to_string(pt.pq.x) + " " + std::to_string(pt.pq.y) + " " + std::to_string(pt.pq.z);
        const double nfx = std::ldexp(double(n), -OF);
        ASSERT_LE(std::abs(nfx - nref), b.value) << "n " << at;
        worst[0] = std::max(worst[0], std::abs(nfx - nref) / b.value);
        for (int k = 0; k < 2; ++k) {
            const double ga = std::ldexp(double(g[k == 0 ? a0 : a1]), -OF);
            ASSERT_LE(std::abs(ga - gref[k]), b.grad) << "grad axis " << k << " " << at;
            worst[1] = std::max(worst[1], std::abs(ga - gref[k]) / b.grad);
        }
        ASSERT_EQ(g[3 - a0 - a1], 0) << "the axis outside the plane " << at;
    }
    std::printf("[ subband_fx ] %s (LF %d, OF %d, K %d): worst error / bound: n %.3f, grad %.3f\n",
                prof.name.c_str(), prof.noiseLatticeFrac, OF, K, worst[0], worst[1]);
}

TEST(SubbandFx, ReducedSubbandWithinTheBound) { checkProfile(reducedSubband(), 1, 20000); }
TEST(SubbandFx, OrientedTilesWithinTheBound) {
    for (int K : {4, 8}) {
        Profile p = reducedSubband();
        p.noiseSubbandOrientations = K;
        p.name = "reduced_subband, K " + std::to_string(K);
        checkProfile(p, 20 + K, 10000);
        ASSERT_FALSE(::testing::Test::HasFatalFailure());
        checkProfile(fullSubband(NoiseSubband::Xy, K), 30 + K, 3000);
        ASSERT_FALSE(::testing::Test::HasFatalFailure());
    }
}

// The oriented tiles: their words round the tiles without saturating, they are the reference's
// oriented subbands on the ROM's pixels (subbandNoise with the anisotropic filter at a footprint
// that keeps one orientation only is out of reach; instead: their sum is the isotropic tile),
// and the direction constants are round(256 cos), round(256 sin).
TEST(SubbandFx, OrientedTilesSumToTheIsotropicOne) {
    const double lsb = std::ldexp(1.0, -contract::kSubbandValueFrac);
    const std::vector<double>& iso = subbandRomTile(0);
    for (int K : {4, 8}) {
        const std::vector<double>& t = subbandRomTile(K);
        ASSERT_EQ(t.size(), size_t(K) * kSubbandRomWords);
        double maxDiff = 0;
        for (int a = 0; a < kSubbandRomWords; ++a) {
            double sum = 0;
            for (int i = 0; i < K; ++i) {
                const int64_t w = subbandRomWord(K, i, a);
                ASSERT_LT(w, fx::maxSigned(contract::kSubbandValueBits)) << "K " << K << " tile " << i << " word " << a;
                ASSERT_GT(w, fx::minSigned(contract::kSubbandValueBits)) << "K " << K << " tile " << i << " word " << a;
                ASSERT_LE(std::abs(double(w) * lsb - t[size_t(i) * kSubbandRomWords + a]), 0.5 * lsb);
                sum += t[size_t(i) * kSubbandRomWords + a];
            }
            maxDiff = std::max(maxDiff, std::abs(sum - iso[size_t(a)]));
        }
        EXPECT_LT(maxDiff, 1e-5) << "K " << K;  // float tiles summed in float by the reference
        int c, s;
        subbandDirection(K, 1, &c, &s);
        EXPECT_EQ(c, int(std::lround(256 * std::cos(3.141592653589793 / K))));
        EXPECT_EQ(s, int(std::lround(256 * std::sin(3.141592653589793 / K))));
    }
}

// The corrected lg against log2: for every length up to 2^16 (the 4 mantissa bits exact below
// 2^4, truncated above) lg L - lg_fx lies in -0.0376 .. +0.0875 octave (header's bound), and both
// ends are reached (the bound is the correction's, not a loose one).
TEST(SubbandFx, CorrectedLgWithinItsBound) {
    const Profile p = reducedSubband();
    double lo = 1, hi = -1;
    for (uint64_t len = 1; len < (uint64_t(1) << 16); ++len) {
        const double lg = double(subbandLgCorrectFx(mitchellLgFx(p, len))) / (1 << contract::kFadeLgFrac);
        const double e = std::log2(double(len)) - p.jacobian.fracBits - lg;
        lo = std::min(lo, e);
        hi = std::max(hi, e);
    }
    EXPECT_GE(lo, -0.0376);
    EXPECT_LE(hi, 0.0875);
    EXPECT_LT(lo, -0.03);
    EXPECT_GT(hi, 0.08);
}

// The weights against eq. 4's Gaussian: M = m I, so c_i . J of the octave is m c_i . J_s and the
// hardware's lg is off only by the direction constants (2^-9 relative), Mitchell's lg with its
// mantissa corrected (the true lg is the unit's + -0.0376 .. +0.0875 octave: the 16 mantissa steps'
// ends against floor(16 lg(1 + (m + 1/2) / 16)) / 16) and the table's quarter octave. With a
// table of h at each entry's top end (lg nu = -FadeLgLo + (k + 1) / 4) the table's lg is the
// true lg + -0.0875 .. +0.2876: lambda_fx lies between the exact lambda of the footprint scaled by
// 2^-0.09 and by 2^+0.29 (each edge's factor apart), up to the table's rounding.
TEST(SubbandFx, WeightsAreTheGaussianWithinTheTablesStep) {
    for (int K : {4, 8}) {
        Profile p = reducedSubband();
        p.noiseSubbandOrientations = K;
        p.filterBandlimit = FilterBandlimit::Isotropic;
        const double sigma = 0.2887, pi = 3.141592653589793;
        auto h = [&](double nu) { return std::exp(-sigma * sigma * pi * pi * nu * nu / 2); };
        int64_t table[contract::kFadeEntries];
        const int64_t one = int64_t(1) << contract::kFadeFrac;
        for (int k = 0; k < contract::kFadeEntries; ++k)
            table[k] = std::llround(h(std::exp2(-contract::kFadeLgLo + (k + 1.0) / 4.0)) * double(one));
        std::mt19937_64 rng(5 + K);
        std::uniform_real_distribution<double> u(-1.0, 1.0), lm(-2.0, 3.0);
        int checked = 0;
        for (int t = 0; t < 3000; ++t) {
            int64_t j[6];
            glm::dvec3 dx, dy;
            const double mag = std::exp2(lm(rng) - 4);
            for (int k = 0; k < 3; ++k) {
                j[k] = fx::quantize(mag * u(rng), p.jacobian.intBits, p.jacobian.fracBits);
                j[3 + k] = fx::quantize(mag * u(rng), p.jacobian.intBits, p.jacobian.fracBits);
                dx[k] = fx::toDouble(j[k], p.jacobian.fracBits);
                dy[k] = fx::toDouble(j[3 + k], p.jacobian.fracBits);
            }
            const double m = std::exp2(int(rng() % 5));  // an octave's scale, lg ||M|| exact
            const int64_t lgm = std::llround(std::log2(m) * (1 << contract::kFadeLgFrac));
            int64_t lg[16], lam[8];
            subbandPixelLgFx(p, j, lg);
            subbandLambdaFx(p, lg, lgm, table, lam);
            int a0, a1;
            subbandAxes(p, &a0, &a1);
            for (int i = 0; i < K; ++i) {
                const double th = pi * i / K;
                const double px = m * std::abs(std::cos(th) * dx[a0] + std::sin(th) * dx[a1]);
                const double py = m * std::abs(std::cos(th) * dy[a0] + std::sin(th) * dy[a1]);
                // Inside the table's range only (nu from 1/8 to 32 on both edges), away from 0.
                if (std::min(px, py) < 0.15 || std::max(px, py) > 28) continue;
                const double fx = double(lam[i]) / double(one);
                const double hi = h(px * std::exp2(-0.09)) * h(py * std::exp2(-0.09));
                const double lo = h(px * std::exp2(0.29)) * h(py * std::exp2(0.29));
                ASSERT_LE(fx, std::min(1.0, hi) + 2.0 / one) << "K " << K << " i " << i << " nu " << px << " " << py;
                ASSERT_GE(fx, lo - 2.0 / one) << "K " << K << " i " << i << " nu " << px << " " << py;
                ++checked;
            }
        }
        EXPECT_GT(checked, 2000) << "K " << K;
    }
}
TEST(SubbandFx, FullFormatsWithinTheBound) {
    for (NoiseSubband plane : {NoiseSubband::Xy, NoiseSubband::Xz, NoiseSubband::Yz}) {
        checkProfile(fullSubband(plane), 2 + int(plane), 5000);
        ASSERT_FALSE(::testing::Test::HasFatalFailure());
    }
}

// The unit's period: 2^SubbandPeriodLog2 noise units on both in-plane axes, any value on the third.
TEST(SubbandFx, PeriodicOnThePlane) {
    const Profile p = reducedSubband();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-40.0, 40.0);
    const double period = double(1 << contract::kSubbandPeriodLog2);
    for (int t = 0; t < 2000; ++t) {
        const glm::dvec3 x(u(rng), u(rng), u(rng));
        int64_t n0, g0[3], n1, g1[3];
        const UnitPoint a = unitPoint(p, x), b = unitPoint(p, x + glm::dvec3(period, 3.0 * t, -2 * period));
        subbandFx(p, a.lat, a.frac, nullptr, &n0, g0);
        subbandFx(p, b.lat, b.frac, nullptr, &n1, g1);
        ASSERT_EQ(n0, n1);
        for (int k = 0; k < 3; ++k) ASSERT_EQ(g0[k], g1[k]);
    }
}

// The unit against the reference model's basis between the ROM's pixels: the bilinear lookup
// of the 128-pixel tile instead of the 256-pixel one (itself nearly exact there: 16 pixels per
// unit). Linear interpolation of a sinusoid of frequency w (radians per ROM pixel) misses it by
// about t (1 - t) w^2 / 2 of its amplitude at the offset t, mean square over t: w^4 / 120. The
// band is centred on w = pi/8 per ROM pixel and reaches pi/4; per axis w_a^2 averages r^2 / 2
// (r the radius), so the RMS error is about sd r_c^2 sqrt(2 / 120) ~ 0.02 sd for the centre
// r_c = pi/8, and 0.04 sd at r = pi / (4 sqrt 2) (the band's power-weighted radius is between).
// The piecewise-constant derivative misses the sinusoid's by about w / sqrt 12 of its RMS (0.11
// at the centre, 0.23 at the band's edge). Bounds: RMS < 0.04 sd, value correlation above 0.998,
// gradient correlation above 0.98 (1 - 0.2^2 / 2).
TEST(SubbandFx, CloseToTheReferenceBasis) {
    const Profile p = reducedSubband();
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-40.0, 40.0);
    double se = 0, sr = 0, sf = 0, sfr = 0, gse = 0, gr = 0, gf = 0, gfr = 0;
    const int n = 20000;
    for (int t = 0; t < n; ++t) {
        const UnitPoint pt = unitPoint(p, glm::dvec3(u(rng), u(rng), u(rng)));
        int64_t v, g[3];
        subbandFx(p, pt.lat, pt.frac, nullptr, &v, g);
        glm::dvec3 gref;
        const double ref = noise(pt.pq, p.noise, &gref);
        const double f = std::ldexp(double(v), -p.noiseOutFrac);
        se += (f - ref) * (f - ref), sr += ref * ref, sf += f * f, sfr += f * ref;
        for (int k : {0, 2}) {
            const double gk = std::ldexp(double(g[k]), -p.noiseOutFrac);
            gse += (gk - gref[k]) * (gk - gref[k]), gr += gref[k] * gref[k], gf += gk * gk, gfr += gk * gref[k];
        }
    }
    const double sd = std::sqrt(sr / n), rms = std::sqrt(se / n);
    const double corr = sfr / std::sqrt(sf * sr), gcorr = gfr / std::sqrt(gf * gr);
    std::printf("[ subband_fx ] against the reference basis: RMS %.4f (sd %.4f, %.3f sd), correlation %.4f; "
                "gradient RMS %.4f (%.3f of its RMS), correlation %.4f\n",
                rms, sd, rms / sd, corr, std::sqrt(gse / (2 * n)), std::sqrt(gse / gr), gcorr);
    EXPECT_LT(rms, 0.04 * sd);
    EXPECT_GT(corr, 0.998);
    EXPECT_GT(gcorr, 0.98);
}

}  // namespace
}  // namespace pst

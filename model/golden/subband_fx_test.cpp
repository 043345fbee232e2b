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

#include "contract.h"
#include "fixed.h"
#include "noise_fx.h"
#include "source_dir.h"
#include "subband.h"

namespace pst {
namespace {

Profile reducedSubband() { return loadProfile(sourceDir() + "/sim/test_profiles/reduced_subband.toml"); }
// The full formats (LF 16) with a subband unit on the plane given.
Profile fullSubband(NoiseSubband plane) {
    Profile p = loadNamedProfile("full", sourceDir());
    p.noiseSubband = plane;
    p.noise = hardwareNoise(p);
    p.name = "full formats, subband";
    return p;
}

struct Point {
    int lat[3];
    int64_t frac[3];
    glm::dvec3 pq;  // the point the unit sees
};

// The unit's input for a point p (identity transform, as the hardware's octave transform).
Point unitPoint(const Profile& prof, const glm::dvec3& p) {
    Point pt;
    int64_t s[3], M[9] = {}, o[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) s[k] = fx::quantize(p[k], prof.coord.intBits, prof.coord.fracBits);
    for (int k = 0; k < 3; ++k) M[4 * k] = fx::quantize(1.0, prof.matrix.intBits, prof.matrix.fracBits);
    octaveTransformFx(prof, s, M, o, pt.lat, pt.frac);
    for (int k = 0; k < 3; ++k)
        pt.pq[k] = double(fx::floorShift(s[k], prof.coord.fracBits)) + std::ldexp(double(pt.frac[k]), -prof.noiseLatticeFrac);
    return pt;
}

TEST(SubbandFx, RomWordsRoundTheTile) {
    // Every word is the tile rounded to VF bits, inside the word's range without saturating, so
    // |word - tile| <= 2^-(VF+1) holds everywhere (the bound's premise).
    const std::vector<double>& t = subbandRomTile();
    ASSERT_EQ(int(t.size()), kSubbandRomWords);
    const double lsb = std::ldexp(1.0, -contract::kSubbandValueFrac);
    const int64_t hi = fx::maxSigned(contract::kSubbandValueBits), lo = fx::minSigned(contract::kSubbandValueBits);
    double sum2 = 0;
    for (int i = 0; i < kSubbandRomWords; ++i) {
        const int64_t w = subbandRomWord(i);
        ASSERT_LT(w, hi) << "word " << i << " saturates";
        ASSERT_GT(w, lo) << "word " << i << " saturates";
        ASSERT_LE(std::abs(double(w) * lsb - t[size_t(i)]), 0.5 * lsb) << "word " << i;
        sum2 += t[size_t(i)] * t[size_t(i)];
    }
    // The tile's standard deviation is Rayshade noise's (subbandCentreScale), within the sampling
    // of a 64 x 64 field (0.255 for the reference's seed 1).
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
            ASSERT_NEAR(subbandRomReference(uv, nullptr), ref, 1e-6) << "pixel " << x << ", " << y;
        }
}

void checkProfile(const Profile& prof, uint64_t seed, int count) {
    const int OF = prof.noiseOutFrac;
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
        const Point pt = unitPoint(prof, p);
        int64_t n, g[3];
        subbandFx(prof, pt.lat, pt.frac, &n, g);
        glm::dvec2 gref;
        const double nref = subbandRomReference(glm::dvec2(pt.pq[a0], pt.pq[a1]), &gref);
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
    std::printf("[ subband_fx ] %s (LF %d, OF %d): worst error / bound: n %.3f, grad %.3f\n", prof.name.c_str(),
                prof.noiseLatticeFrac, OF, worst[0], worst[1]);
}

TEST(SubbandFx, ReducedSubbandWithinTheBound) { checkProfile(reducedSubband(), 1, 20000); }
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
        const Point a = unitPoint(p, x), b = unitPoint(p, x + glm::dvec3(period, 3.0 * t, -2 * period));
        subbandFx(p, a.lat, a.frac, &n0, g0);
        subbandFx(p, b.lat, b.frac, &n1, g1);
        ASSERT_EQ(n0, n1);
        for (int k = 0; k < 3; ++k) ASSERT_EQ(g0[k], g1[k]);
    }
}

// The unit against the reference model's basis between the ROM's pixels: the bilinear lookup
// of the 64-pixel tile instead of the 256-pixel one (itself nearly exact there: 16 pixels per
// unit). Linear interpolation of a sinusoid of frequency w (radians per ROM pixel) misses it by
// about t (1 - t) w^2 / 2 of its amplitude at the offset t, mean square over t: w^4 / 120. The
// band is centred on w = pi/4 per ROM pixel and reaches pi/2; per axis w_a^2 averages r^2 / 2
// (r the radius), so the RMS error is about sd r_c^2 sqrt(2 / 120) ~ 0.08 sd for the centre
// r_c = pi/4, and 0.16 sd at r = pi / (2 sqrt 2) (the band's power-weighted radius is between).
// Bound: RMS < 0.16 sd; value and gradient also correlate above 0.98 and 0.9.
TEST(SubbandFx, CloseToTheReferenceBasis) {
    const Profile p = reducedSubband();
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-40.0, 40.0);
    double se = 0, sr = 0, sf = 0, sfr = 0, gse = 0, gr = 0, gf = 0, gfr = 0;
    const int n = 20000;
    for (int t = 0; t < n; ++t) {
        const Point pt = unitPoint(p, glm::dvec3(u(rng), u(rng), u(rng)));
        int64_t v, g[3];
        subbandFx(p, pt.lat, pt.frac, &v, g);
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
    EXPECT_LT(rms, 0.16 * sd);
    EXPECT_GT(corr, 0.98);
    EXPECT_GT(gcorr, 0.9);
}

}  // namespace
}  // namespace pst

// Tests of the golden worley unit (worley_fx.h) against its double reference, the hardware
// variant of model/worley.h at the exact point the unit sees: F_k, grad F_k, n and grad n
// within the bounds derived in worley_fx.cpp (worleyFxErrorBound), and the ROM words.
#include "worley_fx.h"

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "contract.h"
#include "fixed.h"
#include "noise_fx.h"
#include "worley.h"
#include "source_dir.h"
#include "unit_point_test.h"

namespace pst {
namespace {

// The test profile reduced_worley, and the full formats with a worley unit (search, points, order).
Profile reducedWorley() { return loadProfile(sourceDir() + "/sim/test_profiles/reduced_worley.toml"); }
Profile fullWorley(WorleySearchKind search, int points, int order) {
    Profile p = loadNamedProfile("full", sourceDir());
    p.noiseHash = NoiseHash::Perm256;
    p.noiseWorleySearch = search == WorleySearchKind::Octant ? NoiseWorleySearch::Octant : NoiseWorleySearch::Cube27;
    p.noiseWorleyPoints = points;
    p.noiseWorleyOrder = order;
    p.noise = hardwareNoise(p);
    return p;
}

// Compares one point: every F_k and grad F_k of the trace, n and grad n.
void checkPoint(const Profile& prof, const UnitPoint& pt, const double coef[4], double* worst) {
    const int NF = prof.noiseOutFrac + prof.noiseGuardBits, OF = prof.noiseOutFrac;
    int64_t creg[4];
    double cq[4], sumAbs = 0;
    NoiseOptions opt = prof.noise;
    for (int k = 0; k < 4; ++k) {
        creg[k] = fx::quantize(coef[k], contract::kWorleyCoefInt, contract::kWorleyCoefFrac);
        cq[k] = std::ldexp(double(creg[k]), -contract::kWorleyCoefFrac);
        opt.coef[size_t(k)] = k < prof.noiseWorleyOrder ? cq[k] : 0.0;
        if (k < prof.noiseWorleyOrder) sumAbs += std::abs(cq[k]);
    }
    int64_t n, g[3];
    WorleyFxTrace tr;
    worleyFx(prof, pt.lat, pt.frac, creg, &n, g, &tr);
    const WorleyResult ref = worley(pt.pq, prof.noiseWorleyOrder, WorleyMetric::Euclid, worleySearchOf(prof.noise));
    glm::dvec3 gref;
    const double nref = worleyBasis(pt.pq, opt, &gref);
    const WorleyFxErrorBound b = worleyFxErrorBound(prof, sumAbs);
    const std::string at = "at " + std::to_string(pt.pq.x) + " " + std::to_string(pt.pq.y) + " " + std::to_string(pt.pq.z);
    const double e = std::ldexp(1.0, -NF);
    for (int k = 0; k < prof.noiseWorleyOrder; ++k) {
        const double F = std::ldexp(double(tr.F[k]), -NF);
        // F_fx in (F - e, F]: the floor of the exact square root.
        ASSERT_LE(F, ref.F[k]) << "F" << k + 1 << " " << at;
        ASSERT_GT(F, ref.F[k] - e) << "F" << k + 1 << " " << at;
        for (int a = 0; a < 3; ++a) {
            const double ga = std::ldexp(double(tr.g[k][a]), -NF);
            ASSERT_LE(std::abs(ga - ref.grad[k][a]), b.grad) << "grad F" << k + 1 << " axis " << a << " " << at;
            worst[1] = std::max(worst[1], std::abs(ga - ref.grad[k][a]) / b.grad);
        }
        worst[0] = std::max(worst[0], (ref.F[k] - F) / b.F);
    }
    const double nfx = std::ldexp(double(n), -OF);
    ASSERT_LE(std::abs(nfx - nref), b.value) << "n " << at;
    worst[2] = std::max(worst[2], std::abs(nfx - nref) / b.value);
    for (int a = 0; a < 3; ++a) {
        const double ga = std::ldexp(double(g[a]), -OF);
        ASSERT_LE(std::abs(ga - gref[a]), b.gradN) << "grad n axis " << a << " " << at;
        worst[3] = std::max(worst[3], std::abs(ga - gref[a]) / b.gradN);
    }
}

void checkProfile(const Profile& prof, uint64_t seed, int count) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-60.0, 60.0);
    const double coefs[][4] = {{1, 0, 0, 0}, {-1, 1, 0, 0}, {0.5, 1.25, -0.75, 2}, {-3.5, 2.75, 1, -1}};
    double worst[4] = {0, 0, 0, 0};
    for (int t = 0; t < count; ++t) {
        const UnitPoint pt = unitPoint(prof, glm::dvec3(u(rng), u(rng), u(rng)));
        checkPoint(prof, pt, coefs[t % 4], worst);
        if (::testing::Test::HasFatalFailure()) return;
    }
    std::printf("[ worley_fx ] %s (LF %d, NF %d, %s, <= %d points, F1..F%d): worst error / bound: F %.3f, "
                "grad F %.3f, n %.3f, grad n %.3f\n",
                prof.name.c_str(), prof.noiseLatticeFrac, prof.noiseOutFrac + prof.noiseGuardBits,
                toString(prof.noise.search), prof.noise.maxPoints, prof.noiseWorleyOrder, worst[0], worst[1], worst[2],
                worst[3]);
}

TEST(WorleyFx, ReducedWorleyWithinTheBound) { checkProfile(reducedWorley(), 1, 20000); }

TEST(WorleyFx, FullFormatsWithinTheBound) {
    Profile p = fullWorley(WorleySearchKind::Octant, 4, 4);
    p.name = "full formats, octant";
    checkProfile(p, 2, 10000);
    p = fullWorley(WorleySearchKind::Cube27, 9, 2);
    p.name = "full formats, cube27";
    checkProfile(p, 3, 5000);
}

// Special points: cell corners, the octant's switch at u = 1/2, and points exactly on a
// feature point (S = 0: F = 0, gradient 0 in both) with the full formats' LF = 16 >= 9.
TEST(WorleyFx, SpecialPoints) {
    const Profile p = fullWorley(WorleySearchKind::Octant, 4, 2);
    const double q = std::ldexp(1.0, -p.noiseLatticeFrac);
    double worst[4] = {0, 0, 0, 0};
    const double coef[4] = {-1, 1, 0, 0};
    for (int i = -3; i <= 3; ++i)
        for (double f : {0.0, q, 0.5 - q, 0.5, 0.5 + q, 1.0 - q}) {
            checkPoint(p, unitPoint(p, glm::dvec3(i + f, 2 * i - f, 7.0 + f * i)), coef, worst);
            ASSERT_FALSE(::testing::Test::HasFatalFailure());
        }
    int onPoint = 0;
    for (int64_t c = -20; c <= 20; ++c) {
        const WorleyCube cube = worleyRomCube(worleyRomIndex(c, 3, -c), 4);
        const glm::dvec3 x = glm::dvec3(double(c), 3.0, double(-c)) + cube.offset[0];
        const UnitPoint pt = unitPoint(p, x);
        int64_t n, g[3];
        WorleyFxTrace tr;
        const int64_t creg[4] = {4096, 0, 0, 0};
        worleyFx(p, pt.lat, pt.frac, creg, &n, g, &tr);
        if (tr.S[0] == 0) {
            ++onPoint;
            EXPECT_EQ(tr.F[0], 0);
            EXPECT_EQ(n, 0);
            EXPECT_EQ(g[0] | g[1] | g[2], 0);
        }
        checkPoint(p, pt, coef, worst);
        ASSERT_FALSE(::testing::Test::HasFatalFailure());
    }
    EXPECT_GT(onPoint, 10);  // the octant holds the home cube's first point
}

// The ROM words are the reference's cubes (count clamped to M, position bytes).
TEST(WorleyFx, RomWordsAreTheReferenceCubes) {
    for (int m : {1, 4, 9})
        for (int e = 0; e < 256; ++e) {
            const WorleyRomWord w = worleyRomWord(e, m);
            const WorleyCube c = worleyRomCube(e, m);
            ASSERT_EQ(w.count, c.count);
            ASSERT_GE(w.count, 1);
            ASSERT_LE(w.count, m);
            for (int j = 0; j < c.count; ++j)
                for (int a = 0; a < 3; ++a) ASSERT_EQ((2.0 * w.b[size_t(3 * j + a)] + 1) / 512.0, c.offset[j][a]);
        }
}

TEST(WorleyFx, RefusesALatticeNoiseProfile) {
    const Profile p = loadNamedProfile("reduced", sourceDir());
    const int lat[3] = {0, 0, 0};
    const int64_t frac[3] = {0, 0, 0}, coef[4] = {0, 0, 0, 0};
    int64_t n, g[3];
    EXPECT_THROW(worleyFx(p, lat, frac, coef, &n, g), std::invalid_argument);
}

}  // namespace
}  // namespace pst

// Tests of the Worley cellular basis: F1..F4 and IDs against a brute-force search over a
// large block of cubes, the gradients against central differences, the Poisson table.
#include "worley.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <cstdio>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace pst {
namespace {

// The Poisson(4) probabilities, computed here without the model's table code.
double poisson(int m) { return std::exp(-kWorleyDensity + m * std::log(kWorleyDensity) - std::lgamma(m + 1.0)); }

TEST(Worley, PoissonTableHasTheClampedPoissonDistribution) {
    const auto& t = worleyPoissonTable();
    std::array<int, 10> hist{};
    double mean = 0;
    for (uint8_t m : t) {
        ASSERT_GE(m, kWorleyMinPoints);
        ASSERT_LE(m, kWorleyMaxPoints);
        ++hist[m];
        mean += m / 256.0;
    }
    // clamp(Poisson(4), 1, 9): P(1) takes P(0), P(9) takes the tail.
    double expectMean = 0, tail = 1;
    for (int m = 1; m <= 9; ++m) {
        double pm = poisson(m) + (m == 1 ? poisson(0) : 0.0);
        if (m == 9) pm = tail;  // what is left
        tail -= m == 1 ? poisson(0) + poisson(1) : poisson(m);
        expectMean += m * pm;
        // Each bucket holds its probability to within one 1/256 step of the table.
        EXPECT_NEAR(hist[m] / 256.0, pm, 1.0 / 256.0) << "m = " << m;
    }
    EXPECT_NEAR(mean, expectMean, 9.0 / 256.0);
    EXPECT_GT(mean, 3.5);  // "a density of about 4"
    EXPECT_LT(mean, 4.5);
    // The table is monotone (an inverse CDF): a binary search would do, as in the paper.
    EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
}

TEST(Worley, CubesAreReproducibleAndInside) {
    for (int64_t i = -3; i <= 3; ++i) {
        const WorleyCube a = worleyCube(i, 2 * i, -i), b = worleyCube(i, 2 * i, -i);
        ASSERT_EQ(a.count, b.count);
        for (int n = 0; n < a.count; ++n) {
            EXPECT_EQ(a.offset[n], b.offset[n]);
            EXPECT_EQ(a.id[n], a.id[0] + uint32_t(n));
            for (int c = 0; c < 3; ++c) {
                EXPECT_GT(a.offset[n][c], 0.0);
                EXPECT_LT(a.offset[n][c], 1.0);
            }
        }
    }
    // The hash is taken mod 2^32 per axis.
    const WorleyCube a = worleyCube(5, -6, 7), b = worleyCube(5 + (int64_t(1) << 32), -6, 7);
    EXPECT_EQ(a.count, b.count);
    EXPECT_EQ(a.offset[0], b.offset[0]);
}

// Mean number of points over many cubes: the density the texture sees.
TEST(Worley, MeanPointsPerCube) {
    double sum = 0;
    const int n = 40;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) sum += worleyCube(i - 20, j - 20, k - 20).count;
    const double mean = sum / (n * n * n);
    EXPECT_NEAR(mean, 4.0, 0.1);
}

struct Brute {
    std::vector<double> d;      // sorted distances
    std::vector<uint32_t> id;   // IDs in the same order
};

// Every point of every cube within `radius` cubes of p's cube, sorted.
Brute bruteForce(const glm::dvec3& p, WorleyMetric metric, int radius) {
    const glm::dvec3 b = glm::floor(p);
    std::vector<std::pair<double, uint32_t>> all;
    for (int i = -radius; i <= radius; ++i)
        for (int j = -radius; j <= radius; ++j)
            for (int k = -radius; k <= radius; ++k) {
                const WorleyCube c = worleyCube(int64_t(b.x) + i, int64_t(b.y) + j, int64_t(b.z) + k);
                for (int n = 0; n < c.count; ++n) {
                    const glm::dvec3 q = b + glm::dvec3(i, j, k) + c.offset[n];
                    const glm::dvec3 d = p - q;
                    const double m = metric == WorleyMetric::Euclid
                                         ? std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z)
                                         : std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
                    all.push_back({m, c.id[n]});
                }
            }
    std::sort(all.begin(), all.end());
    Brute r;
    for (auto& [m, id] : all) {
        r.d.push_back(m);
        r.id.push_back(id);
    }
    return r;
}

TEST(Worley, F1ToF4EqualABruteForceSearch) {
    // 7 x 7 x 7 cubes around the sample: far more than F4 can ever need (<= 4 cubes away).
    std::mt19937_64 rng(1996);
    std::uniform_real_distribution<double> u(-50.0, 50.0);
    for (WorleyMetric metric : {WorleyMetric::Euclid, WorleyMetric::Manhattan}) {
        for (int k = 0; k < 400; ++k) {
            const glm::dvec3 p(u(rng), u(rng), u(rng));
            const Brute b = bruteForce(p, metric, 3);
            const WorleyResult r = worley(p, 4, metric);
            for (int n = 0; n < 4; ++n) {
                // Same points, so the same distances up to the rounding of the difference.
                ASSERT_NEAR(r.F[n], b.d[n], 1e-12) << "F" << n + 1 << " metric " << toString(metric);
                const glm::dvec3& dn = r.delta[n];
                ASSERT_NEAR(metric == WorleyMetric::Euclid ? std::sqrt(glm::dot(dn, dn))
                                                           : std::abs(dn.x) + std::abs(dn.y) + std::abs(dn.z),
                            r.F[n], 1e-12);
                if (b.d[n + 1] - b.d[n] > 1e-9 && (n == 0 || b.d[n] - b.d[n - 1] > 1e-9)) {
                    ASSERT_EQ(r.id[n], b.id[n]) << "ID of F" << n + 1;
                }
            }
            // A lower order gives the same leading distances.
            const WorleyResult r1 = worley(p, 1, metric);
            ASSERT_EQ(r1.F[0], r.F[0]);
        }
    }
}

TEST(Worley, EuclidF1SearchAlsoRightInCorners) {
    // Samples near cube corners and faces, where the neighbours matter most.
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<int> ci(-30, 30);
    std::uniform_real_distribution<double> e(0.0, 0.02);
    for (int k = 0; k < 300; ++k) {
        glm::dvec3 p(ci(rng), ci(rng), ci(rng));
        for (int a = 0; a < 3; ++a) p[a] += (k >> a) & 1 ? e(rng) : 1.0 - e(rng);
        const Brute b = bruteForce(p, WorleyMetric::Euclid, 3);
        const WorleyResult r = worley(p, 4, WorleyMetric::Euclid);
        for (int n = 0; n < 4; ++n) ASSERT_NEAR(r.F[n], b.d[n], 1e-12);
    }
}

TEST(Worley, GradientsMatchCentralDifferences) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-20.0, 20.0);
    const double h = 1e-7;
    int checked = 0;
    for (WorleyMetric metric : {WorleyMetric::Euclid, WorleyMetric::Manhattan}) {
        for (int k = 0; k < 2000; ++k) {
            const glm::dvec3 p(u(rng), u(rng), u(rng));
            const WorleyResult r = worley(p, 4, metric);
            // Away from the cell boundaries: the four nearest must stay the same points within
            // the stencil (gaps between consecutive F well above the step), and away from a
            // point's own coordinate planes for Manhattan's sign().
            bool ok = true;
            for (int n = 0; n < 3; ++n) ok = ok && r.F[n + 1] - r.F[n] > 1e-4;
            const Brute b = bruteForce(p, metric, 3);
            ok = ok && b.d[4] - b.d[3] > 1e-4 && r.F[0] > 1e-3;
            if (!ok) continue;
            for (int a = 0; a < 3; ++a) {
                glm::dvec3 e(0.0);
                e[a] = h;
                const WorleyResult rp = worley(p + e, 4, metric), rm = worley(p - e, 4, metric);
                for (int n = 0; n < 4; ++n) {
                    if (rp.id[n] != r.id[n] || rm.id[n] != r.id[n]) { ok = false; break; }
                    const double fd = (rp.F[n] - rm.F[n]) / (2 * h);
                    ASSERT_NEAR(r.grad[n][a], fd, 1e-6) << "F" << n + 1 << " axis " << a;
                }
            }
            checked += ok;
            // The Euclidean gradient is the unit vector from the point.
            if (metric == WorleyMetric::Euclid) {
                for (int n = 0; n < 4; ++n) ASSERT_NEAR(glm::dot(r.grad[n], r.grad[n]), 1.0, 1e-12);
            }
        }
    }
    EXPECT_GT(checked, 3000);
}

TEST(Worley, BasisIsTheCoefficientSum) {
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(-9.0, 9.0);
    NoiseOptions opt;
    opt.basis = NoiseBasis::Worley;
    opt.coef = {-1.0, -1.0, 2.0, 0.0};  // 2 F3 - F2 - F1 (paper, section 4)
    opt.cell = 0.25;
    for (int k = 0; k < 200; ++k) {
        const glm::dvec3 p(u(rng), u(rng), u(rng));
        const WorleyResult r = worley(p, 3, WorleyMetric::Euclid);
        glm::dvec3 g;
        const double n = noise(p, opt, &g);
        // (summed in another order: equal up to rounding)
        EXPECT_NEAR(n, 2 * r.F[2] - r.F[1] - r.F[0] + 0.25 * worleyCellValue(r.id[0]), 1e-13);
        const glm::dvec3 eg = 2.0 * r.grad[2] - r.grad[1] - r.grad[0];
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(g[a], eg[a], 1e-13);
        EXPECT_GE(worleyCellValue(r.id[0]), 0.0);
        EXPECT_LT(worleyCellValue(r.id[0]), 1.0);
    }
}

TEST(Worley, MeanF1) {
    // For a Poisson process of density 4, E[F1] = Gamma(4/3) (4 pi 4 / 3)^(-1/3) = 0.3491; the
    // clamp to 1..9 points per cube moves it a little.
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> u(-200.0, 200.0);
    double sum = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) sum += worley(glm::dvec3(u(rng), u(rng), u(rng)), 1, WorleyMetric::Euclid).F[0];
    EXPECT_NEAR(sum / n, std::tgamma(4.0 / 3.0) * std::pow(4.0 * M_PI * 4.0 / 3.0, -1.0 / 3.0), 0.01);
}

TEST(Worley, NonFiniteAndHugeInputs) {
    const WorleyResult r = worley(glm::dvec3(NAN, 0, 0), 4, WorleyMetric::Euclid);
    for (int n = 0; n < 4; ++n) EXPECT_EQ(r.F[n], 0.0);
    // Periodic continuation beyond 2^31: same F as one period down.
    const glm::dvec3 p(0.3, 0.6, 0.2);
    const WorleyResult a = worley(p + glm::dvec3(4294967296.0 * 3, 0, 0), 2, WorleyMetric::Euclid),
                       b = worley(p, 2, WorleyMetric::Euclid);
    EXPECT_NEAR(a.F[0], b.F[0], 1e-6);
    EXPECT_NEAR(a.F[1], b.F[1], 1e-6);
}


// The hardware's cube contents: ROM entry e is the paper's cube (e, 0, 0) with its count
// clamped and each coordinate cut to its top byte, put at the centre of its 1/256 bin.
TEST(Worley, RomCubesAreThePapersCubesQuantized) {
    for (int m = 1; m <= kWorleyMaxPoints; ++m)
        for (int e = 0; e < 256; ++e) {
            const WorleyCube paper = worleyCube(e, 0, 0);
            const WorleyCube rom = worleyRomCube(e, m);
            ASSERT_EQ(rom.count, std::min(paper.count, m)) << "entry " << e;
            for (int n = 0; n < rom.count; ++n)
                for (int a = 0; a < 3; ++a) {
                    const double b = std::floor(paper.offset[n][a] * 256.0);
                    ASSERT_EQ(rom.offset[n][a], (2.0 * b + 1.0) / 512.0) << "entry " << e << " point " << n;
                    ASSERT_LE(std::abs(rom.offset[n][a] - paper.offset[n][a]), 1.0 / 512.0);
                }
        }
    // The cube hash is the perm256 lattice hash of (i + 576) mod 256: period 256 on each axis.
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<int64_t> u(-100000, 100000);
    for (int t = 0; t < 1000; ++t) {
        const int64_t i = u(rng), j = u(rng), k = u(rng);
        const int h = worleyRomIndex(i, j, k);
        ASSERT_GE(h, 0);
        ASSERT_LT(h, 256);
        ASSERT_EQ(h, worleyRomIndex(i + 256, j - 512, k + 768));
        const auto& P = NoiseTables::get().perm;
        auto X = [](int64_t x) { return int(((x % 256) + 256 + 64) % 256); };
        ASSERT_EQ(h, P[size_t(P[size_t(P[size_t(X(i))] ^ X(j))] ^ X(k))]);
    }
}

// The octant search equals a brute force over its eight cubes written here (sorting every
// candidate), for both cube sources and several caps.
TEST(Worley, OctantSearchIsABruteForceOverItsEightCubes) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-200.0, 200.0);
    for (WorleyCubes cubes : {WorleyCubes::Lcg, WorleyCubes::Rom256})
        for (int m : {1, 2, 4, 9})
            for (int t = 0; t < 3000; ++t) {
                const glm::dvec3 p(u(rng), u(rng), u(rng));
                WorleySearch s;
                s.octant = true;
                s.maxPoints = m;
                s.cubes = cubes;
                const WorleyResult r = worley(p, 4, WorleyMetric::Euclid, s);
                const glm::dvec3 base = glm::floor(p), fr = p - base;
                std::vector<double> d2;
                for (int c = 0; c < 8; ++c) {
                    glm::dvec3 o(0.0);
                    for (int a = 0; a < 3; ++a) o[a] = (c >> a) & 1 ? (fr[a] >= 0.5 ? 1.0 : -1.0) : 0.0;
                    const int64_t ci = int64_t(base.x + o.x), cj = int64_t(base.y + o.y), ck = int64_t(base.z + o.z);
                    const WorleyCube cube = cubes == WorleyCubes::Rom256 ? worleyRomCube(worleyRomIndex(ci, cj, ck), m)
                                                                         : worleyCube(ci, cj, ck);
                    for (int n = 0; n < std::min(cube.count, m); ++n) {
                        const glm::dvec3 d = fr - (o + cube.offset[n]);
                        d2.push_back(glm::dot(d, d));
                    }
                }
                std::sort(d2.begin(), d2.end());
                ASSERT_GE(d2.size(), 8u);
                for (int n = 0; n < 4; ++n)
                    ASSERT_EQ(r.F[n], std::sqrt(d2[size_t(n)])) << "F" << n + 1 << " at " << p.x << " " << p.y << " " << p.z;
            }
}

// The hardware variants (octant or 27 cubes, <= M points per cube, the ROM's cubes) against
// the paper's algorithm: the search's loss at the same points (LCG cubes), and the ROM's
// statistics (its points are other points: only distributions compare).
TEST(Worley, HardwareVariantDifferenceFromTheExactAlgorithm) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(-300.0, 300.0);
    std::vector<glm::dvec3> pts(50000);
    for (auto& p : pts) p = glm::dvec3(u(rng), u(rng), u(rng));
    std::vector<WorleyResult> exact;
    double exactMean[2] = {0, 0};
    for (const auto& p : pts) {
        exact.push_back(worley(p, 2, WorleyMetric::Euclid));
        for (int n = 0; n < 2; ++n) exactMean[n] += exact.back().F[n] / double(pts.size());
    }
    std::printf("[ worley ] exact: mean F1 %.4f, F2 %.4f\n", exactMean[0], exactMean[1]);
    for (bool octant : {true, false})
        for (int m : {9, 4, 3, 2}) {
            WorleySearch s;
            s.octant = octant;
            s.radius = octant ? -1 : 1;
            s.maxPoints = m;
            int differ[2] = {0, 0};
            double sumEx[2] = {0, 0}, romMean[2] = {0, 0};
            for (size_t i = 0; i < pts.size(); ++i) {
                s.cubes = WorleyCubes::Lcg;
                const WorleyResult r = worley(pts[i], 2, WorleyMetric::Euclid, s);
                s.cubes = WorleyCubes::Rom256;
                const WorleyResult rr = worley(pts[i], 2, WorleyMetric::Euclid, s);
                for (int n = 0; n < 2; ++n) {
                    ASSERT_GE(r.F[n], exact[i].F[n]);
                    if (r.F[n] > exact[i].F[n]) ++differ[n];
                    sumEx[n] += r.F[n] - exact[i].F[n];
                    romMean[n] += rr.F[n] / double(pts.size());
                }
            }
            std::printf("[ worley ] %s, <= %d points/cube: F1 differs at %6.3f%% (mean +%.4f), F2 at %6.3f%% "
                        "(mean +%.4f); with the ROM's cubes mean F1 %.4f, F2 %.4f\n",
                        octant ? "octant (8 cubes)" : "cube27 (27)    ", m, 100.0 * differ[0] / pts.size(),
                        sumEx[0] / pts.size(), 100.0 * differ[1] / pts.size(), sumEx[1] / pts.size(), romMean[0],
                        romMean[1]);
            if (m == 9) {
                // The 27 cubes hold F1 and F2 almost always; the octant misses F1 only when the
                // nearest point is beyond a far face (F1 > 1/2 at least): rare at 4 points/cube.
                EXPECT_LT(differ[0], int(pts.size() / (octant ? 50 : 1000)));
            }
        }
}

}  // namespace
}  // namespace pst

namespace pst {
namespace {

// The hardware variant's difference from the exact search (Worley's Poisson count up to 9 and
// as many cubes as it takes): a fixed 27-cube neighbourhood (radius 1) and at most M points per
// cube, over 100k random points. F_n of the cut search is never smaller than the exact F_n
// (it sees a subset of the points); the table says how often and by how much it is larger.
TEST(Worley, FixedSearchDifferenceFromTheExactSearch) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(-300.0, 300.0);
    std::vector<glm::dvec3> pts(100000);
    for (auto& p : pts) p = glm::dvec3(u(rng), u(rng), u(rng));
    std::printf("[ worley ] fixed search vs exact, %zu points: %% of points where F differs, max and mean "
                "excess\n", pts.size());
    for (WorleyMetric metric : {WorleyMetric::Euclid, WorleyMetric::Manhattan}) {
        std::vector<WorleyResult> exact;
        exact.reserve(pts.size());
        for (const auto& p : pts) exact.push_back(worley(p, 2, metric));
        for (const WorleySearch s : {WorleySearch{1, 9}, WorleySearch{1, 6}, WorleySearch{1, 4}, WorleySearch{1, 3},
                                     WorleySearch{1, 2}, WorleySearch{2, 4}}) {
            int differ[2] = {0, 0};
            double maxEx[2] = {0, 0}, sumEx[2] = {0, 0};
            for (size_t i = 0; i < pts.size(); ++i) {
                const WorleyResult r = worley(pts[i], 2, metric, s);
                for (int n = 0; n < 2; ++n) {
                    ASSERT_GE(r.F[n], exact[i].F[n]) << "F" << n + 1;
                    const double ex = r.F[n] - exact[i].F[n];
                    if (ex > 0) ++differ[n];
                    maxEx[n] = std::max(maxEx[n], ex);
                    sumEx[n] += ex;
                }
            }
            std::printf("[ worley ] %-9s radius %d, <= %d points/cube: F1 %6.3f%% (max +%.3g, mean +%.2g), "
                        "F2 %6.3f%% (max +%.3g, mean +%.2g)\n",
                        toString(metric), s.radius, s.maxPoints, 100.0 * differ[0] / pts.size(), maxEx[0],
                        sumEx[0] / pts.size(), 100.0 * differ[1] / pts.size(), maxEx[1], sumEx[1] / pts.size());
            if (s.radius == 1 && s.maxPoints == 9) {
                // Euclid: a 27-cube search misses the nearest point only when it lies beyond the
                // neighbour cubes (F1 > 1 minus the distance to the face): rare at 4 points/cube.
                EXPECT_LT(differ[0], int(pts.size() / 1000)) << toString(metric);
            }
        }
    }
}


}  // namespace
}  // namespace pst

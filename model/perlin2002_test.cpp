// Tests of perlin2002: values against Perlin's ImprovedNoise.java (through the independent
// Python transliteration's table, model/testdata/improved_noise_ref.{py,txt}), the analytic
// gradient against central differences, and the noise() entry point.
#include "perlin2002.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "noise.h"
#include "source_dir.h"

namespace pst {
namespace {

TEST(Perlin2002, EqualsThePublishedImplementationToTheLastBit) {
    const std::string path = sourceDir() + "/model/testdata/improved_noise_ref.txt";
    std::ifstream in(path);
    ASSERT_TRUE(in) << path;
    int count = 0, onLattice = 0;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string f[4];
        ASSERT_TRUE(ls >> f[0] >> f[1] >> f[2] >> f[3]) << line;
        double v[4];
        for (int k = 0; k < 4; ++k) v[k] = std::strtod(f[k].c_str(), nullptr);  // C99 hex floats
        const glm::dvec3 p(v[0], v[1], v[2]);
        const double n = perlin2002(p);
        ASSERT_EQ(n, v[3]) << "at (" << f[0] << ", " << f[1] << ", " << f[2] << ")";
        // The gradient path does not change the value.
        glm::dvec3 g;
        ASSERT_EQ(perlin2002(p, &g), v[3]);
        NoiseOptions opt;
        opt.basis = NoiseBasis::Perlin2002;
        ASSERT_EQ(noise(p, opt), v[3]);
        onLattice += p.x == std::floor(p.x) && p.y == std::floor(p.y) && p.z == std::floor(p.z);
        ++count;
    }
    EXPECT_GE(count, 1000);
    EXPECT_GT(onLattice, 0);
}

TEST(Perlin2002, PermutationIsAPermutation) {
    const auto& P = perlin2002Permutation();
    std::array<int, 256> seen{};
    for (uint8_t v : P) ++seen[v];
    for (int i = 0; i < 256; ++i) EXPECT_EQ(seen[i], 1) << i;
    EXPECT_EQ(P[0], 151);
    EXPECT_EQ(P[255], 180);
}

TEST(Perlin2002, ZeroOnTheLatticeAndPeriodic256) {
    // Gradient noise vanishes at every lattice point; the hash repeats every 256 cells.
    std::mt19937_64 rng(3);
    std::uniform_int_distribution<int> ci(-1000, 1000);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 200; ++k) {
        EXPECT_EQ(perlin2002(glm::dvec3(ci(rng), ci(rng), ci(rng))), 0.0);
        const glm::dvec3 p(ci(rng) + u(rng), ci(rng) + u(rng), ci(rng) + u(rng));
        EXPECT_NEAR(perlin2002(p + glm::dvec3(256.0, -512.0, 768.0)), perlin2002(p), 1e-12);
    }
}

TEST(Perlin2002, GradientMatchesCentralDifferences) {
    std::mt19937_64 rng(2002);
    std::uniform_real_distribution<double> cell(-40.0, 40.0), frac(0.02, 0.98);
    const double h = 1e-6;
    double maxErr = 0, maxAbsN = 0;
    for (int k = 0; k < 3000; ++k) {
        // Away from the lattice planes, so the differences stay inside one cell.
        const glm::dvec3 p(std::floor(cell(rng)) + frac(rng), std::floor(cell(rng)) + frac(rng),
                           std::floor(cell(rng)) + frac(rng));
        glm::dvec3 g;
        maxAbsN = std::max(maxAbsN, std::abs(perlin2002(p, &g)));
        for (int a = 0; a < 3; ++a) {
            glm::dvec3 e(0.0);
            e[a] = h;
            const double fd = (perlin2002(p + e) - perlin2002(p - e)) / (2 * h);
            maxErr = std::max(maxErr, std::abs(fd - g[a]));
            ASSERT_NEAR(g[a], fd, 1e-6) << "axis " << a << " at " << p.x << " " << p.y << " " << p.z;
        }
    }
    EXPECT_LT(maxAbsN, 1.5);
    EXPECT_GT(maxAbsN, 0.5);  // not a flat function
}

TEST(Perlin2002, GradientIsContinuousAcrossCellFaces) {
    // fade' = 0 on the lattice planes: the gradient from both sides of a face agrees.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.05, 0.95);
    for (int k = 0; k < 300; ++k) {
        const int a = k % 3;
        glm::dvec3 p(u(rng) + 3, u(rng) - 7, u(rng) + 11);
        p[a] = std::floor(p[a]) + 1.0;
        glm::dvec3 lo = p, gl, gh;
        lo[a] = std::nextafter(p[a], -1e9);
        perlin2002(lo, &gl);
        perlin2002(p, &gh);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(gl[c], gh[c], 1e-9);
    }
}

TEST(Perlin2002, NonFiniteGivesZero) {
    glm::dvec3 g(1.0);
    EXPECT_EQ(perlin2002(glm::dvec3(NAN, 0.5, 0.5), &g), 0.0);
    EXPECT_EQ(g, glm::dvec3(0.0));
    EXPECT_EQ(perlin2002(glm::dvec3(0.5, INFINITY, 0.5)), 0.0);
}

}  // namespace
}  // namespace pst

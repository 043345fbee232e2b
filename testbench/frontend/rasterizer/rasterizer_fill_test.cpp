// Rasterizer tests, fill rule: no cracks and no double coverage on shared edges, coverage of
// jittered meshes, speed.

#include "rasterizer_test_util.h"

namespace pst {
namespace {


// ---- Fill rule ----------------------------------------------------------------------------

// Per-pixel count of the triangles covering the sample point.
std::vector<int> coverageCount(const Camera& cam, const Mesh& mesh, const SampleOffset& off) {
    std::vector<int> count(size_t(cam.width) * cam.height, 0);
    scanMesh(cam, mesh, 0, [&](const Fragment& f) { ++count[size_t(f.y) * cam.width + f.x]; }, off);
    return count;
}

// The square [-1, 1]^2 (y = 0) as a grid with jittered interior vertices, random diagonals
// and random windings.
Mesh jitteredSquare(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.35, 0.35);
    Mesh m;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            double x = -1.0 + 2.0 * i / n, z = -1.0 + 2.0 * j / n;
            if (i > 0 && i < n) x += jitter(rng) * 2.0 / n;
            if (j > 0 && j < n) z += jitter(rng) * 2.0 / n;
            m.positions.push_back({x, 0.0, z});
            m.texcoords.push_back({x, 0.0, z});
        }
    auto idx = [&](int i, int j) { return uint32_t(i * (n + 1) + j); };
    auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
        if (rng() & 1) std::swap(b, c);
        m.triangles.push_back({a, b, c});
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            uint32_t a = idx(i, j), b = idx(i, j + 1), c = idx(i + 1, j + 1), d = idx(i + 1, j);
            if (rng() & 1) {
                add(a, b, c);
                add(a, c, d);
            } else {
                add(a, b, d);
                add(b, c, d);
            }
        }
    return m;
}

// Signed distances (pixels) of point p to the edges of a convex screen polygon; > 0 inside.
double insideMargin(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
    double area = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        area += a.x * b.y - a.y * b.x;
    }
    double margin = 1e30;
    for (size_t i = 0; i < poly.size(); ++i) {
        glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()], e = b - a;
        double cross = e.x * (p.y - a.y) - e.y * (p.x - a.x);
        margin = std::min(margin, (area > 0 ? cross : -cross) / glm::length(e));
    }
    return margin;
}

// Screen position (y down) of a world point, through glm::project.
glm::dvec2 screenOf(const Camera& cam, glm::dvec3 p) {
    glm::dvec3 w = glm::project(p, cam.view(), cam.projection(),
                                glm::dvec4(0.0, 0.0, cam.width, cam.height));
    return {w.x, cam.height - w.y};
}

// Every sample inside the square is hit exactly once, every sample outside never.
void expectExactCover(const Camera& cam, const Mesh& mesh, const std::vector<glm::dvec3>& outline,
                      const SampleOffset& off) {
    std::vector<glm::dvec2> poly;
    for (const auto& p : outline) poly.push_back(screenOf(cam, p));
    std::vector<int> count = coverageCount(cam, mesh, off);
    int inside = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            int c = count[size_t(y) * cam.width + x];
            ASSERT_LE(c, 1) << "double coverage at " << x << "," << y;
            double m = insideMargin(poly, glm::dvec2(x, y) + off(x, y));
            if (m > 1e-6) {
                ASSERT_EQ(c, 1) << "hole at " << x << "," << y;
                ++inside;
            }
            if (m < -1e-6) {
                ASSERT_EQ(c, 0) << "outside hit at " << x << "," << y;
            }
        }
    EXPECT_GT(inside, cam.width * cam.height / 10);
}

TEST(Rasterizer, NoCracksNoDoubleCoverage) {
    Camera cam = makeCamera({0.4, 2.2, 1.9}, {0.0, 0.0, 0.0}, 200, 150);
    std::vector<glm::dvec3> outline = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    // Random sample positions in [0, 1)^2, a fixed function of the pixel.
    SampleOffset jittered = [](int x, int y) {
        uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u;
        h ^= h >> 13;
        h *= 0x5bd1e995u;
        h ^= h >> 15;
        return glm::dvec2((h & 0xffff) / 65536.0, (h >> 16) / 65536.0);
    };
    for (unsigned seed : {1u, 2u, 3u}) {
        Mesh m = jitteredSquare(12, seed);
        expectExactCover(cam, m, outline, pixelCentre());
        expectExactCover(cam, m, outline, jittered);
    }
    // The same close up, crossing the near plane: clipped edges must still match.
    Camera close = makeCamera({0.1, 0.3, 0.8}, {0.0, 0.0, -1.0}, 160, 120, 70.0);
    Mesh m = jitteredSquare(16, 4u);
    std::vector<int> count = coverageCount(close, m, pixelCentre());
    for (int c : count) ASSERT_LE(c, 1);
}

// A fan around a vertex that projects exactly onto a sample point, with horizontal and
// vertical edges running exactly through rows and columns of sample points: the tie-breaking
// of the fill rule decides, and must give every sample to exactly one triangle.
TEST(Rasterizer, FillRuleTiesOnEdgesAndVertex) {
    Camera cam = makeCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 64, 64, 60.0);
    Mesh fan;
    fan.positions.push_back({0.0, 0.0, -2.0});  // projects to exactly (32, 32)
    for (int k = 0; k < 8; ++k) {
        double a = k * kPi / 4.0;
        double r = (k % 2) ? std::sqrt(2.0) : 1.0;  // a square ring: (+-1, 0), (+-1, +-1), ...
        fan.positions.push_back({std::round(r * std::cos(a)), std::round(r * std::sin(a)), -2.0});
    }
    fan.texcoords = fan.positions;
    for (uint32_t k = 0; k < 8; ++k) {
        uint32_t b = 1 + k, c = 1 + (k + 1) % 8;
        if (k % 3 == 0) std::swap(b, c);  // mixed windings
        fan.triangles.push_back({0, b, c});
    }
    SampleOffset corner = [](int, int) { return glm::dvec2(0.0, 0.0); };
    std::vector<glm::dvec3> outline = {{-1, -1, -2}, {1, -1, -2}, {1, 1, -2}, {-1, 1, -2}};
    expectExactCover(cam, fan, outline, corner);
    std::vector<int> count = coverageCount(cam, fan, corner);
    EXPECT_EQ(count[32 * 64 + 32], 1);
    // Samples on the row and column through the centre are exactly on edges: still once.
    for (int i = 20; i < 44; ++i) {
        EXPECT_EQ(count[32 * 64 + i], 1) << i;
        EXPECT_EQ(count[i * 64 + 32], 1) << i;
    }
    // Top-left: which triangle owns a tie. Scan each triangle alone and find the owner of
    // (a) a sample on the horizontal edge right of the centre: the triangle below it (its
    // world centroid has y < 0); (b) one on the vertical edge above the centre: the triangle
    // to its right (x > 0); (c) the centre vertex: the triangle right of it and below its
    // horizontal edge (x > 0, y < 0).
    auto owner = [&](int sx, int sy) {
        glm::dvec3 found(0.0);
        int hits = 0;
        for (const auto& tri : fan.triangles) {
            Mesh one = fan;
            one.triangles = {tri};
            scanMesh(cam, one, 0, [&](const Fragment& f) {
                if (f.x == sx && f.y == sy) {
                    ++hits;
                    const auto& p = fan.positions;
                    found = (p[tri[0]] + p[tri[1]] + p[tri[2]]) / 3.0;
                }
            }, corner);
        }
        EXPECT_EQ(hits, 1) << sx << "," << sy;
        return found;
    };
    EXPECT_LT(owner(40, 32).y, 0.0);
    EXPECT_GT(owner(32, 24).x, 0.0);
    glm::dvec3 c = owner(32, 32);
    EXPECT_GT(c.x, 0.0);
    EXPECT_LT(c.y, 0.0);
}

// ---- A full-size frame -------------------------------------------------------------------

// (Timings live in the benchmark, testbench/frontend/rasterizer/rasterizer_bench.cpp.)
TEST(Rasterizer, TeapotAt512IsFiniteAndFillsTheFrame) {
    Camera teapotCam = makeCamera({0.0, 4.0, 8.0}, {0.2, 1.4, 0.0}, 512, 512);
    Mesh teapot = makeTeapot(6);
    // The teapot fills a good part of the frame, with finite values in front of the camera.
    FragmentBuffer fb = render(teapotCam, teapot);
    int covered = 0;
    for (const Fragment& f : fb.fragments()) {
        if (f.object < 0) continue;
        ++covered;
        ASSERT_TRUE(finite(f.s) && finite(f.dsdx) && finite(f.dsdy));
        ASSERT_GT(f.depth, 5.0);
        ASSERT_LT(f.depth, 13.0);
    }
    EXPECT_GT(covered, 512 * 512 / 5);
}

}  // namespace
}  // namespace pst

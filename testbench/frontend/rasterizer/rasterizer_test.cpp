// Rasterizer tests: exact Jacobian (against finite differences and a closed form), s against
// an independent ray-plane intersection, z-buffer and occluder rule, near-plane clipping at
// the horizon, fill rule (no cracks, no double coverage), speed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/ext/matrix_projection.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "rasterizer.h"

namespace pst {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- Helpers ------------------------------------------------------------------------------

Camera makeCamera(glm::dvec3 eye, glm::dvec3 target, int width, int height, double fovy = 40.0) {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.width = width;
    c.height = height;
    c.fovyDeg = fovy;
    return c;
}

// A tilted plane (object space y = 0) and a general affine texture map of object space.
glm::dmat4 tiltedModel() {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(0.2, -0.3, 0.1));
    m = glm::rotate(m, glm::radians(25.0), glm::normalize(glm::dvec3(1.0, 0.3, -0.5)));
    return m;
}
glm::dmat4 skewTexture() {
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, -1.0, 0.5));
    t = glm::rotate(t, glm::radians(40.0), glm::normalize(glm::dvec3(0.2, 1.0, 0.4)));
    t = glm::scale(t, glm::dvec3(2.0, 0.7, 1.3));
    t[1][0] = 0.25;  // shear: column 1 (y), row 0 (x)
    return t;
}

// A plane z = 0 (object y = 0 rotated by +90 degrees about x) with texcoords = world position.
Mesh planeZ0(double halfSize, int n) {
    glm::dmat4 model = glm::rotate(glm::dmat4(1.0), kPi / 2.0, glm::dvec3(1.0, 0.0, 0.0));
    return makePlane(halfSize, n).transformed(model, model);
}

FragmentBuffer render(const Camera& cam, const Mesh& mesh,
                      const SampleOffset& off = pixelCentre()) {
    FragmentBuffer fb(cam.width, cam.height);
    rasterize(cam, mesh, 0, fb, nullptr, off);
    return fb;
}

SampleOffset shifted(double dx, double dy) {
    return [=](int, int) { return glm::dvec2(0.5 + dx, 0.5 + dy); };
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double maxAbs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// World-space ray through screen point (sx, sy), built from the camera's definition by hand
// (not from view()/projection()): direction with unit component along the view axis.
glm::dvec3 rayDirection(const Camera& cam, double sx, double sy) {
    glm::dvec3 f = glm::normalize(cam.target - cam.eye);
    glm::dvec3 r = glm::normalize(glm::cross(f, cam.up));
    glm::dvec3 u = glm::cross(r, f);
    double tanHalf = std::tan(cam.fovyDeg * kPi / 360.0);
    double aspect = double(cam.width) / cam.height;
    double nx = 2.0 * sx / cam.width - 1.0, ny = 1.0 - 2.0 * sy / cam.height;
    return f + (nx * tanHalf * aspect) * r + (ny * tanHalf) * u;
}

// Ray parameter t (= eye-space depth, as the direction has unit view-axis component) where
// the ray through pixel centre (x, y) meets the plane through p0 with normal n.
double rayPlane(const Camera& cam, int x, int y, glm::dvec3 p0, glm::dvec3 n) {
    glm::dvec3 d = rayDirection(cam, x + 0.5, y + 0.5);
    return glm::dot(p0 - cam.eye, n) / glm::dot(d, n);
}

// ---- Jacobian -----------------------------------------------------------------------------

// ds/dx and ds/dy against central differences of s, rendered with the sample point moved by
// +-h: s is one projective function on the whole plane, so every interior pixel qualifies.
TEST(Rasterizer, JacobianMatchesCentralDifferences) {
    Camera cam = makeCamera({0.7, 1.6, 3.5}, {0.0, -0.2, 0.0}, 160, 120);
    Mesh mesh = makePlane(2.5, 4).transformed(tiltedModel(), skewTexture());
    const double h = 1e-3;
    FragmentBuffer c = render(cam, mesh);
    FragmentBuffer xp = render(cam, mesh, shifted(h, 0.0));
    FragmentBuffer xm = render(cam, mesh, shifted(-h, 0.0));
    FragmentBuffer yp = render(cam, mesh, shifted(0.0, h));
    FragmentBuffer ym = render(cam, mesh, shifted(0.0, -h));
    int checked = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            if (!(c.covered(x, y) && xp.covered(x, y) && xm.covered(x, y) && yp.covered(x, y) &&
                  ym.covered(x, y)))
                continue;
            const Fragment& f = c.at(x, y);
            glm::dvec3 fdx = (xp.at(x, y).s - xm.at(x, y).s) / (2.0 * h);
            glm::dvec3 fdy = (yp.at(x, y).s - ym.at(x, y).s) / (2.0 * h);
            double scale = maxAbs(f.dsdx) + maxAbs(f.dsdy);
            ASSERT_LT(maxAbs(fdx - f.dsdx), 1e-6 * scale) << x << "," << y;
            ASSERT_LT(maxAbs(fdy - f.dsdy), 1e-6 * scale) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, cam.width * cam.height / 3);
}

// Camera looking straight down -z at the plane z = 0 with s = position: s moves by one
// pixel's world size per pixel, dsdy negative (y grows downward), depth = distance.
TEST(Rasterizer, JacobianClosedFormFacingPlane) {
    const double d = 3.0;
    Camera cam = makeCamera({0.0, 0.0, d}, {0.0, 0.0, 0.0}, 96, 64, 50.0);
    FragmentBuffer fb = render(cam, planeZ0(10.0, 3));
    double pixel = 2.0 * d * std::tan(glm::radians(cam.fovyDeg / 2.0)) / cam.height;
    for (const Fragment& f : fb.fragments()) {
        ASSERT_EQ(f.object, 0);
        EXPECT_NEAR(f.depth, d, 1e-12);
        EXPECT_NEAR(f.dsdx.x, pixel, 1e-12 * pixel);
        EXPECT_NEAR(f.dsdx.y, 0.0, 1e-12 * pixel);
        EXPECT_NEAR(f.dsdy.x, 0.0, 1e-12 * pixel);
        EXPECT_NEAR(f.dsdy.y, -pixel, 1e-12 * pixel);
        EXPECT_NEAR(f.dsdx.z, 0.0, 1e-12);
        EXPECT_NEAR(f.dsdy.z, 0.0, 1e-12);
        // The pixel centre's world position.
        EXPECT_NEAR(f.s.x, (f.x + 0.5 - cam.width / 2.0) * pixel, 1e-12);
        EXPECT_NEAR(f.s.y, (cam.height / 2.0 - f.y - 0.5) * pixel, 1e-12);
    }
}

// ---- Perspective-correct s ----------------------------------------------------------------

// s at each pixel centre = texture map of the ray-plane intersection, computed by hand.
TEST(Rasterizer, TexcoordIsRayPlaneIntersection) {
    Camera cam = makeCamera({0.7, 1.6, 3.5}, {0.0, -0.2, 0.0}, 160, 120);
    glm::dmat4 model = tiltedModel(), tex = skewTexture();
    Mesh mesh = makePlane(2.5, 3).transformed(model, tex);
    glm::dvec3 p0(model[3]), n = glm::normalize(glm::dvec3(model[1]));  // image of y = 0
    glm::dmat4 worldToTex = tex * glm::inverse(model);
    FragmentBuffer fb = render(cam, mesh);
    int covered = 0;
    for (const Fragment& f : fb.fragments()) {
        if (f.object < 0) continue;
        ++covered;
        double t = rayPlane(cam, f.x, f.y, p0, n);
        glm::dvec3 hit = cam.eye + t * rayDirection(cam, f.x + 0.5, f.y + 0.5);
        glm::dvec3 s = glm::dvec3(worldToTex * glm::dvec4(hit, 1.0));
        ASSERT_LT(maxAbs(f.s - s), 1e-10 * (1.0 + maxAbs(s))) << f.x << "," << f.y;
        ASSERT_NEAR(f.depth, t, 1e-10 * t);
    }
    EXPECT_GT(covered, 1000);
    // The same through glm::unProject (window y up) at one pixel, as a cross-check.
    const Fragment& f = fb.at(80, 60);
    ASSERT_EQ(f.object, 0);
    glm::dvec4 viewport(0.0, 0.0, cam.width, cam.height);
    glm::dvec3 a = glm::unProject(glm::dvec3(80.5, cam.height - 60.5, 0.0), cam.view(),
                                  cam.projection(), viewport);
    glm::dvec3 b = glm::unProject(glm::dvec3(80.5, cam.height - 60.5, 0.5), cam.view(),
                                  cam.projection(), viewport);
    glm::dvec3 hit = a + (glm::dot(p0 - a, n) / glm::dot(b - a, n)) * (b - a);
    EXPECT_LT(maxAbs(f.s - glm::dvec3(worldToTex * glm::dvec4(hit, 1.0))), 1e-9);
}

// Back faces are drawn (solid textures are two-sided).
TEST(Rasterizer, BackFacesAreDrawn) {
    Camera below = makeCamera({0.0, -3.0, 0.01}, {0.0, 0.0, 0.0}, 32, 32);
    FragmentBuffer fb = render(below, makePlane(5.0, 1));
    for (const Fragment& f : fb.fragments()) EXPECT_EQ(f.object, 0);
}

// A zero-area triangle (mesh.h: zeroArea, the rule the atlas shares) is skipped even where its
// rounding-thin sliver would cover a sample: a sliver +-h about y = 0, sampled on that row.
TEST(Rasterizer, ZeroAreaTrianglesAreSkipped) {
    const Camera cam = makeCamera({0.0, 0.0, 3.0}, {0.0, 0.0, 0.0}, 32, 32);
    auto sliver = [](double h) {
        Mesh m;
        m.positions = {{-1.0, -h, 0.0}, {1.0, -h, 0.0}, {0.0, h, 0.0}};
        m.texcoords = m.positions;
        m.triangles = {{0, 1, 2}};
        return m;
    };
    // Samples at y + 0: the row whose samples lie on world y = 0 (the screen's centre line).
    auto covered = [&](const Mesh& m) {
        size_t n = 0;
        for (const Fragment& f : render(cam, m, shifted(0.0, -0.5)).fragments()) n += f.object >= 0;
        return n;
    };
    EXPECT_GT(covered(sliver(1e-3)), 0u);
    EXPECT_FALSE(zeroArea(sliver(1e-3).positions[0], sliver(1e-3).positions[1], sliver(1e-3).positions[2]));
    const Mesh thin = sliver(1e-13);  // area 2e-13, longest edge 2: 5e-14 of its square
    EXPECT_TRUE(zeroArea(thin.positions[0], thin.positions[1], thin.positions[2]));
    EXPECT_EQ(zeroAreaTriangles(thin), 1u);
    EXPECT_EQ(covered(thin), 0u);
}

// ---- Z-buffer and occluder ----------------------------------------------------------------

// A unit quad in the plane z = zPlane centred at x = cx (texcoords = world position).
Mesh quadAt(double cx, double zPlane, int n = 1) {
    glm::dmat4 model = glm::translate(glm::dmat4(1.0), glm::dvec3(cx, 0.0, zPlane));
    model = glm::rotate(model, kPi / 2.0, glm::dvec3(1.0, 0.0, 0.0));
    return makePlane(1.0, n).transformed(model, model);
}

TEST(Rasterizer, NearerWinsRegardlessOfOrder) {
    Camera cam = makeCamera({0.0, 0.0, 5.0}, {0.0, 0.0, 0.0}, 128, 96);
    Mesh nearQuad = quadAt(-0.4, 0.0), farQuad = quadAt(0.4, -1.0);
    FragmentBuffer ab(cam.width, cam.height), ba(cam.width, cam.height);
    FragmentBuffer onlyNear = render(cam, nearQuad), onlyFar = render(cam, farQuad);
    rasterize(cam, nearQuad, 1, ab);
    rasterize(cam, farQuad, 2, ab);
    rasterize(cam, farQuad, 2, ba);
    rasterize(cam, nearQuad, 1, ba);
    int overlap = 0, farVisible = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const Fragment &f = ab.at(x, y), &g = ba.at(x, y);
            ASSERT_EQ(f.object, g.object);
            ASSERT_EQ(f.depth, g.depth);
            bool n = onlyNear.covered(x, y), fa = onlyFar.covered(x, y);
            int expected = n ? 1 : (fa ? 2 : -1);
            ASSERT_EQ(f.object, expected) << x << "," << y;
            if (n) {
                EXPECT_NEAR(f.depth, 5.0, 1e-12);
            } else if (fa) {
                EXPECT_NEAR(f.depth, 6.0, 1e-12);
            }
            overlap += n && fa;
            farVisible += !n && fa;
        }
    EXPECT_GT(overlap, 100);
    EXPECT_GT(farVisible, 100);
}

// Occluder rule: depth >= occluderDepth * (1 - kOccluderRelEpsilon) is discarded.
TEST(Rasterizer, OccluderDiscardsSamplesBehindAndCoincident) {
    Camera cam = makeCamera({0.0, 0.0, 5.0}, {0.0, 0.0, 0.0}, 128, 96);
    FragmentBuffer occ = render(cam, quadAt(-0.4, 0.0));

    // Behind: drawn only outside the occluder's coverage.
    FragmentBuffer behind(cam.width, cam.height);
    rasterize(cam, quadAt(0.4, -1.0), 3, behind, &occ);
    FragmentBuffer farAlone = render(cam, quadAt(0.4, -1.0));
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x)
            ASSERT_EQ(behind.covered(x, y), farAlone.covered(x, y) && !occ.covered(x, y));

    // The same surface again, even tessellated differently: always discarded.
    for (int n : {1, 7}) {
        FragmentBuffer again(cam.width, cam.height);
        rasterize(cam, quadAt(-0.4, 0.0, n), 3, again, &occ);
        for (const Fragment& f : again.fragments()) ASSERT_LT(f.object, 0);
    }

    // Slightly in front (1e-4 nearer): kept wherever it covers.
    FragmentBuffer front(cam.width, cam.height);
    rasterize(cam, quadAt(-0.4, 1e-4), 3, front, &occ);
    FragmentBuffer frontAlone = render(cam, quadAt(-0.4, 1e-4));
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x)
            ASSERT_EQ(front.covered(x, y), frontAlone.covered(x, y));
}

// Two-pass shell (planet and atmosphere): the sphere 0.1% larger survives the first pass as
// occluder wherever the inner sphere is visible; the identical sphere never does.
TEST(Rasterizer, OccluderShellAroundSphere) {
    Camera cam = makeCamera({0.3, 0.5, 4.0}, {0.0, 0.0, 0.0}, 96, 96);
    Mesh sphere = makeSphere(32, 16);
    FragmentBuffer inner = render(cam, sphere);
    FragmentBuffer shell(cam.width, cam.height), same(cam.width, cam.height);
    glm::dmat4 grow = glm::scale(glm::dmat4(1.0), glm::dvec3(1.001));
    rasterize(cam, sphere.transformed(grow, grow), 1, shell, &inner);
    rasterize(cam, sphere, 1, same, &inner);
    int innerCount = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            if (inner.covered(x, y)) {
                ++innerCount;
                ASSERT_TRUE(shell.covered(x, y));
                ASSERT_LT(shell.at(x, y).depth, inner.at(x, y).depth);
            }
            ASSERT_FALSE(same.covered(x, y));
        }
    EXPECT_GT(innerCount, 1000);
}

// ---- Near-plane clipping ------------------------------------------------------------------

// A huge ground plane under a camera looking at the horizon: it extends behind the camera and
// is clipped; it covers exactly the lower half, with finite values and exact s.
TEST(Rasterizer, NearClippingGroundToHorizon) {
    Camera cam = makeCamera({0.0, 1.0, 0.0}, {0.0, 1.0, -10.0}, 128, 96);
    for (int n : {1, 5}) {
        FragmentBuffer fb = render(cam, makePlane(1000.0, n));
        for (const Fragment& f : fb.fragments()) {
            ASSERT_EQ(f.object >= 0, f.y >= cam.height / 2) << f.x << "," << f.y << " n=" << n;
            if (f.object < 0) continue;
            ASSERT_TRUE(std::isfinite(f.depth) && finite(f.s) && finite(f.dsdx) && finite(f.dsdy));
            ASSERT_GE(f.depth, cam.nearPlane);
            double t = rayPlane(cam, f.x, f.y, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
            glm::dvec3 hit = cam.eye + t * rayDirection(cam, f.x + 0.5, f.y + 0.5);
            ASSERT_LT(maxAbs(f.s - hit), 1e-9 * (1.0 + maxAbs(hit))) << f.x << "," << f.y;
            ASSERT_NEAR(f.depth, t, 1e-9 * t);
        }
    }
}

// Triangles entirely behind the camera produce nothing.
TEST(Rasterizer, BehindCameraIsInvisible) {
    Camera cam = makeCamera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 64, 64);
    glm::dmat4 behind = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 3.0));
    FragmentBuffer fb = render(cam, makeSphere().transformed(behind, behind));
    for (const Fragment& f : fb.fragments()) ASSERT_LT(f.object, 0);
}

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

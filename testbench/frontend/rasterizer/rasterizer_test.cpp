// Rasterizer tests: exact Jacobian (against finite differences and a closed form), s against
// an independent ray-plane intersection, z-buffer and occluder rule, near-plane clipping at
// the horizon, fill rule (no cracks, no double coverage), speed.

#include "rasterizer_test_util.h"

namespace pst {
namespace {


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

}  // namespace
}  // namespace pst

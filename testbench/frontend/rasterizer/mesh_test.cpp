// Mesh tests: triangle counts, the teapot's well-known extents, sphere and torus radii,
// outward winding, no NaN, no zero-area triangle.
#include <cmath>
#include <map>
#include <tuple>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh.h"

namespace pst {
namespace {

glm::dvec3 corner(const Mesh& m, const std::array<uint32_t, 3>& t, int k) {
    return m.positions[t[k]];
}

// Unnormalised normal (twice the area) of a triangle, following its winding.
glm::dvec3 areaNormal(const Mesh& m, const std::array<uint32_t, 3>& t) {
    return glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0));
}

glm::dvec3 centroid(const Mesh& m, const std::array<uint32_t, 3>& t) {
    return (corner(m, t, 0) + corner(m, t, 1) + corner(m, t, 2)) / 3.0;
}

// Every mesh: matching array sizes, valid indices, finite values, texcoords = positions,
// no zero-area triangle.
void expectWellFormed(const Mesh& m) {
    ASSERT_EQ(m.positions.size(), m.texcoords.size());
    ASSERT_FALSE(m.triangles.empty());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(m.positions[i][c]));
            ASSERT_TRUE(std::isfinite(m.texcoords[i][c]));
        }
        ASSERT_EQ(m.positions[i], m.texcoords[i]);
    }
    for (const auto& t : m.triangles) {
        for (uint32_t k : t) ASSERT_LT(k, m.positions.size());
        ASSERT_GT(0.5 * glm::length(areaNormal(m, t)), 1e-9);
    }
}

// Directed edges, with endpoints rounded to 1e-9: on a consistently wound surface no
// directed edge occurs twice (a neighbour traverses a shared edge the other way).
void expectConsistentWinding(const Mesh& m) {
    using Key = std::tuple<long long, long long, long long>;
    auto key = [&](uint32_t i) {
        const glm::dvec3& p = m.positions[i];
        return Key(std::llround(p.x * 1e9), std::llround(p.y * 1e9), std::llround(p.z * 1e9));
    };
    std::map<std::pair<Key, Key>, int> directed;
    for (const auto& t : m.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{key(t[k]), key(t[(k + 1) % 3])}];
    int repeated = 0;
    for (const auto& [edge, count] : directed) repeated += count > 1;
    EXPECT_EQ(repeated, 0);
}

TEST(Mesh, CubeIsClosedAndOutward) {
    Mesh m = makeCube();
    expectWellFormed(m);
    EXPECT_EQ(m.triangles.size(), 12u);
    expectConsistentWinding(m);
    for (const auto& t : m.triangles) EXPECT_GT(glm::dot(areaNormal(m, t), centroid(m, t)), 0.0);
    for (const auto& p : m.positions)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(std::abs(p[c]), 1.0);
}

TEST(Mesh, SphereVerticesOnUnitSphere) {
    Mesh m = makeSphere(24, 12);
    expectWellFormed(m);
    // 2 poles + 11 rings of 24; 2 * 24 cap triangles + 2 * 24 * 10 between rings.
    EXPECT_EQ(m.positions.size(), 2u + 11u * 24u);
    EXPECT_EQ(m.triangles.size(), 2u * 24u + 2u * 24u * 10u);
    for (const auto& p : m.positions) EXPECT_NEAR(glm::length(p), 1.0, 1e-14);
    expectConsistentWinding(m);
    for (const auto& t : m.triangles) EXPECT_GT(glm::dot(areaNormal(m, t), centroid(m, t)), 0.0);
}

TEST(Mesh, TorusDistanceToRingIsMinorRadius) {
    const double R = 1.5, r = 0.4;
    Mesh m = makeTorus(R, r, 32, 16);
    expectWellFormed(m);
    EXPECT_EQ(m.positions.size(), 32u * 16u);
    EXPECT_EQ(m.triangles.size(), 2u * 32u * 16u);
    // Nearest point of the ring (radius R in the plane y = 0) to p.
    auto ringPoint = [&](const glm::dvec3& p) {
        return R * glm::normalize(glm::dvec3(p.x, 0.0, p.z));
    };
    for (const auto& p : m.positions) EXPECT_NEAR(glm::length(p - ringPoint(p)), r, 1e-14);
    expectConsistentWinding(m);
    // Outward = away from the tube's centre line.
    for (const auto& t : m.triangles) {
        glm::dvec3 c = centroid(m, t);
        EXPECT_GT(glm::dot(areaNormal(m, t), c - ringPoint(c)), 0.0);
    }
}

TEST(Mesh, PlaneFacesUp) {
    Mesh m = makePlane(2.0, 3);
    expectWellFormed(m);
    EXPECT_EQ(m.positions.size(), 16u);
    EXPECT_EQ(m.triangles.size(), 18u);
    expectConsistentWinding(m);
    double area = 0.0;
    for (const auto& t : m.triangles) {
        glm::dvec3 n = areaNormal(m, t);
        EXPECT_GT(n.y, 0.0);
        EXPECT_EQ(n.x, 0.0);
        EXPECT_EQ(n.z, 0.0);
        area += 0.5 * n.y;
    }
    EXPECT_NEAR(area, 16.0, 1e-12);
    for (const auto& p : m.positions) {
        EXPECT_EQ(p.y, 0.0);
        EXPECT_LE(std::abs(p.x), 2.0);
        EXPECT_LE(std::abs(p.z), 2.0);
    }
}

TEST(Mesh, TransformedMapsPositionsAndTexcoordsSeparately) {
    Mesh m = makeCube();
    glm::dmat4 model = glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 2.0, 3.0));
    glm::dmat4 tex = glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
    Mesh t = m.transformed(model, tex);
    ASSERT_EQ(t.positions.size(), m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_EQ(t.positions[i], m.positions[i] + glm::dvec3(1.0, 2.0, 3.0));
        EXPECT_EQ(t.texcoords[i], 2.0 * m.texcoords[i]);
    }
    EXPECT_EQ(t.triangles, m.triangles);
    // A mirror keeps the triangles counter-clockwise seen from outside.
    Mesh mirrored = m.transformed(glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, 1.0, 1.0)),
                                  glm::dmat4(1.0));
    for (const auto& tri : mirrored.triangles)
        EXPECT_GT(glm::dot(areaNormal(mirrored, tri), centroid(mirrored, tri)), 0.0);
}

// 32 patches of subdiv^2 quads, two triangles each, minus one triangle per quad along the
// collapsed edge of the 4 lid-knob patches (apex) and the 4 bottom patches (centre), for
// subdiv >= 2.
size_t teapotTriangles(int subdiv) {
    return size_t(32 * subdiv * subdiv * 2 - 8 * subdiv);
}

TEST(Mesh, TeapotTriangleCount) {
    // (At subdiv 1 the spout-tip patches' four corners are collinear and vanish as well.)
    for (int subdiv : {2, 3, 4, 6, 8}) {
        Mesh m = makeTeapot(subdiv);
        EXPECT_EQ(m.positions.size(), size_t(32 * (subdiv + 1) * (subdiv + 1)));
        EXPECT_EQ(m.triangles.size(), teapotTriangles(subdiv)) << "subdiv " << subdiv;
    }
    EXPECT_EQ(makeTeapot().triangles.size(), 992u);  // default subdiv 4
}

TEST(Mesh, TeapotIsWellFormedAndConsistentlyWound) {
    Mesh m = makeTeapot(6);
    expectWellFormed(m);
    expectConsistentWinding(m);
}

// The well-known extents of Newell's teapot (z-up: x [-3, 3.434], y [-2, 2], z [0, 3.15]),
// here y-up. A fine tessellation reaches them within its sampling.
TEST(Mesh, TeapotBoundingBox) {
    Mesh m = makeTeapot(32);
    glm::dvec3 lo(1e9), hi(-1e9);
    for (const auto& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    EXPECT_NEAR(lo.x, -3.0, 0.01);   // handle
    EXPECT_NEAR(hi.x, 3.434, 0.01);  // spout tip
    EXPECT_NEAR(lo.y, 0.0, 1e-12);   // base
    EXPECT_NEAR(hi.y, 3.15, 1e-12);  // lid knob
    EXPECT_NEAR(lo.z, -2.0, 1e-12);  // body
    EXPECT_NEAR(hi.z, 2.0, 1e-12);
}

// Each connected part (rim + body + bottom, lid, handle, spout) faces outward: checked at a
// place where "outward" is obvious; expectConsistentWinding covers the rest of each part.
TEST(Mesh, TeapotFacesOutward) {
    const int subdiv = 6;
    Mesh m = makeTeapot(subdiv);
    // Triangles are emitted patch by patch in the table's order; count them per patch.
    auto patchOf = [&](size_t tri) {
        // Patches 20-23 (knob) and 28-31 (bottom) lose `subdiv` triangles each.
        size_t full = size_t(2 * subdiv * subdiv), reduced = full - subdiv;
        size_t start = 0;
        for (int p = 0; p < 32; ++p) {
            size_t n = (p >= 20 && p < 24) || p >= 28 ? reduced : full;
            if (tri < start + n) return p;
            start += n;
        }
        return -1;
    };
    int checked[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < m.triangles.size(); ++i) {
        const auto& t = m.triangles[i];
        glm::dvec3 n = areaNormal(m, t), c = centroid(m, t);
        int p = patchOf(i);
        if (p >= 4 && p < 12) {  // body: radially outward
            EXPECT_GT(n.x * c.x + n.z * c.z, 0.0) << "patch " << p;
            ++checked[0];
        } else if (p >= 24 && p < 28) {  // lid: up
            EXPECT_GT(n.y, 0.0) << "patch " << p;
            ++checked[1];
        } else if (p >= 12 && p < 16 && c.x < -2.9) {  // outer side of the handle: -x
            EXPECT_LT(n.x, 0.0) << "patch " << p;
            ++checked[2];
        } else if (p >= 16 && p < 18 && std::abs(c.z) > 0.3) {  // flanks of the spout base
            EXPECT_GT(n.z * c.z, 0.0) << "patch " << p;
            ++checked[3];
        }
    }
    for (int k = 0; k < 4; ++k) EXPECT_GT(checked[k], 0) << "part " << k;
}

}  // namespace
}  // namespace pst

#include "atlas.h"

#include <cmath>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "atlas_render.h"
#include "input_error.h"
#include "mesh.h"
#include "multires.h"

namespace pst {
namespace {

// A right triangle in the z = 0 plane with legs (p, q): area p q / 2, longest edge sqrt(p^2+q^2).
AtlasTriangle rightTriangle(double p, double q, int index) {
    AtlasTriangle t;
    t.index = index;
    t.x = {glm::dvec3(0, 0, 0), glm::dvec3(p, 0, 0), glm::dvec3(0, q, 0)};
    t.s = t.x;
    return t;
}

std::vector<AtlasTriangle> meshTriangles(const Mesh& m) {
    std::vector<AtlasTriangle> out;
    for (size_t i = 0; i < m.triangles.size(); ++i) {
        const auto& tr = m.triangles[i];
        if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2]) continue;
        AtlasTriangle t;
        t.index = int(i);
        for (int k = 0; k < 3; ++k) {
            t.x[size_t(k)] = m.positions[tr[size_t(k)]];
            t.s[size_t(k)] = m.texcoords[tr[size_t(k)]];
        }
        out.push_back(t);
    }
    return out;
}

AtlasOptions opts(AtlasKind k, int size, Magnification m, bool seamFree = true) {
    AtlasOptions o;
    o.kind = k;
    o.size = size;
    o.magnification = m;
    o.seamFree = seamFree;
    return o;
}

// Chart images scale by (1 - kChartInset) about their centroid: areas by its square.
constexpr double kInsetArea = (1 - kChartInset) * (1 - kChartInset);

// Every texel claimed by at most one chart, and every claimed texel inside the atlas.
void expectPacked(const Atlas& a) {
    std::vector<int> claims(size_t(a.size()) * a.size(), 0);
    for (size_t t = 0; t < a.charts.size(); ++t) {
        for (const glm::ivec2& p : a.footprint(int(t))) {
            ASSERT_GE(p.x, 0);
            ASSERT_GE(p.y, 0);
            ASSERT_LT(p.x, a.size());
            ASSERT_LT(p.y, a.size());
            ++claims[size_t(p.y) * a.size() + p.x];
        }
        for (const glm::dvec2& u : a.charts[t].u) {
            EXPECT_GE(u.x, 0.0);
            EXPECT_GE(u.y, 0.0);
            EXPECT_LE(u.x, a.size());
            EXPECT_LE(u.y, a.size());
        }
    }
    for (int c : claims) ASSERT_LE(c, 1);
}

// Eq. (3) and the overscan, by hand for M = 8 triangles (4 pairs) in a 16 x 16 atlas:
// a = 16 / ceil(sqrt(4)) = 8. Nearest cells are (L+2) x (L+1): L = 6 gives 8 x 7 cells, 2 per
// row and 2 rows = 4 pairs; L = 7 (9 x 8) holds only 1 x 2. Bilinear cells (L+4) x (L+1):
// L = 4 (8 x 5) holds 2 x 3, L = 5 (9 x 6) 1 x 2. The standard layout's L x L cells: L = 8.
TEST(Atlas, UniformEdgeFollowsEq3AndOverscan) {
    std::vector<AtlasTriangle> tris;
    for (int i = 0; i < 8; ++i) tris.push_back(rightTriangle(1.0 + i, 2.0, i));
    const Atlas n = buildAtlas(tris, opts(AtlasKind::Uniform, 16, Magnification::Nearest));
    EXPECT_DOUBLE_EQ(n.eq3Edge, 8.0);
    for (const Chart& c : n.charts) EXPECT_EQ(c.legs, 6);
    EXPECT_EQ(n.cellSize(6), glm::ivec2(8, 7));
    expectPacked(n);
    // C = 8 charts x 6^2 / 2 texels / 16^2.
    EXPECT_NEAR(coverage(n), 8 * 18.0 / 256.0 * kInsetArea, 1e-12);

    const Atlas b = buildAtlas(tris, opts(AtlasKind::Uniform, 16, Magnification::Bilinear));
    for (const Chart& c : b.charts) EXPECT_EQ(c.legs, 4);
    expectPacked(b);
    const Atlas s = buildAtlas(tris, opts(AtlasKind::Uniform, 16, Magnification::Nearest, false));
    for (const Chart& c : s.charts) EXPECT_EQ(c.legs, 8);
    expectPacked(s);
    EXPECT_NEAR(coverage(s), 1.0, 1e-12);  // 4 full 8 x 8 cells
}

// Footprint sizes: nearest (L+1)(L+2)/2 texels a triangle, so a pair fills its (L+2) x (L+1)
// cell; bilinear (L+2)(L+3)/2 - 2 (the staircase i+j <= L+1 without its two far corners), so
// a pair leaves 2 of its (L+4) x (L+1) cell's texels unused.
TEST(Atlas, FootprintsTileTheCell) {
    std::vector<AtlasTriangle> tris = {rightTriangle(1, 1, 0), rightTriangle(2, 1, 1)};
    const Atlas n = buildAtlas(tris, opts(AtlasKind::Uniform, 16, Magnification::Nearest));
    const int L = n.charts[0].legs;
    EXPECT_EQ(L, 14);  // 16 wide: L + 2 <= 16
    EXPECT_EQ(n.footprint(0).size(), size_t((L + 1) * (L + 2) / 2));
    EXPECT_EQ(n.footprint(0).size() + n.footprint(1).size(), size_t((L + 2) * (L + 1)));
    const Atlas b = buildAtlas(tris, opts(AtlasKind::Uniform, 16, Magnification::Bilinear));
    const int Lb = b.charts[0].legs;
    EXPECT_EQ(Lb, 12);
    EXPECT_EQ(b.footprint(1).size(), size_t((Lb + 2) * (Lb + 3) / 2 - 2));
    EXPECT_EQ(b.footprint(0).size() + b.footprint(1).size(), size_t((Lb + 4) * (Lb + 1) - 2));
}

// Eq. (2) by hand: triangles of areas 1 and 4 with equal chart images A_u = 14^2/2/16^2:
// S^2 = (1 + 4) * (1/2) (A_u/1 + A_u/4) = 3.125 * 98 / 256, S = 1.09375.
TEST(Atlas, RelativeScaleUniformByHand) {
    std::vector<AtlasTriangle> tris = {rightTriangle(1, 2, 0), rightTriangle(2, 4, 1)};
    const Atlas a = buildAtlas(tris, opts(AtlasKind::Uniform, 16, Magnification::Nearest));
    EXPECT_NEAR(relativeScale(a), 1.09375 * (1 - kChartInset), 1e-12);
    EXPECT_NEAR(coverage(a), 2 * 98.0 / 256.0 * kInsetArea, 1e-12);
}

// Area weighting by hand: two triangles of area 4 (weight sqrt(4) = 2) and two of area 1
// (weight 1), 16 x 16, nearest. A strip of legs L >= 7 holds one pair (2 (L+2) > 16). With
// scale k: strip 1 (the area-4 pair) L1 = floor(2k), strip 2 L2 = floor(k); heights
// (L1 + 1) + (L2 + 1) <= 16 holds for k < 5 (k -> 5-: 9 and 4, 15 rows) and fails at k = 5
// (17 rows). So L1 = 9, L2 = 4.
TEST(Atlas, AreaWeightedByHand) {
    std::vector<AtlasTriangle> tris = {rightTriangle(1, 2, 0), rightTriangle(2, 4, 1), rightTriangle(2, 1, 2),
                                       rightTriangle(4, 2, 3)};
    const Atlas a = buildAtlas(tris, opts(AtlasKind::Area, 16, Magnification::Nearest));
    EXPECT_EQ(a.charts[1].legs, 9);
    EXPECT_EQ(a.charts[3].legs, 9);
    EXPECT_EQ(a.charts[0].legs, 4);
    EXPECT_EQ(a.charts[2].legs, 4);
    EXPECT_EQ(a.stripCount, 2);
    expectPacked(a);
    // r_j^2 = (sum A_x = 10) * A_u / A_x: 10 * (81/2/256) / 4 and 10 * (16/2/256) / 1.
    const double r2big = 10 * (40.5 / 256) / 4, r2small = 10 * (8.0 / 256) / 1;
    EXPECT_NEAR(relativeScale(a), std::sqrt((2 * r2big + 2 * r2small) / 4) * (1 - kChartInset), 1e-12);
    EXPECT_NEAR(coverage(a), (2 * 40.5 + 2 * 8.0) / 256 * kInsetArea, 1e-12);
}

// Two slivers (long edge ~8, area 0.4) and two compact triangles (longest edge ~2.83, area 2)
// in a 16 x 16 nearest atlas, where a strip of legs >= 7 holds one pair: area weighting puts
// the compact pair in the first, larger strip, length weighting the slivers.
TEST(Atlas, LengthWeightingFavoursSlivers) {
    std::vector<AtlasTriangle> tris = {rightTriangle(8, 0.1, 0), rightTriangle(2, 2, 1), rightTriangle(0.1, 8, 2),
                                       rightTriangle(2, 2, 3)};
    const Atlas area = buildAtlas(tris, opts(AtlasKind::Area, 16, Magnification::Nearest));
    const Atlas length = buildAtlas(tris, opts(AtlasKind::Length, 16, Magnification::Nearest));
    EXPECT_LT(area.charts[0].legs, area.charts[1].legs);
    EXPECT_GT(length.charts[0].legs, length.charts[1].legs);
    EXPECT_EQ(area.charts[0].legs, area.charts[2].legs);
    expectPacked(area);
    expectPacked(length);
}

// The packings of real meshes: nothing overlaps, everything inside, for every kind and layout.
TEST(Atlas, MeshesPackWithoutOverlap) {
    const std::vector<Mesh> meshes = {makeTeapot(4), makeTorus(1.0, 0.4, 16, 8), makeSphere(12, 6)};
    for (const Mesh& m : meshes)
        for (AtlasKind k : {AtlasKind::Uniform, AtlasKind::Area, AtlasKind::Length})
            for (Magnification f : {Magnification::Nearest, Magnification::Bilinear})
                for (bool seamFree : {true, false}) {
                    const Atlas a = buildAtlas(meshTriangles(m), opts(k, 256, f, seamFree));
                    expectPacked(a);
                    EXPECT_GT(coverage(a), 0.3);
                    EXPECT_LE(coverage(a), 1.0);
                }
}

// Every texel fragment is the affine chart map at the texel centre: the vertex texels carry
// the vertices' s, and stepping one texel right or down adds ds/du or ds/dv.
TEST(Atlas, TexelFragmentsInterpolateTheChart) {
    std::vector<AtlasTriangle> tris = {rightTriangle(3, 1, 0), rightTriangle(1, 2, 1)};
    tris[1].s = {glm::dvec3(5, 6, 7), glm::dvec3(5, 8, 7), glm::dvec3(4, 6, 9)};
    const Atlas a = buildAtlas(tris, opts(AtlasKind::Uniform, 16, Magnification::Bilinear));
    const std::vector<AtlasTexel> tx = atlasTexels(a);
    for (int t = 0; t < 2; ++t) {
        const Chart& c = a.charts[size_t(t)];
        for (int k = 0; k < 3; ++k) {
            const glm::ivec2 p(int(std::floor(c.u[size_t(k)].x)), int(std::floor(c.u[size_t(k)].y)));
            bool found = false;
            for (const AtlasTexel& x : tx)
                if (x.triangle == t && x.x == p.x && x.y == p.y) {
                    found = true;
                    EXPECT_NEAR(glm::length(x.s - a.triangles[size_t(t)].s[size_t(k)]), 0.0, 1e-4);
                }
            EXPECT_TRUE(found);
        }
        for (const AtlasTexel& x : tx)
            for (const AtlasTexel& y : tx)
                if (x.triangle == t && y.triangle == t) {
                    const glm::dvec3 step = y.s - x.s - double(y.x - x.x) * x.dsdu - double(y.y - x.y) * x.dsdv;
                    ASSERT_NEAR(glm::length(step), 0.0, 1e-9);
                }
    }
    // A unit chart step along u[1] - u[0] moves s along s1 - s0: ds/du . (u1 - u0) = s1 - s0.
    const Chart& c = a.charts[1];
    const AtlasTexel& x = *std::find_if(tx.begin(), tx.end(), [](const AtlasTexel& t) { return t.triangle == 1; });
    const glm::dvec2 e = c.u[1] - c.u[0];
    EXPECT_NEAR(glm::length(x.dsdu * e.x + x.dsdv * e.y - (a.triangles[1].s[1] - a.triangles[1].s[0])), 0.0, 1e-9);
}

// The seam rule (Fig. 2, 4c, section 6.3): a lookup anywhere on a chart (inside, on its edges
// and at its vertices) reads only the chart's own texels with the seam-free layout for its
// filter; the standard layout, and bilinear lookups into the nearest layout, read others.
size_t seamLookups(const Atlas& a, Magnification filter) {
    const std::vector<int> own = a.owners();
    const std::vector<float> rgba(own.size() * 4, 0.f);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    size_t seams = 0;
    for (int t = 0; t < int(a.charts.size()); ++t) {
        std::vector<glm::dvec3> bs = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
        for (int k = 0; k < 200; ++k) {
            double p = U(rng), q = U(rng);
            if (p + q > 1) p = 1 - p, q = 1 - q;
            bs.push_back({1 - p - q, p, q});
            bs.push_back({1 - p, p, 0});  // on the edges
            bs.push_back({0, p, 1 - p});
            bs.push_back({1 - p, 0, p});
        }
        for (const glm::dvec3& b : bs)
            seams += lookupAtlas(rgba, own, a.size(), t, chartPoint(a, t, b), filter).touchedForeign;
    }
    return seams;
}

TEST(Atlas, SeamFreeChartsReadOnlyTheirOwnTexels) {
    const std::vector<AtlasTriangle> tris = meshTriangles(makeTorus(1.0, 0.4, 16, 8));
    for (AtlasKind k : {AtlasKind::Uniform, AtlasKind::Area, AtlasKind::Length}) {
        const Atlas n = buildAtlas(tris, opts(k, 256, Magnification::Nearest));
        const Atlas b = buildAtlas(tris, opts(k, 256, Magnification::Bilinear));
        const Atlas s = buildAtlas(tris, opts(k, 256, Magnification::Nearest, false));
        EXPECT_EQ(seamLookups(n, Magnification::Nearest), 0u) << toString(k);
        EXPECT_EQ(seamLookups(b, Magnification::Bilinear), 0u) << toString(k);
        EXPECT_EQ(seamLookups(b, Magnification::Nearest), 0u) << toString(k);
        EXPECT_GT(seamLookups(n, Magnification::Bilinear), 0u) << toString(k);
        EXPECT_GT(seamLookups(s, Magnification::Nearest), 0u) << toString(k);
        EXPECT_GT(seamLookups(s, Magnification::Bilinear), 0u) << toString(k);
    }
}

// The rule render shares (mesh.h: zeroArea): a zero-area triangle of any mesh, an OBJ's
// included, gets no chart; sceneTriangles skips and counts it, and the atlas builds.
TEST(Atlas, SceneTrianglesSkipZeroAreaTriangles) {
    Scene scene;
    SceneObject o;
    o.name = "obj";
    o.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
    o.mesh.texcoords = o.mesh.positions;
    o.mesh.triangles = {{0, 1, 3}, {0, 1, 2}, {0, 0, 1}, {1, 2, 3}};  // collinear, repeated corner
    scene.objects.push_back(o);
    size_t skipped = 99;
    const std::vector<AtlasTriangle> tris = sceneTriangles(scene, &skipped);
    EXPECT_EQ(skipped, 2u);
    ASSERT_EQ(tris.size(), 2u);
    EXPECT_EQ(tris[0].index, 0);  // indices stay the mesh's
    EXPECT_EQ(tris[1].index, 3);
    EXPECT_NO_THROW(buildAtlas(tris, opts(AtlasKind::Uniform, 64, Magnification::Nearest)));
}

TEST(Atlas, RefusesDegenerateTrianglesAndOverfullSizes) {
    std::vector<AtlasTriangle> tris = {rightTriangle(1, 1, 0), rightTriangle(1, 1, 1)};
    tris[1].x[2] = 0.5 * (tris[1].x[0] + tris[1].x[1]);  // collinear
    try {
        buildAtlas(tris, opts(AtlasKind::Uniform, 64, Magnification::Nearest));
        FAIL() << "degenerate triangle accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("triangle 1 of object 0: degenerate"), std::string::npos) << e.what();
    }
    // 8 x 8 nearest: the smallest cell is 3 x 2, so 2 x 4 pairs = 16 triangles fit, 17 do not.
    std::vector<AtlasTriangle> many;
    for (int i = 0; i < 17; ++i) many.push_back(rightTriangle(1, 1 + i, i));
    for (AtlasKind k : {AtlasKind::Uniform, AtlasKind::Area, AtlasKind::Length}) {
        EXPECT_THROW(buildAtlas(many, opts(k, 8, Magnification::Nearest)), InputError);
        many.pop_back();
        EXPECT_NO_THROW(buildAtlas(many, opts(k, 8, Magnification::Nearest)));
        many.push_back(rightTriangle(1, 18, 16));
    }
}

// The multiresolution atlas (section 4.3) on a plane of 4 x 4 quads (32 triangles, each quad's
// two triangles sharing its diagonal): 16 pairs in a 32 x 32 atlas; the largest power of two a
// with (32 / a)^2 >= 16 cells is a = 8, so 4 x 4 cells of 8 x 8 texels, legs 8 - 2 = 6.
TEST(Multires, PairsShareAnEdgeAndCellsArePowersOfTwo) {
    const std::vector<AtlasTriangle> tris = meshTriangles(makePlane(1.0, 4));
    ASSERT_EQ(tris.size(), 32u);
    const Atlas a = buildMultiresAtlas(tris, opts(AtlasKind::Uniform, 32, Magnification::Nearest));
    EXPECT_EQ(a.mipCell, 8);
    expectPacked(a);
    // Each cell holds two triangles with two common vertices (an edge of the plane's mesh).
    std::map<std::pair<int, int>, std::vector<int>> cells;
    for (size_t t = 0; t < a.charts.size(); ++t) {
        EXPECT_EQ(a.charts[t].legs, 6);  // nearest: a - 2
        EXPECT_EQ(a.charts[t].cell.x % 8, 0);
        EXPECT_EQ(a.charts[t].cell.y % 8, 0);
        cells[{a.charts[t].cell.x, a.charts[t].cell.y}].push_back(int(t));
    }
    EXPECT_EQ(cells.size(), 16u);
    for (const auto& [c, ts] : cells) {
        ASSERT_EQ(ts.size(), 2u);
        int common = 0;
        for (const glm::dvec3& p : a.triangles[size_t(ts[0])].x)
            for (const glm::dvec3& q : a.triangles[size_t(ts[1])].x) common += p == q;
        EXPECT_EQ(common, 2);
    }
}

// Every kind refuses a size that is not a power of two, more pairs than the smallest cells
// hold (the 4 x 4 plane's 16 pairs in nearest cells of at least 4 x 4 texels: 8 x 8 holds 4,
// 16 x 16 all 16) and a non-manifold mesh.
TEST(Multires, RefusesNonPowerOfTwoOverfullAndNonManifold) {
    const std::vector<AtlasTriangle> tris = meshTriangles(makePlane(1.0, 4));
    // Three triangles on one edge (0,0,0)-(1,0,0).
    std::vector<AtlasTriangle> fin = {rightTriangle(1, 1, 0), rightTriangle(1, 1, 1), rightTriangle(1, 1, 2)};
    fin[1].x[2] = glm::dvec3(0, -1, 0);
    fin[2].x[2] = glm::dvec3(0, 0, 1);
    auto message = [](const std::vector<AtlasTriangle>& t, const AtlasOptions& o) {
        try {
            buildMultiresAtlas(t, o);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    for (AtlasKind k : {AtlasKind::Uniform, AtlasKind::Area, AtlasKind::Length}) {
        EXPECT_EQ(message(tris, opts(k, 48, Magnification::Nearest)),
                  "--size: 48 is not a power of two (the MIP levels halve it)");
        EXPECT_EQ(message(tris, opts(k, 8, Magnification::Nearest)),
                  "--size: 32 triangles (16 pairs) do not fit a 8 x 8 multiresolution atlas (it holds 4 pairs in 4 x 4 cells)");
        EXPECT_NO_THROW(buildMultiresAtlas(tris, opts(k, 16, Magnification::Nearest))) << toString(k);
        EXPECT_NE(message(fin, opts(k, 64, Magnification::Nearest)).find("shared by 3 triangles (non-manifold)"),
                  std::string::npos);
    }
}

// The non-uniform multiresolution atlases: each pair's cell a power of two on its own grid
// (so every MIP block holds one pair's cell or whole cells), the heavier pair (section 4.2's
// weight: RMS sqrt(area) or longest edge) never in a smaller cell, the two charts of a cell
// sharing a mesh edge, seam-free lookups, and MIP texels averaging only neighbours at every
// level on the torus (closed and connected; its inner triangles are smaller than its outer).
TEST(Multires, NonUniformCellsFollowWeightsAndMipStaysLocal) {
    const std::vector<AtlasTriangle> tris = meshTriangles(makeTorus(1.0, 0.4, 16, 8));
    for (AtlasKind k : {AtlasKind::Area, AtlasKind::Length})
        for (Magnification f : {Magnification::Nearest, Magnification::Bilinear}) {
            SCOPED_TRACE(std::string(toString(k)) + " " + toString(f));
            const Atlas a = buildMultiresAtlas(tris, opts(k, 256, f));
            expectPacked(a);
            EXPECT_EQ(seamLookups(a, f), 0u);
            std::map<std::pair<int, int>, std::vector<int>> cells;
            std::set<int> sides;
            for (size_t t = 0; t < a.charts.size(); ++t) {
                const Chart& c = a.charts[t];
                const int side = a.cellSize(c.legs).x;
                EXPECT_EQ(side & (side - 1), 0) << side;
                EXPECT_EQ(c.cell.x % side, 0);
                EXPECT_EQ(c.cell.y % side, 0);
                EXPECT_LE(side, a.mipCell);
                sides.insert(side);
                cells[{c.cell.x, c.cell.y}].push_back(int(t));
            }
            EXPECT_GT(sides.size(), 1u);  // non-uniform
            std::vector<std::pair<double, int>> weightSide;
            for (const auto& [o, ts] : cells) {
                ASSERT_EQ(ts.size(), 2u);  // the torus pairs every triangle
                int common = 0;
                double sum2 = 0;
                for (int t : ts) {
                    const AtlasTriangle& tr = a.triangles[size_t(t)];
                    const double w = k == AtlasKind::Area ? std::sqrt(tr.area()) : tr.longestEdge();
                    sum2 += w * w;
                }
                for (const glm::dvec3& p : a.triangles[size_t(ts[0])].x)
                    for (const glm::dvec3& q : a.triangles[size_t(ts[1])].x) common += p == q;
                EXPECT_EQ(common, 2);
                weightSide.push_back({std::sqrt(sum2 / 2), a.cellSize(a.charts[size_t(ts[0])].legs).x});
            }
            // The cells follow the weights: the heaviest quarter of the pairs in larger cells, on
            // average, than the lightest quarter (quadrants fit their cells locally, so a pair may
            // sit one size off its neighbour of equal weight elsewhere).
            std::sort(weightSide.begin(), weightSide.end());
            const size_t q = weightSide.size() / 4;
            double light = 0, heavy = 0;
            for (size_t i = 0; i < q; ++i) light += weightSide[i].second, heavy += weightSide[weightSide.size() - 1 - i].second;
            EXPECT_GT(heavy, light);
            const std::vector<long long> mix = mipMixing(a, dualGraph(a.triangles));
            ASSERT_EQ(mix.size(), 9u);
            for (size_t l = 0; l < mix.size(); ++l) EXPECT_EQ(mix[l], 0) << "level " << l;
        }
}

// Edge use, vertices welded by position: the cube and the torus are closed (every edge on two
// triangles); the cube without its +x face has that face's 4 edges open; a 2 x 2 plane has
// its 8 rim edges open; three triangles on one edge make it non-manifold (and their other 6
// edges open), the first of them named.
TEST(Multires, CountsOpenAndNonManifoldEdges) {
    for (const Mesh& closed : {makeCube(), makeTorus(1.0, 0.4, 16, 8)}) {
        const MeshEdges m = meshEdges(meshTriangles(closed));
        EXPECT_EQ(m.open, 0);
        EXPECT_EQ(m.nonManifold, 0);
        EXPECT_EQ(m.firstNonManifold, -1);
    }
    std::vector<AtlasTriangle> cube = meshTriangles(makeCube());
    cube.erase(cube.begin(), cube.begin() + 2);  // the +x quad's two triangles
    const MeshEdges holed = meshEdges(cube);
    EXPECT_EQ(holed.open, 4);
    EXPECT_EQ(holed.nonManifold, 0);
    EXPECT_EQ(meshEdges(meshTriangles(makePlane(1.0, 2))).open, 8);
    std::vector<AtlasTriangle> fin = {rightTriangle(1, 1, 0), rightTriangle(1, 1, 1), rightTriangle(1, 1, 2)};
    fin[1].x[2] = glm::dvec3(0, -1, 0);
    fin[2].x[2] = glm::dvec3(0, 0, 1);
    const MeshEdges f = meshEdges(fin);
    EXPECT_EQ(f.nonManifold, 1);
    EXPECT_EQ(f.mostTriangles, 3);
    EXPECT_EQ(f.open, 6);
    EXPECT_EQ(f.firstNonManifold, 0);
}

// Balanced quadtree: every triangle placed once in a 2^k grid of cells, seam-free lookups, and
// MIP texels of the multiresolution atlas average only connected patches of the torus (a
// closed, connected surface) at every level, while the strip atlas mixes non-neighbours.
TEST(Multires, MipTexelsAverageOnlyNeighbours) {
    const std::vector<AtlasTriangle> tris = meshTriangles(makeTorus(1.0, 0.4, 16, 8));
    const Atlas m = buildMultiresAtlas(tris, opts(AtlasKind::Uniform, 256, Magnification::Bilinear));
    expectPacked(m);
    EXPECT_EQ(seamLookups(m, Magnification::Bilinear), 0u);
    const std::vector<std::vector<int>> dual = dualGraph(m.triangles);
    for (const auto& nb : dual) EXPECT_EQ(nb.size(), 3u);  // a closed triangle mesh
    const std::vector<long long> mixM = mipMixing(m, dual);
    ASSERT_EQ(mixM.size(), 9u);  // 256 .. 1
    for (size_t l = 0; l < mixM.size(); ++l) EXPECT_EQ(mixM[l], 0) << "level " << l;
    const Atlas s = buildAtlas(tris, opts(AtlasKind::Uniform, 256, Magnification::Bilinear));
    const std::vector<long long> mixS = mipMixing(s, dualGraph(s.triangles));
    EXPECT_GT(mixS[6], 0);
}

// The partition's balance: the torus's 128 pairs in 16 x 16 texel cells of a 256 x 256
// atlas (a 16 x 16 grid of cells, half of it used): each quadtree node's four quadrants hold
// equal shares of its pairs, within one pair (METIS's 0.1 % imbalance, rounded), down to the
// 4 x 4-cell nodes; the non-uniform atlases' quadrants each at least 3/4 filled with cells
// (measured 83 % and up: power-of-two cells leave the rest).
TEST(Multires, PartitionIsBalanced) {
    const std::vector<AtlasTriangle> tris = meshTriangles(makeTorus(1.0, 0.4, 16, 8));
    const Atlas u = buildMultiresAtlas(tris, opts(AtlasKind::Uniform, 256, Magnification::Bilinear));
    ASSERT_EQ(u.mipCell, 16);
    for (int side = 128; side >= 64; side /= 2) {
        std::map<std::pair<int, int>, int> pairs;
        for (const Chart& c : u.charts) pairs[{c.cell.x / side, c.cell.y / side}] += 1;  // 2 charts a pair
        const int share = 2 * 128 / ((256 / side) * (256 / side));
        EXPECT_EQ(pairs.size(), size_t((256 / side) * (256 / side)));
        for (const auto& [q, n] : pairs) EXPECT_NEAR(n, share, 2) << "side " << side;
    }
    for (AtlasKind k : {AtlasKind::Area, AtlasKind::Length}) {
        const Atlas a = buildMultiresAtlas(tris, opts(k, 256, Magnification::Bilinear));
        std::map<std::pair<int, int>, long long> texels;
        for (size_t t = 0; t < a.charts.size(); ++t)
            if (!a.charts[t].second) {
                const int c = a.cellSize(a.charts[t].legs).x;
                texels[{a.charts[t].cell.x / 128, a.charts[t].cell.y / 128}] += (long long)c * c;
            }
        ASSERT_EQ(texels.size(), 4u);
        for (const auto& [q, n] : texels) EXPECT_GE(n, 128 * 128 * 3 / 4) << toString(k) << " " << n;
    }
}

// MIP levels average the written texels only; the trilinear lookup at one texel per pixel is
// the bilinear lookup of level 0, at two texels per pixel that of level 1; background texels
// carry no weight.
TEST(Multires, MipLevelsAndTrilinear) {
    Image img(2, 2, 4);
    const float c[4][4] = {{1, 0, 0, 1}, {9, 9, 9, 9}, {0, 1, 0, 1}, {0, 0, 1, 1}};
    for (int k = 0; k < 4; ++k)
        for (int ch = 0; ch < 4; ++ch) img.pixel(k % 2, k / 2)[ch] = c[k][ch];
    const std::vector<Image> lv = mipLevels(img, {0, -1, 1, 2});  // texel 1 is background
    ASSERT_EQ(lv.size(), 2u);
    EXPECT_FLOAT_EQ(lv[1].pixel(0, 0)[0], 1.f / 3);
    EXPECT_FLOAT_EQ(lv[1].pixel(0, 0)[1], 1.f / 3);
    EXPECT_FLOAT_EQ(lv[1].pixel(0, 0)[2], 1.f / 3);
    EXPECT_FLOAT_EQ(lv[1].pixel(0, 0)[3], 1.f);
    EXPECT_FLOAT_EQ(lv[1].pixel(0, 0)[4], 0.75f);  // 3 of 4 texels written
    const glm::dvec4 t0 = lookupTrilinear(lv, {0.75, 0.5}, {1, 0}, {0, 1});
    EXPECT_NEAR(t0.r, 1.0, 1e-6);  // texels 0 and 1 of level 0 at 3:1, but texel 1 is background
    const glm::dvec4 t2 = lookupTrilinear(lv, {0.5, 0.75}, {1, 0}, {0, 1});
    EXPECT_NEAR(t2.g, 0.75 * 0 + 0.25 * 1, 1e-6);  // texels 0 and 2 at 3:1
    const glm::dvec4 t1 = lookupTrilinear(lv, {0.75, 0.5}, {2, 0}, {0, 2});
    EXPECT_NEAR(t1.r, 1.0 / 3, 1e-6);
}

// Section 4.2's aim carried into the multiresolution atlas: on the teapot (triangle areas over
// two orders of magnitude) the weighted atlases spread the per-triangle relative scale r_j
// (Fig. 7) less than the uniform one: the standard deviation of lg r_j, measured 0.79 uniform,
// 0.58 area, 0.59 length at 512 x 512 bilinear (the strips: 0.79, 0.11, 0.43; power-of-two
// cells alone leave about 0.29). Their cells also fill the atlas where the uniform one's one
// power of two cannot: C 0.27 uniform, 0.66 area, 0.67 length.
double lgScaleSpread(const Atlas& a) {
    double m = 0, m2 = 0;
    const std::vector<double> r = triangleScales(a);
    for (double x : r) m += std::log2(x) / double(r.size()), m2 += std::log2(x) * std::log2(x) / double(r.size());
    return std::sqrt(std::max(0.0, m2 - m * m));
}

TEST(Multires, AreaWeightingEvensTheRelativeScale) {
    const std::vector<AtlasTriangle> tris = meshTriangles(makeTeapot(4));
    const Atlas u = buildMultiresAtlas(tris, opts(AtlasKind::Uniform, 512, Magnification::Bilinear));
    const Atlas area = buildMultiresAtlas(tris, opts(AtlasKind::Area, 512, Magnification::Bilinear));
    const Atlas length = buildMultiresAtlas(tris, opts(AtlasKind::Length, 512, Magnification::Bilinear));
    expectPacked(area);
    expectPacked(length);
    EXPECT_LT(lgScaleSpread(area), lgScaleSpread(u));
    EXPECT_LT(lgScaleSpread(length), lgScaleSpread(u));
    EXPECT_GT(coverage(area), 2 * coverage(u));
    EXPECT_GT(coverage(length), 2 * coverage(u));
}

}  // namespace
}  // namespace pst

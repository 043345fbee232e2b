#include "atlas_test_util.h"

namespace pst {
namespace {

using namespace atlas_test;

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

}  // namespace
}  // namespace pst

// The multiresolution atlas (section 4.3): pairs, power-of-two cells, MIP levels, METIS partition.
#include "atlas_test_util.h"

namespace pst {
namespace {

using namespace atlas_test;

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

// Meshed texture atlases for procedural solid texturing (Carr and Hart, "Real-Time Procedural
// Solid Texturing", section 4): every surface triangle gets its own chart image, an isosceles
// right triangle; pairs of them share a rectangular cell and cells are packed in horizontal
// strips. The atlas is filled once by the texture pipeline (one fragment per texel: the solid
// coordinates s at the texel centre and the Jacobian ds/du, ds/dv per texel) and the object is
// then drawn by ordinary texture mapping.
//
// Texel (i, j) covers [i, i+1) x [j, j+1) in texel units; j = 0 is the atlas image's top row.
//
// Seam-free rasterization (section 4.1, Fig. 4c; section 6.3 for bilinear): chart vertices sit
// on texel centres (the half-texel offset) and the cell leaves room for the texels the
// magnification filter reads beyond the hypotenuse (the overscan): with legs of L texels a
// triangle's footprint is the staircase { i' + j' <= L + m, 0 <= i', j' <= L } (m = 0 for
// nearest, 1 for bilinear, which also reads one texel past the legs' far ends), and a pair's
// cell is (L + 2 + 2m) x (L + 1) texels: for nearest one column more than the L + 1 square,
// as the paper says. The second triangle of a pair is the first rotated by 180 degrees.
// Chart vertices are pulled toward the chart's centroid by kChartInset texels so that samples
// on a chart edge (rounding of the interpolated u, v) stay on the chart's own texels.
//
// The "standard" layout (seamFree = false) is what the paper's Fig. 2 shows: pairs in L x L
// cells sharing the diagonal, vertices on texel corners, texels owned by the triangle holding
// their centre. It is kept to measure the seams that seam-free rasterization removes.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace pst {

enum class AtlasKind { Uniform, Area, Length };
bool parseAtlasKind(const std::string& name, AtlasKind* out);  // "uniform", "area", "length"
const char* toString(AtlasKind k);

// The magnification filter the atlas is seam-free for (it decides the footprints).
enum class Magnification { Nearest, Bilinear };
bool parseMagnification(const std::string& name, Magnification* out);  // "nearest", "bilinear"
const char* toString(Magnification m);

constexpr double kChartInset = 1e-6;

// One surface triangle: where it comes from, its positions and solid coordinates.
struct AtlasTriangle {
    int object = 0;                 // scene object
    int index = 0;                  // triangle of the object's mesh
    std::array<glm::dvec3, 3> x{};  // positions
    std::array<glm::dvec3, 3> s{};  // solid texture coordinates
    double area() const;            // A(x1, x2, x3)
    double longestEdge() const;
};

// The chart image of one triangle.
struct Chart {
    std::array<glm::dvec2, 3> u{};  // image of x[0], x[1], x[2] (texel units); u[0] is the right angle
    glm::ivec2 cell{0};             // the pair cell's top-left texel
    int legs = 0;                   // L: leg length in texels
    bool second = false;            // the pair's rotated triangle
};

struct AtlasOptions {
    AtlasKind kind = AtlasKind::Uniform;
    int size = 512;                 // H: the atlas is H x H texels
    Magnification magnification = Magnification::Bilinear;
    bool seamFree = true;
};

struct Atlas {
    AtlasOptions options;
    std::vector<AtlasTriangle> triangles;
    std::vector<Chart> charts;      // one per triangle, same order
    double eq3Edge = 0;             // eq. (3): the pair edge a = H / ceil(sqrt(M / 2)) texels, no overscan
    int stripCount = 0;
    int mipCell = 0;                // multiresolution atlas (multires.h): the largest a x a pair cell; 0 = strips

    int size() const { return options.size; }
    glm::ivec2 cellSize(int legs) const;  // a pair cell with legs L (width, height)
    // The texels chart t writes.
    std::vector<glm::ivec2> footprint(int t) const;
    // Owner of each texel (row-major, size x size): the triangle, or -1 for background.
    std::vector<int> owners() const;
    // Sets every chart's vertices from its cell, legs and side (after packing).
    void placeCharts();
};

// The smallest legs the packer gives a chart (texels).
constexpr int kMinLegs = 1;

// Refuses a degenerate triangle (mesh.h: zeroArea; InputError "triangle N of object K: ...":
// sceneTriangles skips them, so only a caller's own triangles can be) and rotates each
// triangle's vertices so that x[0], the chart's right angle, is opposite the longest edge.
void prepareTriangles(std::vector<AtlasTriangle>& triangles);

// Builds the atlas of `kind` over the triangles (section 4.1 uniform, 4.2 area and length
// weighted). Throws InputError ("--size: ...") when the triangles do not fit at kMinLegs, and
// ("triangle N of object K: ...") for a degenerate (zero-area) triangle.
Atlas buildAtlas(std::vector<AtlasTriangle> triangles, const AtlasOptions& options);

// Eq. (1): coverage C, the summed area of the chart images in a unit-square texture map.
double coverage(const Atlas& atlas);
// Eq. (2): relative scale S = sqrt(sum_j A(x_j) * (1/M) sum_j A(u_j) / A(x_j)).
double relativeScale(const Atlas& atlas);
// Each triangle's own relative scale sqrt(sum A(x) * A(u_j) / A(x_j)) (1 = ideal; Fig. 7).
std::vector<double> triangleScales(const Atlas& atlas);
// Fraction of the atlas's texels written by some chart.
double texelUse(const Atlas& atlas);

// One texel of the atlas as a fragment for the texture pipeline.
struct AtlasTexel {
    int x = 0, y = 0;
    int triangle = 0;
    glm::dvec3 s{0.0};      // solid coordinates at the texel centre (affine over the chart)
    glm::dvec3 dsdu{0.0};   // per texel along +u (columns)
    glm::dvec3 dsdv{0.0};   // per texel along +v (rows, downward)
};
std::vector<AtlasTexel> atlasTexels(const Atlas& atlas);

// The chart point of barycentric coordinates b on triangle t.
glm::dvec2 chartPoint(const Atlas& atlas, int t, const glm::dvec3& b);

// A texture lookup at chart point u (texel units) of triangle t, clamp-to-edge addressing.
// `touchedForeign` counts a texel read with a positive weight whose owner is not t.
struct AtlasLookup {
    glm::dvec4 rgba{0.0};
    bool touchedForeign = false;
};
// rgba: size x size x 4 floats, row-major (an Image's data); owners from Atlas::owners().
AtlasLookup lookupAtlas(const std::vector<float>& rgba, const std::vector<int>& owners, int size, int t,
                        const glm::dvec2& u, Magnification filter);

}  // namespace pst

// The multiresolution mesh atlas (section 4.3): triangles paired across shared edges, the pairs'
// dual graph partitioned hierarchically into a balanced quadtree with METIS (the
// multiconstraint partitioner the paper cites), and each quadtree node placed in its quadrant
// of the atlas, so that a MIP texel at level l (a 2^l x 2^l block) averages only triangles that
// are neighbours on the surface, up to the level the partition keeps contiguous.
//
// Uniform: every pair in an a x a cell (section 4.3 as written). Area- and length-weighted
// (section 4.2's weights carried over): each pair's cell a power of two sized by its weight, and
// the quadtree balances the cells' texels instead of their count (METIS vertex weights), so a
// node holds either one pair's cell or whole cells of neighbouring smaller pairs.
#pragma once

#include <vector>

#include "atlas.h"
#include "render.h"

namespace pst {

// The use of the mesh's edges (vertices welded by position, as in dualGraph): open edges, on
// one triangle only (a boundary: a plane's rim, an OBJ with a hole), and non-manifold edges, on
// more than two. The pairing and the dual graph of the multiresolution atlas take open edges (a
// triangle on the boundary has fewer neighbours, and may stay alone in its cell) but not
// non-manifold ones (a pair's shared edge must be the hypotenuse of exactly two charts); the
// strip atlases use no adjacency and take both.
struct MeshEdges {
    long long open = 0;          // edges on exactly one triangle
    long long nonManifold = 0;   // edges on three or more triangles
    int mostTriangles = 0;       // the most triangles on one non-manifold edge (0: none)
    int firstNonManifold = -1;   // a triangle (index into the list) on the first non-manifold edge, -1: none
};
MeshEdges meshEdges(const std::vector<AtlasTriangle>& triangles);

// The mesh's dual graph: triangles adjacent across an edge (vertices welded by position).
// Throws InputError ("--mip: ...") for an edge shared by more than two triangles.
std::vector<std::vector<int>> dualGraph(const std::vector<AtlasTriangle>& triangles);

// Builds the multiresolution atlas of options.kind (options.size a power of two; InputError
// "--size: ..." otherwise, or when the pairs do not fit at the smallest cell). Pair cells are
// a x a texels, a a power of two (one a for Uniform, per pair for Area and Length); charts are
// seam-free for options.magnification inside them (legs a - 2 - 2m).
Atlas buildMultiresAtlas(std::vector<AtlasTriangle> triangles, const AtlasOptions& options);

// MIP levels of a filled atlas, 5 channels: RGBA and the written share w of the texel. Level 0
// is `texels` (w = 1 where a chart wrote, else 0 and RGBA 0); each level averages the 2 x 2
// blocks of the one below weighted by w (background carries no weight), down to 1 x 1.
std::vector<Image> mipLevels(const Image& texels, const std::vector<int>& owners);

// For each MIP level, the number of its texels whose block holds triangles that do not form one
// connected patch of the dual graph (a texel averaging non-neighbours).
std::vector<long long> mipMixing(const Atlas& atlas, const std::vector<std::vector<int>>& dual);

// Trilinear lookup at chart point u with screen derivatives du/dx, du/dy (texel units): level
// lg max(|du/dx|, |du/dy|), each level's four texels weighted by bilinear weight times w.
glm::dvec4 lookupTrilinear(const std::vector<Image>& levels, const glm::dvec2& u, const glm::dvec2& dudx,
                           const glm::dvec2& dudy);

}  // namespace pst

// Triangle meshes for the paper's scenes: the Utah teapot from Newell's Bezier patches
// (tessellated coarsely, as the paper's prototype did), cube, sphere, torus, and large
// planes reaching the horizon. Positions are in object space; the solid texture coordinate
// of a vertex is its object-space position (the scene applies a texture-space affine map).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace pst {

struct Mesh {
    std::vector<glm::dvec3> positions;  // object space
    std::vector<glm::dvec3> texcoords;  // solid texture coordinates s = (s, t, r), one per vertex
    std::vector<std::array<uint32_t, 3>> triangles;  // counter-clockwise seen from outside

    // A copy with positions mapped by `model` and texcoords by `texture` (both affine).
    Mesh transformed(const glm::dmat4& model, const glm::dmat4& texture) const;
};

// The one rule for degenerate triangles (scenes/README.md, "Zero-area triangles"): a triangle
// whose area is at most 1e-12 of its longest edge squared (a repeated corner, three collinear
// corners, a sliver thinner than rounding) covers no sample and has no surface to texture.
// Render (rasterizer.cpp: scanMesh, rasterize) and the atlas (atlas_render.h: sceneTriangles)
// both skip it; the OBJ reader keeps it (it is valid OBJ). Relative, so scale-invariant.
inline bool zeroArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double e = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    return !(0.5 * glm::length(glm::cross(b - a, c - a)) > 1e-12 * e * e);
}
// The triangles of `m` zeroArea skips.
size_t zeroAreaTriangles(const Mesh& m);

// Utah teapot: Newell's 32 bicubic Bezier patches, each split into `subdiv` x `subdiv` quads
// (two triangles each). Object space: about 6.4 wide, 3.15 high, base at y = 0, spout toward +x.
Mesh makeTeapot(int subdiv = 4);
// Axis-aligned cube [-1, 1]^3.
Mesh makeCube();
// Unit sphere (radius 1) as a UV sphere.
Mesh makeSphere(int slices = 24, int stacks = 12);
// Torus around the y axis: major radius R, minor radius r.
Mesh makeTorus(double R = 1.0, double r = 0.4, int segmentsU = 32, int segmentsV = 16);
// Square in the plane y = 0, [-halfSize, halfSize]^2 in x and z, split into n x n quads
// (n > 1 keeps each triangle's depth range small), normal +y.
Mesh makePlane(double halfSize = 1.0, int n = 1);

}  // namespace pst

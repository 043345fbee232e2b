// A small scan-converting rasterizer like the paper's prototype (section 4.1): perspective
// camera, clipping at the near plane, triangle setup with edge functions, a z-buffer,
// perspective-correct solid texture coordinates s and the exact analytic Jacobian
// ds/dx, ds/dy at each sample point. No polygon-edge antialiasing (as in the paper).
//
// Screen convention: pixel (x, y) covers [x, x+1) x [y, y+1), y = 0 is the top row, the
// default sample point is the pixel centre (x + 0.5, y + 0.5). dsdy is the derivative with
// respect to y growing downward.
//
// Conventions (rasterizer.cpp):
// - Viewport: x_screen = (ndc.x + 1) / 2 * width, y_screen = (1 - ndc.y) / 2 * height.
// - Near clipping in homogeneous space at w = nearPlane (w = -z_eye); texcoords are carried
//   linearly, which is exact there. No far plane.
// - Fill rule: top-left. A sample exactly on an edge belongs to the triangle below a
//   horizontal edge and to the triangle right of any other edge. Edge functions are evaluated
//   with the edge's endpoints in a canonical order, so triangles sharing an edge get exactly
//   opposite values: no cracks and no double coverage, for any winding.
// - Depth: eye-space distance along the view axis, w = -z_eye, interpolated perspective-
//   correctly (1/w is affine in screen space). The z-buffer keeps the strictly nearer sample;
//   on an exact tie the fragment drawn first stays.
// - s = N / D with N = sum l_i s_i / w_i, D = sum l_i / w_i (l_i screen barycentrics), and
//   ds/dx = (N_x - s D_x) / D exactly at the sample point (likewise ds/dy).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh.h"

namespace pst {

struct Camera {
    glm::dvec3 eye = glm::dvec3(0.0, 0.0, 5.0);
    glm::dvec3 target = glm::dvec3(0.0);
    glm::dvec3 up = glm::dvec3(0.0, 1.0, 0.0);
    double fovyDeg = 40.0;     // vertical field of view
    double nearPlane = 0.05;   // triangles are clipped here
    int width = 512;
    int height = 512;

    glm::dmat4 view() const;
    // Projection with an infinite far plane, so planes reach the horizon.
    glm::dmat4 projection() const;
};

// One visible sample of one object: what the texture pipeline consumes.
struct Fragment {
    int x = 0, y = 0;      // pixel
    double depth = 0;      // eye-space distance along the view axis (z-buffer key, smaller is nearer)
    glm::dvec3 s{0.0};     // solid texture coordinate at the sample point
    glm::dvec3 dsdx{0.0};  // exact ds/dx at the sample point (per pixel)
    glm::dvec3 dsdy{0.0};  // exact ds/dy
    int object = -1;       // index of the object in the scene, -1 = empty
};

// Where in pixel (x, y) the sample lies, as an offset in [0, 1)^2.
using SampleOffset = std::function<glm::dvec2(int x, int y)>;
SampleOffset pixelCentre();

// Occluder test of rasterize(): a sample is discarded when the occluder covers the pixel and
//   depth >= occluderDepth * (1 - kOccluderRelEpsilon),
// i.e. it survives only if it is nearer than the occluder by more than this relative margin.
// So a surface identical to the occluder's (drawn again in a second pass) is always discarded,
// whatever rounding its second rasterization gets, while a shell slightly outside it (the same
// sphere 0.1% larger) is kept.
constexpr double kOccluderRelEpsilon = 1e-9;

// A z-buffered frame of fragments (one per pixel, the nearest).
class FragmentBuffer {
public:
    FragmentBuffer(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }
    const Fragment& at(int x, int y) const { return frags_[size_t(y) * width_ + x]; }
    Fragment& at(int x, int y) { return frags_[size_t(y) * width_ + x]; }
    bool covered(int x, int y) const { return at(x, y).object >= 0; }
    const std::vector<Fragment>& fragments() const { return frags_; }

private:
    int width_, height_;
    std::vector<Fragment> frags_;
};

// Rasterizes `mesh` (world space, with texcoords) as object `objectId` into `out`, keeping the
// nearest fragment per pixel. If `occluder` is given, a sample behind the occluder's fragment
// at that pixel is discarded (depth test against an earlier pass, without writing to it).
// Back faces are not culled (solid textures are two-sided).
void rasterize(const Camera& camera, const Mesh& mesh, int objectId, FragmentBuffer& out,
               const FragmentBuffer* occluder = nullptr,
               const SampleOffset& offset = pixelCentre());

// The scan conversion under rasterize(), without any depth test: calls `visit` once for each
// (triangle, pixel) whose sample point the triangle covers, with the fragment's depth, s and
// Jacobian (object = objectId). Near clipping, the fill rule and the sample points are those
// of rasterize(), so where triangles tile a surface (sharing edges and vertices), each
// sample the surface covers is visited exactly once: no cracks, no double hits.
using FragmentVisitor = std::function<void(const Fragment& frag)>;
void scanMesh(const Camera& camera, const Mesh& mesh, int objectId, const FragmentVisitor& visit,
              const SampleOffset& offset = pixelCentre());

}  // namespace pst

// Scan conversion: vertex transform, near clipping in homogeneous space, triangle setup with
// canonical edge functions (top-left fill rule), perspective-correct s and its exact Jacobian,
// z-buffer. The conventions are listed in rasterizer.h.
#include "rasterizer.h"

#include <algorithm>
#include <cmath>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec4.hpp>

namespace pst {

// ---- Camera -------------------------------------------------------------------------------

glm::dmat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::dmat4 Camera::projection() const {
    return glm::infinitePerspective(glm::radians(fovyDeg), double(width) / double(height),
                                    nearPlane);
}

SampleOffset pixelCentre() {
    return [](int, int) { return glm::dvec2(0.5, 0.5); };
}

FragmentBuffer::FragmentBuffer(int width, int height)
    : width_(width), height_(height), frags_(size_t(width) * size_t(height)) {
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            at(x, y).x = x;
            at(x, y).y = y;
        }
}

namespace {

// A vertex in clip space with its solid texture coordinate.
struct ClipVertex {
    glm::dvec4 clip;
    glm::dvec3 s;
};

// A vertex after the perspective divide: screen position and the quantities that are affine
// in screen space, 1/w and s/w.
struct ScreenVertex {
    glm::dvec2 p;
    double invW;
    glm::dvec3 sOverW;
};

// ---- Near clipping ------------------------------------------------------------------------

// Signed distance to the near plane in homogeneous space (w = -z_eye), >= 0 inside.
double nearDistance(const ClipVertex& v, double nearPlane) { return v.clip.w - nearPlane; }

// Point where edge (in, out) crosses the near plane. Always computed from the inside vertex,
// so the two triangles sharing a clipped edge create bit-identical vertices (no T-cracks).
ClipVertex intersectNear(const ClipVertex& in, double dIn, const ClipVertex& out, double dOut) {
    double t = dIn / (dIn - dOut);
    return {in.clip + t * (out.clip - in.clip), in.s + t * (out.s - in.s)};
}

// Sutherland-Hodgman against w >= nearPlane: the triangle becomes a polygon of 0, 3 or 4
// vertices written to `poly`; returns the count.
int clipNear(const ClipVertex tri[3], double nearPlane, ClipVertex poly[4]) {
    double d[3];
    for (int i = 0; i < 3; ++i) d[i] = nearDistance(tri[i], nearPlane);
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3;
        bool inI = d[i] >= 0.0, inJ = d[j] >= 0.0;
        if (inI) poly[n++] = tri[i];
        if (inI && !inJ) poly[n++] = intersectNear(tri[i], d[i], tri[j], d[j]);
        if (!inI && inJ) poly[n++] = intersectNear(tri[j], d[j], tri[i], d[i]);
    }
    return n;
}

// ---- Triangle setup -----------------------------------------------------------------------

// Perspective divide and viewport map.
ScreenVertex toScreen(const ClipVertex& v, int width, int height) {
    double invW = 1.0 / v.clip.w;
    double nx = v.clip.x / v.clip.w, ny = v.clip.y / v.clip.w;
    return {glm::dvec2((nx + 1.0) * 0.5 * width, (1.0 - ny) * 0.5 * height), invW,
            v.s * invW};
}

// Lexicographic order on screen points (y first, then x), used to orient edges canonically.
bool before(const glm::dvec2& a, const glm::dvec2& b) {
    return a.y < b.y || (a.y == b.y && a.x < b.x);
}

// Edge function of one triangle edge, evaluated with the edge's endpoints in canonical order
// a -> b (a before b): E(p) = sign * ((b - a) x (p - a)). `sign` (+-1) makes E > 0 inside the
// triangle. A neighbour sharing the edge uses the same a, b and the opposite sign, so its
// value is the exact negative: every sample is strictly inside one of them or on the edge.
// On the edge (E == 0) the top-left rule picks one: with a before b, dy > 0 or (dy == 0,
// dx > 0); the triangle owns the edge if it lies right of a non-horizontal edge (sign < 0,
// a left edge) or below a horizontal one (sign > 0, a top edge). At a shared vertex E is
// exactly 0 (dx * dy - dy * dx) as long as the compiler does not contract it into an FMA
// (x86-64 without -march=...: it cannot); the fill-rule tests would catch that.
struct Edge {
    double ax, ay, dx, dy, sign;
    bool ownsTies;

    Edge() = default;
    Edge(glm::dvec2 p, glm::dvec2 q, double orientation) {
        bool swapped = before(q, p);
        if (swapped) std::swap(p, q);
        ax = p.x;
        ay = p.y;
        dx = q.x - p.x;
        dy = q.y - p.y;
        sign = swapped ? -orientation : orientation;
        ownsTies = dy > 0.0 ? sign < 0.0 : sign > 0.0;
    }
    double operator()(double px, double py) const {
        return sign * (dx * (py - ay) - dy * (px - ax));
    }
    bool covers(double e) const { return e > 0.0 || (e == 0.0 && ownsTies); }
    // Screen-space slopes of E.
    double slopeX() const { return -sign * dy; }
    double slopeY() const { return sign * dx; }
};

// Everything about one (clipped) triangle that does not depend on the pixel.
struct TriangleSetup {
    Edge edge[3];  // edge k runs v_k -> v_k+1; E_k / area is the barycentric of v_k+2
    ScreenVertex v[3];
    double invArea;           // 1 / (twice the screen area)
    double dDdx, dDdy;        // slopes of D = sum l_i / w_i
    glm::dvec3 dNdx, dNdy;    // slopes of N = sum l_i s_i / w_i
    int x0, x1, y0, y1;       // pixel bounding box, clipped to the viewport (inclusive)
};

// Pixel range [lo, hi] whose sample points [x, x + 1) may fall in [minCoord, maxCoord].
void pixelRange(double minCoord, double maxCoord, int size, int& lo, int& hi) {
    lo = int(std::clamp(std::floor(minCoord), 0.0, double(size)));
    hi = int(std::clamp(std::floor(maxCoord), -1.0, double(size - 1)));
}

// Triangle setup; false if the triangle is degenerate on screen or misses the viewport.
bool setupTriangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c,
                   int width, int height, TriangleSetup& t) {
    t.v[0] = a;
    t.v[1] = b;
    t.v[2] = c;
    // Signed doubled area; its sign orients the edges (no back-face culling).
    glm::dvec2 e1 = b.p - a.p, e2 = c.p - a.p;
    double area2 = e1.x * e2.y - e1.y * e2.x;
    if (area2 == 0.0 || !std::isfinite(area2)) return false;
    double orientation = area2 > 0.0 ? 1.0 : -1.0;
    for (int k = 0; k < 3; ++k) t.edge[k] = Edge(t.v[k].p, t.v[(k + 1) % 3].p, orientation);
    t.invArea = 1.0 / std::abs(area2);

    // Constant slopes of the affine D and N: sum over vertices of (dl_i/dx) * value_i.
    t.dDdx = t.dDdy = 0.0;
    t.dNdx = t.dNdy = glm::dvec3(0.0);
    for (int k = 0; k < 3; ++k) {
        const ScreenVertex& opp = t.v[(k + 2) % 3];
        double lx = t.edge[k].slopeX() * t.invArea, ly = t.edge[k].slopeY() * t.invArea;
        t.dDdx += lx * opp.invW;
        t.dDdy += ly * opp.invW;
        t.dNdx += lx * opp.sOverW;
        t.dNdy += ly * opp.sOverW;
    }

    // Bounding box in pixels.
    double minX = std::min({a.p.x, b.p.x, c.p.x}), maxX = std::max({a.p.x, b.p.x, c.p.x});
    double minY = std::min({a.p.y, b.p.y, c.p.y}), maxY = std::max({a.p.y, b.p.y, c.p.y});
    pixelRange(minX, maxX, width, t.x0, t.x1);
    pixelRange(minY, maxY, height, t.y0, t.y1);
    return t.x0 <= t.x1 && t.y0 <= t.y1;
}

// ---- Scan conversion ----------------------------------------------------------------------

// Visits the samples of one set-up triangle. `accept(x, y, depth)` is the early depth test;
// `emit(fragment)` receives the accepted fragments with s and the Jacobian.
template <typename Accept, typename Emit>
void scanTriangle(const TriangleSetup& t, int objectId, const SampleOffset& offset,
                  Accept&& accept, Emit&& emit) {
    for (int y = t.y0; y <= t.y1; ++y)
        for (int x = t.x0; x <= t.x1; ++x) {
            // Coverage of the sample point by the fill rule.
            glm::dvec2 off = offset(x, y);
            double px = x + off.x, py = y + off.y;
            double e0 = t.edge[0](px, py), e1 = t.edge[1](px, py), e2 = t.edge[2](px, py);
            if (!(t.edge[0].covers(e0) && t.edge[1].covers(e1) && t.edge[2].covers(e2)))
                continue;
            // Perspective-correct interpolation: depth = 1 / D.
            double l2 = e0 * t.invArea, l0 = e1 * t.invArea, l1 = e2 * t.invArea;
            double D = l0 * t.v[0].invW + l1 * t.v[1].invW + l2 * t.v[2].invW;
            double depth = 1.0 / D;
            if (!accept(x, y, depth)) continue;
            // s = N / D and its exact Jacobian (N_x D - N D_x) / D^2 = (N_x - s D_x) / D.
            glm::dvec3 N = l0 * t.v[0].sOverW + l1 * t.v[1].sOverW + l2 * t.v[2].sOverW;
            Fragment f;
            f.x = x;
            f.y = y;
            f.depth = depth;
            f.s = N / D;
            f.dsdx = (t.dNdx - f.s * t.dDdx) / D;
            f.dsdy = (t.dNdy - f.s * t.dDdy) / D;
            f.object = objectId;
            emit(f);
        }
}

// Transforms, clips, sets up and scans every triangle of `mesh` in a width x height viewport.
template <typename Accept, typename Emit>
void scanMeshImpl(const Camera& camera, const Mesh& mesh, int objectId, const SampleOffset& offset,
                  int width, int height, Accept&& accept, Emit&& emit) {
    // Vertex transform, once per vertex (shared vertices stay bit-identical).
    glm::dmat4 viewProj = camera.projection() * camera.view();
    std::vector<ClipVertex> verts(mesh.positions.size());
    for (size_t i = 0; i < verts.size(); ++i)
        verts[i] = {viewProj * glm::dvec4(mesh.positions[i], 1.0), mesh.texcoords[i]};

    for (const auto& tri : mesh.triangles) {
        // A zero-area triangle (mesh.h: zeroArea, the rule shared with the atlas) covers nothing.
        if (zeroArea(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]])) continue;
        // Near clipping into a polygon of up to 4 vertices, fanned into 1 or 2 triangles.
        ClipVertex in[3] = {verts[tri[0]], verts[tri[1]], verts[tri[2]]};
        ClipVertex poly[4];
        int n = clipNear(in, camera.nearPlane, poly);
        ScreenVertex sv[4];
        for (int i = 0; i < n; ++i) sv[i] = toScreen(poly[i], camera.width, camera.height);
        for (int i = 1; i + 1 < n; ++i) {
            TriangleSetup t;
            if (setupTriangle(sv[0], sv[i], sv[i + 1], width, height, t))
                scanTriangle(t, objectId, offset, accept, emit);
        }
    }
}

}  // namespace

// ---- Public entry points ------------------------------------------------------------------

void rasterize(const Camera& camera, const Mesh& mesh, int objectId, FragmentBuffer& out,
               const FragmentBuffer* occluder, const SampleOffset& offset) {
    int width = std::min(camera.width, out.width());
    int height = std::min(camera.height, out.height());
    // Early depth test: z-buffer (strictly nearer wins), then the occluder of an earlier pass.
    auto accept = [&](int x, int y, double depth) {
        const Fragment& cur = out.at(x, y);
        if (cur.object >= 0 && !(depth < cur.depth)) return false;
        if (occluder && occluder->covered(x, y) &&
            depth >= occluder->at(x, y).depth * (1.0 - kOccluderRelEpsilon))
            return false;
        return true;
    };
    auto emit = [&](const Fragment& f) { out.at(f.x, f.y) = f; };
    scanMeshImpl(camera, mesh, objectId, offset, width, height, accept, emit);
}

void scanMesh(const Camera& camera, const Mesh& mesh, int objectId, const FragmentVisitor& visit,
              const SampleOffset& offset) {
    auto accept = [](int, int, double) { return true; };
    scanMeshImpl(camera, mesh, objectId, offset, camera.width, camera.height, accept, visit);
}

}  // namespace pst

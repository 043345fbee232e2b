// Simple meshes: cube, UV sphere, torus, subdivided plane. All use texcoords = object-space
// positions and counter-clockwise triangles seen from outside. The teapot is in teapot.cpp.
#include "mesh.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

namespace pst {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Appends a vertex whose texcoord is its position; returns its index.
uint32_t addVertex(Mesh& m, const glm::dvec3& p) {
    m.positions.push_back(p);
    m.texcoords.push_back(p);
    return uint32_t(m.positions.size() - 1);
}

// Appends triangle (a, b, c) unless two of its indices coincide (a collapsed pole).
void addTriangle(Mesh& m, uint32_t a, uint32_t b, uint32_t c) {
    if (a == b || b == c || c == a) return;
    m.triangles.push_back({a, b, c});
}

// Appends the quad a, b, c, d (counter-clockwise) as triangles (a, b, c) and (a, c, d).
void addQuad(Mesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    addTriangle(m, a, b, c);
    addTriangle(m, a, c, d);
}

}  // namespace

size_t zeroAreaTriangles(const Mesh& m) {
    size_t n = 0;
    for (const auto& t : m.triangles) n += zeroArea(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    return n;
}

// Mesh::transformed: positions by `model`, texcoords by `texture`. A mirroring model matrix
// (negative determinant) would turn the triangles clockwise, so their winding is reversed.
Mesh Mesh::transformed(const glm::dmat4& model, const glm::dmat4& texture) const {
    Mesh out;
    out.positions.reserve(positions.size());
    out.texcoords.reserve(texcoords.size());
    for (const glm::dvec3& p : positions)
        out.positions.push_back(glm::dvec3(model * glm::dvec4(p, 1.0)));
    for (const glm::dvec3& s : texcoords)
        out.texcoords.push_back(glm::dvec3(texture * glm::dvec4(s, 1.0)));
    out.triangles = triangles;
    if (glm::determinant(glm::dmat3(model)) < 0.0)
        for (auto& t : out.triangles) std::swap(t[1], t[2]);
    return out;
}

// Cube [-1, 1]^3: 8 shared corners (texcoords equal positions, so sharing is exact),
// 6 faces listed counter-clockwise seen from outside. Corner index = x + 2y + 4z (bits).
Mesh makeCube() {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        addVertex(m, glm::dvec3(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0));
    addQuad(m, 1, 3, 7, 5);  // +x
    addQuad(m, 0, 4, 6, 2);  // -x
    addQuad(m, 2, 6, 7, 3);  // +y
    addQuad(m, 0, 1, 5, 4);  // -y
    addQuad(m, 4, 5, 7, 6);  // +z
    addQuad(m, 0, 2, 3, 1);  // -z
    return m;
}

// UV sphere: longitude phi around +y, colatitude theta from the north pole. Each pole is
// one vertex; quads touching a pole collapse to one triangle.
Mesh makeSphere(int slices, int stacks) {
    Mesh m;
    uint32_t north = addVertex(m, glm::dvec3(0.0, 1.0, 0.0));
    for (int k = 1; k < stacks; ++k) {
        double theta = kPi * k / stacks;
        for (int j = 0; j < slices; ++j) {
            double phi = 2.0 * kPi * j / slices;
            addVertex(m, glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                    std::sin(theta) * std::sin(phi)));
        }
    }
    uint32_t south = addVertex(m, glm::dvec3(0.0, -1.0, 0.0));
    // Index of grid point (slice j, stack k), k = 0 and k = stacks being the poles.
    auto index = [&](int j, int k) -> uint32_t {
        if (k == 0) return north;
        if (k == stacks) return south;
        return 1 + uint32_t((k - 1) * slices + j % slices);
    };
    // Quad (phi_j, theta_k) .. (phi_j+1, theta_k+1): dP/dphi x dP/dtheta points outward.
    for (int k = 0; k < stacks; ++k)
        for (int j = 0; j < slices; ++j)
            addQuad(m, index(j, k), index(j + 1, k), index(j + 1, k + 1), index(j, k + 1));
    return m;
}

// Torus around the y axis: P(u, v) = ((R + r cos v) cos u, r sin v, (R + r cos v) sin u).
Mesh makeTorus(double R, double r, int segmentsU, int segmentsV) {
    Mesh m;
    for (int i = 0; i < segmentsU; ++i) {
        double u = 2.0 * kPi * i / segmentsU;
        for (int j = 0; j < segmentsV; ++j) {
            double v = 2.0 * kPi * j / segmentsV;
            double ring = R + r * std::cos(v);
            addVertex(m, glm::dvec3(ring * std::cos(u), r * std::sin(v), ring * std::sin(u)));
        }
    }
    auto index = [&](int i, int j) -> uint32_t {
        return uint32_t((i % segmentsU) * segmentsV + j % segmentsV);
    };
    // dP/dv x dP/du points away from the tube's centre line.
    for (int i = 0; i < segmentsU; ++i)
        for (int j = 0; j < segmentsV; ++j)
            addQuad(m, index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j));
    return m;
}

// Plane y = 0 over [-halfSize, halfSize]^2 in x and z, n x n quads, normal +y.
Mesh makePlane(double halfSize, int n) {
    Mesh m;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
            addVertex(m, glm::dvec3(-halfSize + 2.0 * halfSize * i / n, 0.0,
                                    -halfSize + 2.0 * halfSize * j / n));
    auto index = [&](int i, int j) -> uint32_t { return uint32_t(i * (n + 1) + j); };
    // (x_i, z_j) -> (x_i, z_j+1) -> (x_i+1, z_j+1): +z cross +x = +y.
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            addQuad(m, index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j));
    return m;
}

}  // namespace pst

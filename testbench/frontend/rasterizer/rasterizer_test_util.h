// Shared helpers of the rasterizer tests (rasterizer_test.cpp, rasterizer_fill_test.cpp): cameras,
// meshes, sample offsets, an independent ray-plane intersection.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/ext/matrix_projection.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "rasterizer.h"

namespace pst {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- Helpers ------------------------------------------------------------------------------

Camera makeCamera(glm::dvec3 eye, glm::dvec3 target, int width, int height, double fovy = 40.0) {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.width = width;
    c.height = height;
    c.fovyDeg = fovy;
    return c;
}

// A tilted plane (object space y = 0) and a general affine texture map of object space.
glm::dmat4 tiltedModel() {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(0.2, -0.3, 0.1));
    m = glm::rotate(m, glm::radians(25.0), glm::normalize(glm::dvec3(1.0, 0.3, -0.5)));
    return m;
}
glm::dmat4 skewTexture() {
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, -1.0, 0.5));
    t = glm::rotate(t, glm::radians(40.0), glm::normalize(glm::dvec3(0.2, 1.0, 0.4)));
    t = glm::scale(t, glm::dvec3(2.0, 0.7, 1.3));
    t[1][0] = 0.25;  // shear: column 1 (y), row 0 (x)
    return t;
}

// A plane z = 0 (object y = 0 rotated by +90 degrees about x) with texcoords = world position.
Mesh planeZ0(double halfSize, int n) {
    glm::dmat4 model = glm::rotate(glm::dmat4(1.0), kPi / 2.0, glm::dvec3(1.0, 0.0, 0.0));
    return makePlane(halfSize, n).transformed(model, model);
}

FragmentBuffer render(const Camera& cam, const Mesh& mesh,
                      const SampleOffset& off = pixelCentre()) {
    FragmentBuffer fb(cam.width, cam.height);
    rasterize(cam, mesh, 0, fb, nullptr, off);
    return fb;
}

SampleOffset shifted(double dx, double dy) {
    return [=](int, int) { return glm::dvec2(0.5 + dx, 0.5 + dy); };
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double maxAbs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// World-space ray through screen point (sx, sy), built from the camera's definition by hand
// (not from view()/projection()): direction with unit component along the view axis.
glm::dvec3 rayDirection(const Camera& cam, double sx, double sy) {
    glm::dvec3 f = glm::normalize(cam.target - cam.eye);
    glm::dvec3 r = glm::normalize(glm::cross(f, cam.up));
    glm::dvec3 u = glm::cross(r, f);
    double tanHalf = std::tan(cam.fovyDeg * kPi / 360.0);
    double aspect = double(cam.width) / cam.height;
    double nx = 2.0 * sx / cam.width - 1.0, ny = 1.0 - 2.0 * sy / cam.height;
    return f + (nx * tanHalf * aspect) * r + (ny * tanHalf) * u;
}

// Ray parameter t (= eye-space depth, as the direction has unit view-axis component) where
// the ray through pixel centre (x, y) meets the plane through p0 with normal n.
double rayPlane(const Camera& cam, int x, int y, glm::dvec3 p0, glm::dvec3 n) {
    glm::dvec3 d = rayDirection(cam, x + 0.5, y + 0.5);
    return glm::dot(p0 - cam.eye, n) / glm::dot(d, n);
}

}  // namespace
}  // namespace pst

// The texture function (paper eq. 1, 3-4) and its filter width (section 3.2, eq. 10-12).
#include "texture.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace pst {

glm::dmat4 Quadric::matrix() const {
    // Eq. 4; symmetric, so GLM's column-major layout reads the same.
    return glm::dmat4(A, B, C, D,  //
                      B, E, F, G,  //
                      C, F, H, I,  //
                      D, G, I, J);
}

double Quadric::value(const glm::dvec3& s) const {
    // Eq. 3.
    const double x = s.x, y = s.y, z = s.z;
    return A * x * x + 2 * B * x * y + 2 * C * x * z + 2 * D * x + E * y * y + 2 * F * y * z +
           2 * G * y + H * z * z + 2 * I * z + J;
}

glm::dvec3 Quadric::gradient(const glm::dvec3& s) const {
    // 2 (Q [s 1])_xyz: eq. 11 with the linear terms D, G, I kept (DESIGN.md section 3).
    return 2.0 * glm::dvec3(A * s.x + B * s.y + C * s.z + D,  //
                            B * s.x + E * s.y + F * s.z + G,  //
                            C * s.x + F * s.y + H * s.z + I);
}

bool parseGradNorm(const std::string& name, GradNorm* out) {
    if (name == "euclid") *out = GradNorm::Euclid;
    else if (name == "max_half_min") *out = GradNorm::MaxHalfMin;
    else if (name == "l1") *out = GradNorm::L1;
    else return false;
    return true;
}

const char* toString(GradNorm v) {
    switch (v) {
    case GradNorm::Euclid: return "euclid";
    case GradNorm::MaxHalfMin: return "max_half_min";
    case GradNorm::L1: return "l1";
    }
    return "?";
}

double evalF(const Texture& tex, const glm::dvec3& s, glm::dvec3* gradS) {
    // Eq. 1: f = q(s) + sum_i a_i n(M_i s + o_i);
    // eq. 10, 12: grad_s f = grad q + sum_i a_i M_i^T grad n.
    double f = tex.quadric.value(s);
    glm::dvec3 g = gradS ? tex.quadric.gradient(s) : glm::dvec3(0.0);
    for (const Octave& o : tex.octaves) {
        glm::dvec3 gn;
        f += o.amplitude * noise(o.M * s + o.offset, tex.noise, gradS ? &gn : nullptr);
        if (gradS) g += o.amplitude * (glm::transpose(o.M) * gn);
    }
    if (gradS) *gradS = g;
    return f;
}

double filterWidth(const glm::dvec3& gradS, const glm::dvec3& dsdx, const glm::dvec3& dsdy,
                   GradNorm norm) {
    // grad_x f = (grad_s f)^T ds/dx (section 3.2), then its norm.
    const double gx = std::abs(glm::dot(gradS, dsdx)), gy = std::abs(glm::dot(gradS, dsdy));
    switch (norm) {
    case GradNorm::Euclid: return std::sqrt(gx * gx + gy * gy);
    case GradNorm::MaxHalfMin: return std::max(gx, gy) + 0.5 * std::min(gx, gy);
    case GradNorm::L1: return gx + gy;
    }
    return 0.0;
}

TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy) {
    return shade(tex, s, dsdx, dsdy, tex.filter);
}

TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy, FilterKind filter) {
    TextureSample r;
    r.f = evalF(tex, s, &r.gradS);
    r.filterWidth = filterWidth(r.gradS, dsdx, dsdy, tex.norm);
    r.rgba = tex.clut.filter(r.f, r.filterWidth, filter);  // eq. 9
    return r;
}

}  // namespace pst

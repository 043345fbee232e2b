// The texture function of Hart et al. 1999 in double precision (the reference model):
//   f(s) = q(s) + sum_i a_i n(T_i s)                       (eq. 1)
//   grad_s f = 2 (Q [s 1])_xyz + sum_i a_i M_i^T grad n    (eq. 10-12, linear terms kept)
//   filterWidth w = |(grad_s f . dsdx, grad_s f . dsdy)|   (section 3.2)
//   colour = box filter of the colour map over [f - w/2, f + w/2] (eq. 9)
#pragma once

#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "colormap.h"
#include "noise.h"

namespace pst {

// q(s,t,r) = A s^2 + 2B st + 2C sr + 2D s + E t^2 + 2F tr + 2G t + H r^2 + 2I r + J  (eq. 3)
struct Quadric {
    double A = 0, B = 0, C = 0, D = 0, E = 0, F = 0, G = 0, H = 0, I = 0, J = 0;

    glm::dmat4 matrix() const;  // the symmetric Q of eq. 4
    double value(const glm::dvec3& s) const;
    glm::dvec3 gradient(const glm::dvec3& s) const;  // 2 (Q [s 1])_xyz
};

// One noise term a_i n(T_i s), T_i s = M s + offset.
struct Octave {
    double amplitude = 0;
    glm::dmat3 M = glm::dmat3(1.0);  // column-major (GLM): M[col][row]
    glm::dvec3 offset = glm::dvec3(0.0);
};

// How |grad_x f| is formed from its two components (gx, gy).
enum class GradNorm {
    Euclid,   // sqrt(gx^2 + gy^2), the paper's |grad f|
    MaxHalfMin,  // max + min/2 (a cheap hardware approximation)
    L1,       // |gx| + |gy| (the paper's zone-plate example, section 3.4)
};
bool parseGradNorm(const std::string& name, GradNorm* out);  // "euclid", "max_half_min", "l1"
const char* toString(GradNorm v);

struct Texture {
    std::string name;
    Quadric quadric;
    std::vector<Octave> octaves;
    NoiseOptions noise;
    ColorMap clut;
    FilterKind filter = FilterKind::Sat;
    GradNorm norm = GradNorm::Euclid;
    // "FILE:LINE: FIELD" of the noise basis in its scene file (set by the parser when the basis
    // is given), so a consumer that cannot do the basis (the hardware profiles) names it.
    std::string basisSource;
};

// The per-fragment result of the texture pipeline.
struct TextureSample {
    double f = 0;                           // colour index (eq. 1)
    glm::dvec3 gradS = glm::dvec3(0.0);     // grad_s f
    double filterWidth = 0;                 // w in colour-index units
    glm::dvec4 rgba = glm::dvec4(0.0);      // filtered colour
};

// f and grad_s f only.
double evalF(const Texture& tex, const glm::dvec3& s, glm::dvec3* gradS = nullptr);

// The filter width from grad_s f and the Jacobian columns dsdx, dsdy.
double filterWidth(const glm::dvec3& gradS, const glm::dvec3& dsdx, const glm::dvec3& dsdy,
                   GradNorm norm);

// The whole pipeline for one fragment with the texture's own filter kind.
TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy);
// Same with the filter kind given (e.g. FilterKind::None for the unfiltered image).
TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy, FilterKind filter);

}  // namespace pst

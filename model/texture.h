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
#include "golden/contract.h"
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

// How |grad_x f| is formed from its two components (gx, gy): GradNorm, generated from
// rtl/contract.toml's filter.norm into golden/contract.h: Euclid sqrt(gx^2 + gy^2), the paper's
// |grad f|; MaxHalfMin max + min/2 (a cheap hardware approximation); L1 |gx| + |gy| (the
// paper's zone-plate example, section 3.4).
bool parseGradNorm(const std::string& name, GradNorm* out);  // "euclid", "max_half_min", "l1"
const char* toString(GradNorm v);

// Bandlimited octaves (scenes/README.md has the measured table): off (the paper), footprint
// (octaveFootprint: each term keeps the standard deviation the pixel's box average of it has
// across the footprint's minor edge and is the mean of up to kFootprintSamples point samples along
// its major edge, so it follows the pixel's own average from frame to frame; the filter width
// grows to sqrt(w^2 + 12 sigma^2), sigma the removed terms' standard deviation: a box of width
// sqrt(12) sigma has the variance of what was removed), isotropic (the hardware's variant,
// octaveIsotropic: the term and its gradient scaled by alpha toward 0, no widening). With basis
// subband, isotropic is the subband filter's isotropic Gaussian (as wide as the footprint's major
// axis) and anisotropic its eq. 4-7 Gaussian from the footprint's Jacobian (subband.h;
// anisotropic needs that basis).
struct Texture;
enum class Bandlimit { Off, Footprint, Isotropic, Anisotropic };
// "off", "footprint", "isotropic", "anisotropic"
bool parseBandlimit(const std::string& name, Bandlimit* out);
const char* toString(Bandlimit v);
// Why texture tex cannot take bandlimit b ("" if it can): anisotropic needs basis subband.
std::string bandlimitUnsupported(const Texture& tex, Bandlimit b);

// Mean and standard deviation of a noise basis over space (sampled once per variant).
struct NoiseMoments {
    double mean = 0, sd = 0;
};
NoiseMoments noiseMoments(const NoiseOptions& opt);

struct Texture {
    std::string name;
    Quadric quadric;
    std::vector<Octave> octaves;
    NoiseOptions noise;
    ColorMap clut;
    FilterKind filter = FilterKind::Sat;
    GradNorm norm = GradNorm::Euclid;
    // Bandlimited octaves (beyond the paper; isotropic also in the hardware): in shade(), each
    // octave's term and its share of grad_s f as the pixel can show them (evalFBandlimited).
    // Point samples (evalF) are unchanged.
    Bandlimit bandlimit = Bandlimit::Off;
    // "FILE:LINE: FIELD" of the noise basis in its scene file (set by the parser when the basis
    // is given), so a consumer that cannot do the basis (the hardware profiles) names it.
    std::string basisSource;
    // "FILE:LINE: FIELD" of the colour map's size (set by the scene parser), for the same reason.
    std::string clutSource;
    // The colour map is a ramp (colormap.interp = "linear", the scene parser's default: linear
    // between its keys) rather than steps; false for a table given any other way. The hardware
    // refuses the colour-table MIP map on a ramp for some bases (hardwareUnsupported,
    // docs/HARDWARE.md unit 6 "Refused combinations"). clutInterpSource: "FILE:LINE: FIELD" of it.
    bool clutRamp = false;
    std::string clutInterpSource;
    // "FILE:LINE: FIELD" of bandlimit when the scene gives it (set by the scene parser), the same.
    std::string bandlimitSource;
    // The filter-width cap (issue 44 part 2; scene key width_cap, `--width-cap`, variant "+cap"):
    // w = min(w, widthCap(tex)) in shade(), as the hardware's filter.width_cap unit does.
    bool widthCap = false;
    std::string widthCapSource;   // "FILE:LINE: FIELD" when the scene gave it
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

// The variance of the basis averaged over a segment nu lattice cells long (random direction and
// place), over the basis's variance: 1 at nu = 0, about c / nu for large nu. Sampled once per basis
// at quarter octaves of nu in [1/16, 16] (Monte Carlo: 1024 segments each, 8 points per cell, at
// least 16) and interpolated in lg nu; 1 below, the last value times 16 / nu above.
double noiseBoxGain(const NoiseOptions& opt, double nu);

// Bandlimit::Isotropic, the hardware's variant (rtl/octave/pst_octave_fade.sv): each edge's footprint in
// lattice cells bounded by nu = ||M||_2 footprintNorm(edge) (one per-octave register, lg ||M||_2,
// instead of |M edge|'s 9 products), clamped to [2^kIsoLgLo, 2^kIsoLgHi] (the fade table's range),
// and alpha = sqrt(g(nu_x)) sqrt(g(nu_y)), g = noiseBoxGain (the share of the term's standard
// deviation that survives the pixel's box average, the two edges averaged independently): the
// term a alpha n and its gradient
// a alpha M^T grad n (toward 0, not toward the basis's mean; no widening).
constexpr double kIsoLgLo = -3.0, kIsoLgHi = 5.0;
double octaveIsotropic(const Octave& o, const NoiseOptions& opt, const glm::dvec3& dsdx, const glm::dvec3& dsdy);
// The spectral norm ||M||_2 (largest singular value).
double spectralNorm(const glm::dmat3& M);
// The hardware's cheap length of a Jacobian column: max + 3/8 (mid + min) of |v_k| (within
// -3 % .. +13.2 % of |v|).
double footprintNorm(const glm::dvec3& v);

// Bandlimit::Footprint's term of octave o at s: with nu = |M dsdx|, |M dsdy| the footprint's edges
// in lattice cells, K = clamp(ceil(2 nu_major), 1, kFootprintSamples) samples n_k at s + ((k + 1/2) / K
// - 1/2) times the major edge's Jacobian column, v = their mean; the term is
// mean + w (v - mean) with w = sqrt(g(nu_minor)) sqrt(g(nu_major) / gK), gK = g(nu_major) when the
// samples are at most half a cell apart, else max(g(nu_major), 1 / K) (nearly independent samples),
// g = noiseBoxGain; *grad: w times the mean of the samples' M^T grad n; *keptVar: the share of the
// term's variance kept, g(nu_major) g(nu_minor).
constexpr int kFootprintSamples = 16;
double octaveFootprint(const Octave& o, const NoiseOptions& opt, const glm::dvec3& s, const glm::dvec3& dsdx,
                       const glm::dvec3& dsdy, glm::dvec3* grad, double* keptVar);

// f and grad_s f of the bandlimited texture: every octave's term as tex.bandlimit filters it
// (octaveFootprint, octaveIsotropic, the subband filters; off: the point sample, as evalF);
// fadedSd: the standard deviation of what was removed (0 for off and the hardware's isotropic).
double evalFBandlimited(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                        const glm::dvec3& dsdy, glm::dvec3* gradS = nullptr, double* fadedSd = nullptr);
// Whether the bandlimit widens the colour-table filter by the removed spread: footprint and the
// subband basis's filters (isotropic, anisotropic).
bool bandlimitWidens(const Texture& tex);
// The filter width of the bandlimited texture: filterWidth of its gradient, widened by fadedSd
// when bandlimitWidens.
double bandlimitedWidth(const Texture& tex, const glm::dvec3& gradS, const glm::dvec3& dsdx,
                        const glm::dvec3& dsdy, double fadedSd);

// The filter-width cap (issue 44 part 2), colour-index units: the width of the box whose variance
// is the noise's whole variance, sqrt(12 sum_{i < octaves} a_i^2) sd(n) (sd of the basis over
// space, noiseMoments; the octaves taken as independent), the most f can spread inside any pixel
// when f is the noise alone: a box wider than that reaches past the values f takes (eq. 9's
// linear f is wrong there). Infinite (no cap) when the quadric is not constant (any of A..I
// non-zero): q's spread in a pixel is |grad q . J| (exact for the linear terms) and grows with
// the footprint without bound, so no per-texture constant bounds f's spread (capping would cut
// q's own, exactly known, width and alias its rings). octaves < 0: every octave of the texture.
double widthCapOf(const Texture& tex, int octaves = -1);
// Whether q(s) varies over space (a coefficient A..I is not 0).
bool quadricVaries(const Quadric& q);
// The cap applied: *w = min(*w, widthCapOf(tex)), the footprint's two widths *wxy (if given)
// scaled by the same factor.
void capWidth(const Texture& tex, double* w, glm::dvec2* wxy = nullptr);

// The filter width from grad_s f and the Jacobian columns dsdx, dsdy.
double filterWidth(const glm::dvec3& gradS, const glm::dvec3& dsdx, const glm::dvec3& dsdy,
                   GradNorm norm);

// The pixel footprint's two widths (|grad_s f . dsdx|, |grad_s f . dsdy|), colour-index units:
// what FilterKind::Trapezoid filters over.
glm::dvec2 footprintWidths(const glm::dvec3& gradS, const glm::dvec3& dsdx, const glm::dvec3& dsdy);

// The footprint widened by the removed terms' spread when bandlimitWidens (both widths scaled so
// that wx^2 + wy^2 grows by 12 fadedSd^2, as bandlimitedWidth's euclidean w); unchanged otherwise.
glm::dvec2 bandlimitedFootprint(const Texture& tex, const glm::dvec2& wxy, double fadedSd);

// The filtered colour of f by `kind`: the trapezoid over the footprint widths wxy (the box of
// width w if both are 0), every other kind over the width w.
glm::dvec4 filterColour(const ColorMap& clut, double f, double w, const glm::dvec2& wxy, FilterKind kind);

// The whole pipeline for one fragment with the texture's own filter kind (bandlimited octaves
// when tex.bandlimit).
TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy);
// Same with the filter kind given (e.g. FilterKind::None for the unfiltered image).
TextureSample shade(const Texture& tex, const glm::dvec3& s, const glm::dvec3& dsdx,
                    const glm::dvec3& dsdy, FilterKind filter);

}  // namespace pst

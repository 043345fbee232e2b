// The colour map c(f) and its box filters (paper section 2.1.1 eq. 2 and section 3.3,
// eq. 9 and 13-15). Index convention: a colour index f in [0, 1) maps to the table
// coordinate u = f * N; entry i covers u in [i, i + 1) (piecewise-constant map), so the
// point sample is clut[floor(u)] taken mod N or clamped to [0, N-1].
//
// Filters (W = w N is the window width in entries):
// - Box: exact mean of the extended piecewise-constant map over [u - W/2, u + W/2].
// - Sat: the paper's integer-index form: lo = floor(u - W/2), hi = floor(u + W/2); the
//   result is (sum of entries lo+1..hi) / (hi - lo), i.e. (csat[hi] - csat[lo]) / (hi - lo)
//   with csat[-1] = 0, and entry hi when hi == lo. In mod mode W >= N gives the table mean;
//   in clamp mode the entries past either end count as clut[0] / clut[N-1] at any W.
// - Mip: level L = floor(lg W) (clamped to [0, lg N]), entry floor(u / 2^L) of that level
//   extended by mod/clamp at its own size N >> L; W <= 1 gives the point sample. Blended:
//   lerp to level L+1 with t = lg W - L.
// - Trapezoid (beyond the paper; filterTrapezoid): the exact mean of the extended map over the
//   distribution of f inside a square pixel when f is linear there, f + X + Y with X, Y uniform
//   of widths Wx = |g_x| N and Wy = |g_y| N: the box of width Wx convolved with the box of width
//   Wy, a trapezoid (a triangle when Wx = Wy). Its variance (Wx^2 + Wy^2) / 12 is the box's of
//   width sqrt(Wx^2 + Wy^2) (the paper's euclidean w); the shape differs. Given one width only
//   (filter(f, w, Trapezoid)) it is the box.
// Robustness: u = f N is clamped to [-2^52, 2^52] (NaN -> 0) and W to [0, 2^53] before any
// floor, so no input is UB; w <= 0 or NaN gives the point sample. An empty
// (default-constructed) map returns transparent black (0, 0, 0, 0).
#pragma once

#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace pst {

enum class WrapMode {
    Mod,    // index taken modulo N (eq. 2 "mod")
    Clamp,  // index clamped to [0, N-1] (eq. 2 "clamp")
};

enum class FilterKind {
    None,        // point sample clut[floor(fN)]
    MipNearest,  // colour-table MIP map, level floor(lg(wN)) (section 3.3.1)
    MipLinear,   // same, blended linearly with the next coarser level
    Sat,         // summed-area colour table with the paper's integer indices (eq. 13-15)
    Box,         // exact integral of the piecewise-constant map over [f - w/2, f + w/2]
    Trapezoid,   // exact integral over the pixel footprint's distribution of f (filterTrapezoid)
};

bool parseWrapMode(const std::string& name, WrapMode* out);      // "mod", "clamp"
// "none", "mip", "mip_linear", "sat", "box", "trapezoid"
bool parseFilterKind(const std::string& name, FilterKind* out);
const char* toString(WrapMode v);
const char* toString(FilterKind v);

class ColorMap {
public:
    ColorMap() = default;
    // entries.size() must be a power of two >= 1.
    ColorMap(std::vector<glm::dvec4> entries, WrapMode wrap);

    int size() const { return static_cast<int>(clut_.size()); }
    WrapMode wrap() const { return wrap_; }
    const std::vector<glm::dvec4>& entries() const { return clut_; }

    // Entry i of the map extended past [0, N) by mod or clamp.
    const glm::dvec4& at(long long i) const;

    // Point sample at colour index f (eq. 2).
    glm::dvec4 sample(double f) const;

    // Box filter of width w (colour-index units, so w * N entries) centred at f, by the
    // given kind. w <= 0 gives the point sample for every kind.
    glm::dvec4 filter(double f, double w, FilterKind kind) const;

    glm::dvec4 filterMip(double f, double w, bool blend) const;  // section 3.3.1
    glm::dvec4 filterSat(double f, double w) const;              // section 3.3.2, every case
    glm::dvec4 filterBox(double f, double w) const;              // exact integral
    // Exact mean over the trapezoid of the box widths wx, wy (colour-index units, any order);
    // wx = wy = 0 gives the point sample, one of them 0 the box of the other.
    glm::dvec4 filterTrapezoid(double f, double wx, double wy) const;
    // The paper's alternative to the case analysis: one 3N-long summed table over entry
    // indices -N..2N-1 of the extended map (see sat3N()); same result as filterSat.
    glm::dvec4 filterSat3N(double f, double w) const;

    // MIP level L (0 = full table, lg N = one entry) : N >> L entries, each the mean of
    // 2^L neighbours of level 0.
    const std::vector<glm::dvec4>& mipLevel(int level) const { return mip_[level]; }
    int mipLevels() const { return static_cast<int>(mip_.size()); }
    // csat[i] = sum_{j<=i} clut[j] (eq. 13).
    const std::vector<glm::dvec4>& sat() const { return csat_; }
    // sat3N()[k + N] = sum of extended entries 0..k for k >= 0, minus the sum of entries
    // k+1..-1 for k < 0 (so the value at k = -1 is 0), k in [-N, 2N-1].
    const std::vector<glm::dvec4>& sat3N() const { return csat3_; }

private:
    // J(s, e, b) = integral over t in [s, e] of c(t) (b - t) dt for the extended map, for
    // e - s < N (mod) or any span (clamp); walks the entries inside the table.
    glm::dvec4 rampIntegral(double s, double e, double b) const;

    std::vector<glm::dvec4> clut_;
    std::vector<std::vector<glm::dvec4>> mip_;
    std::vector<glm::dvec4> csat_;
    std::vector<glm::dvec4> csat3_;
    WrapMode wrap_ = WrapMode::Mod;
};

}  // namespace pst

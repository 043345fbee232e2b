// Colour map and its box filters: paper section 2.1.1 (eq. 2) and section 3.3 (eq. 9, 13-15).
// Conventions are in colormap.h.
#include "colormap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/common.hpp>

namespace pst {

bool parseWrapMode(const std::string& name, WrapMode* out) {
    if (name == "mod") *out = WrapMode::Mod;
    else if (name == "clamp") *out = WrapMode::Clamp;
    else return false;
    return true;
}

bool parseFilterKind(const std::string& name, FilterKind* out) {
    if (name == "none") *out = FilterKind::None;
    else if (name == "mip") *out = FilterKind::MipNearest;
    else if (name == "mip_linear") *out = FilterKind::MipLinear;
    else if (name == "sat") *out = FilterKind::Sat;
    else if (name == "box") *out = FilterKind::Box;
    else if (name == "trapezoid") *out = FilterKind::Trapezoid;
    else return false;
    return true;
}

const char* toString(WrapMode v) { return v == WrapMode::Mod ? "mod" : "clamp"; }

const char* toString(FilterKind v) {
    switch (v) {
    case FilterKind::None: return "none";
    case FilterKind::MipNearest: return "mip";
    case FilterKind::MipLinear: return "mip_linear";
    case FilterKind::Sat: return "sat";
    case FilterKind::Box: return "box";
    case FilterKind::Trapezoid: return "trapezoid";
    }
    return "?";
}

namespace {

constexpr double kMaxCoord = 4503599627370496.0;  // 2^52: |u| bound, floor fits long long
constexpr double kMaxWidth = 9007199254740992.0;  // 2^53: W bound

// u = f N clamped to a safe range (NaN -> 0).
double tableCoord(double f, int n) {
    double u = f * n;
    if (std::isnan(u)) return 0.0;
    return std::clamp(u, -kMaxCoord, kMaxCoord);
}

// W = w N clamped to [0, 2^53] (NaN -> 0).
double tableWidth(double w, int n) {
    double W = w * n;
    if (!(W > 0.0)) return 0.0;
    return std::min(W, kMaxWidth);
}

long long floorLL(double x) { return static_cast<long long>(std::floor(x)); }

long long floorDiv(long long a, long long b) {
    long long q = a / b;
    return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

const glm::dvec4 kBlack(0.0);

}  // namespace

ColorMap::ColorMap(std::vector<glm::dvec4> entries, WrapMode wrap)
    : clut_(std::move(entries)), wrap_(wrap) {
    const size_t n = clut_.size();
    if (n == 0 || (n & (n - 1)) != 0 || n > (size_t(1) << 30))
        throw std::invalid_argument("ColorMap: size must be a power of two >= 1");
    const long long N = static_cast<long long>(n);

    // Summed-area colour table, eq. 13: csat[i] = csat[i-1] + clut[i].
    csat_.resize(n);
    glm::dvec4 acc(0.0);
    for (size_t i = 0; i < n; ++i) csat_[i] = acc += clut_[i];

    // 3N-long table over k = -N..2N-1 of the extended map (section 3.3.2, last paragraph).
    csat3_.assign(3 * n, glm::dvec4(0.0));
    acc = glm::dvec4(0.0);
    for (long long k = 0; k < 2 * N; ++k) csat3_[k + N] = acc += at(k);
    acc = glm::dvec4(0.0);
    for (long long k = -1; k >= -N; --k) {
        csat3_[k + N] = acc;  // minus the sum of entries k+1..-1
        acc -= at(k);
    }

    // Colour-table MIP map (section 3.3.1): level L averages pairs of level L-1.
    mip_.push_back(clut_);
    while (mip_.back().size() > 1) {
        const auto& prev = mip_.back();
        std::vector<glm::dvec4> next(prev.size() / 2);
        for (size_t j = 0; j < next.size(); ++j) next[j] = 0.5 * (prev[2 * j] + prev[2 * j + 1]);
        mip_.push_back(std::move(next));
    }
}

const glm::dvec4& ColorMap::at(long long i) const {
    if (clut_.empty()) return kBlack;
    const long long N = size();
    if (wrap_ == WrapMode::Mod) return clut_[((i % N) + N) % N];
    return clut_[std::clamp(i, 0LL, N - 1)];
}

glm::dvec4 ColorMap::sample(double f) const {
    // Eq. 2 with the floor convention: entry i covers u in [i, i + 1).
    return at(floorLL(tableCoord(f, size())));
}

glm::dvec4 ColorMap::filter(double f, double w, FilterKind kind) const {
    switch (kind) {
    case FilterKind::None: return sample(f);
    case FilterKind::MipNearest: return filterMip(f, w, false);
    case FilterKind::MipLinear: return filterMip(f, w, true);
    case FilterKind::Sat: return filterSat(f, w);
    case FilterKind::Box: return filterBox(f, w);
    case FilterKind::Trapezoid: return filterBox(f, w);  // one width: the box
    }
    return sample(f);
}

// ---- colour-table MIP map (section 3.3.1) -------------------------------------------------

glm::dvec4 ColorMap::filterMip(double f, double w, bool blend) const {
    if (clut_.empty()) return kBlack;
    const double W = tableWidth(w, size());
    if (W <= 1.0) return sample(f);  // finer than one entry: level 0 point sample
    const long long i = floorLL(tableCoord(f, size()));
    const int lgN = mipLevels() - 1;

    // Entry floor(u / 2^L) of level L, extended by mod/clamp at that level's size.
    auto level = [&](int L) -> const glm::dvec4& {
        const auto& tab = mip_[L];
        const long long n = static_cast<long long>(tab.size());
        long long j = floorDiv(i, 1LL << L);
        j = wrap_ == WrapMode::Mod ? ((j % n) + n) % n : std::clamp(j, 0LL, n - 1);
        return tab[j];
    };

    // i = floor(lg w) selects the level; optionally lerp to the next coarser one.
    const double Lf = std::log2(W);
    const int L = static_cast<int>(std::min<double>(std::floor(Lf), lgN));
    if (!blend || L >= lgN) return level(L);
    const double t = std::clamp(Lf - L, 0.0, 1.0);
    return glm::mix(level(L), level(L + 1), t);
}

// ---- summed-area colour table (section 3.3.2, eq. 13-15) ----------------------------------

glm::dvec4 ColorMap::filterSat(double f, double w) const {
    if (clut_.empty()) return kBlack;
    const long long N = size();
    const double u = tableCoord(f, size()), W = tableWidth(w, size());
    if (W <= 0.0) return sample(f);
    auto csat = [&](long long i) { return i < 0 ? glm::dvec4(0.0) : csat_[i]; };  // csat[-1] = 0
    const glm::dvec4& first = clut_[0];
    const glm::dvec4& last = clut_[N - 1];

    // Case "w >= N": the average of the entire colour map, csat[N-1] / N. This holds for
    // mod only; in clamp mode the window may extend far past one end, so W >= N falls
    // through to the clamp cases below (with both extension terms).
    if (wrap_ == WrapMode::Mod && W >= N) return csat_[N - 1] / double(N);

    // Eq. 15 with integer indices: the window covers entries lo+1..hi.
    long long lo = floorLL(u - 0.5 * W), hi = floorLL(u + 0.5 * W);
    if (hi == lo) return at(hi);
    const double count = double(hi - lo);

    if (wrap_ == WrapMode::Mod) {
        // Take f mod 1: shift the window by a multiple of N so its centre entry is in
        // [0, N). With W < N at most one end is then out, and by less than N.
        const long long shift = floorDiv(floorLL(u), N) * N;
        lo -= shift;
        hi -= shift;
        if (hi >= N)  // case f + w/2 >= N, mod: csat[f+w/2-N] + csat[N-1] - csat[f-w/2-1]
            return (csat(hi - N) + csat_[N - 1] - csat(lo)) / count;
        if (lo < -1)  // case f - w/2 < 0, mod: csat[f+w/2] + csat[N-1] - csat[N+f-w/2-1]
            return (csat(hi) + csat_[N - 1] - csat(N + lo)) / count;
        return (csat(hi) - csat(lo)) / count;  // eq. 15
    }

    // Clamp. Windows entirely past one end (not listed in the paper: f itself out of
    // [0, 1]) see only the end entry.
    if (lo >= N - 1) return last;
    if (hi < 0) return first;
    if (hi >= N && lo < -1)  // both ends out (e.g. w >= N): both extension terms
        return (double(-(lo + 1)) * first + csat_[N - 1] + double(hi - (N - 1)) * last) / count;
    if (hi >= N)  // case f + w/2 >= N, clamp: (f+w/2-(N-1)) clut[N-1] + csat[N-1] - csat[f-w/2-1]
        return (double(hi - (N - 1)) * last + csat_[N - 1] - csat(lo)) / count;
    if (lo < -1)  // case f - w/2 < 0, clamp: -(f-w/2) clut[0] + csat[f+w/2]
        return (double(-(lo + 1)) * first + csat(hi)) / count;
    return (csat(hi) - csat(lo)) / count;  // eq. 15
}

glm::dvec4 ColorMap::filterSat3N(double f, double w) const {
    if (clut_.empty()) return kBlack;
    const long long N = size();
    const double u = tableCoord(f, size()), W = tableWidth(w, size());
    if (W <= 0.0) return sample(f);
    if (wrap_ == WrapMode::Mod && W >= N) return csat_[N - 1] / double(N);
    long long lo = floorLL(u - 0.5 * W), hi = floorLL(u + 0.5 * W);
    if (hi == lo) return at(hi);
    const double count = double(hi - lo);
    if (wrap_ == WrapMode::Mod) {  // centre entry in [0, N): the window lies in [-N, 2N-1]
        const long long shift = floorDiv(floorLL(u), N) * N;
        lo -= shift;
        hi -= shift;
    } else {
        if (lo >= N - 1) return clut_[N - 1];
        if (hi < 0) return clut_[0];
    }
    // Table lookup, extended linearly past its ends (clamp mode only).
    auto T = [&](long long k) {
        if (k < -N) return csat3_[0] - double(-N - k) * clut_[0];
        if (k > 2 * N - 1) return csat3_[3 * N - 1] + double(k - (2 * N - 1)) * clut_[N - 1];
        return csat3_[k + N];
    };
    return (T(hi) - T(lo)) / count;
}

// ---- exact box filter (eq. 9) -------------------------------------------------------------

glm::dvec4 ColorMap::filterBox(double f, double w) const {
    if (clut_.empty()) return kBlack;
    const long long N = size();
    double u = tableCoord(f, size());
    const double W = tableWidth(w, size());
    if (W <= 0.0) return sample(f);
    if (wrap_ == WrapMode::Mod) u -= double(N) * std::floor(u / double(N));  // exact f mod 1

    // Sum of whole entries m..n (empty if m > n) of the extended map.
    auto sumEntries = [&](long long m, long long n) {
        glm::dvec4 s(0.0);
        if (m > n) return s;
        auto range = [&](long long a, long long b) {  // 0 <= a, b < N
            return a > b ? glm::dvec4(0.0) : csat_[b] - (a > 0 ? csat_[a - 1] : glm::dvec4(0.0));
        };
        if (wrap_ == WrapMode::Mod) {  // whole periods, then the remainder (wrapping once)
            const long long count = n - m + 1, periods = count / N, rem = count % N;
            const long long r = ((m % N) + N) % N;
            s = double(periods) * csat_[N - 1];
            if (rem > 0) {
                const long long e = r + rem - 1;
                s += e < N ? range(r, e) : range(r, N - 1) + range(0, e - N);
            }
        } else {  // below the table, inside it, above it
            if (m < 0) s += double(std::min(n, -1LL) - m + 1) * clut_[0];
            s += range(std::max(m, 0LL), std::min(n, N - 1));
            if (n >= N) s += double(n - std::max(m, N) + 1) * clut_[N - 1];
        }
        return s;
    };

    // Integral over [a, b]: partial entry ia, whole entries ia+1..ib-1, partial entry ib.
    const double a = u - 0.5 * W, b = u + 0.5 * W;
    const long long ia = floorLL(a), ib = floorLL(b);
    if (ia == ib) return at(ia);
    const glm::dvec4 sum = (double(ia + 1) - a) * at(ia) + sumEntries(ia + 1, ib - 1) +
                           (b - double(ib)) * at(ib);
    return sum / (b - a);
}

// ---- exact trapezoid (the pixel footprint of a linear f) -------------------------------------

glm::dvec4 ColorMap::rampIntegral(double s, double e, double b) const {
    // Entry i covers [i, i + 1): its part [p, q] of [s, e] adds c_i (q - p) (b - (p + q) / 2).
    glm::dvec4 sum(0.0);
    auto walk = [&](double p0, double q0) {
        if (!(q0 > p0)) return;
        for (long long i = floorLL(p0); double(i) < q0; ++i) {
            const double p = std::max(p0, double(i)), q = std::min(q0, double(i + 1));
            if (q > p) sum += at(i) * ((q - p) * (b - 0.5 * (p + q)));
        }
    };
    if (wrap_ == WrapMode::Mod) {
        walk(s, e);  // e - s < N: at most N + 1 entries
        return sum;
    }
    const double N = double(size());
    auto constant = [&](double p, double q, const glm::dvec4& c) {
        if (q > p) sum += c * ((q - p) * (b - 0.5 * (p + q)));
    };
    constant(s, std::min(e, 0.0), clut_[0]);       // below the table
    walk(std::max(s, 0.0), std::min(e, N));         // inside
    constant(std::max(s, N), e, clut_[size() - 1]);  // above
    return sum;
}

glm::dvec4 ColorMap::filterTrapezoid(double f, double wx, double wy) const {
    // With a = max(Wx, Wy), b = min(Wx, Wy), c the extended map and S1' = c, the footprint mean is
    //   (1/b) int_{u-b/2}^{u+b/2} box_a(v) dv,  box_a(v) = (S1(v + a/2) - S1(v - a/2)) / a,
    // and int_al^{al+b} S1(v + h) dv = b S1(al + h) + J(al + h, al + h + b) with
    // J(s, e) = int_s^e (S1(x) - S1(s)) dx = int_s^e c(t) (e - t) dt. Hence, with al = u - b/2,
    //   result = box_a(al) + (J(al + a/2, al + a/2 + b) - J(al - a/2, al - a/2 + b)) / (a b):
    // filterBox's closed form plus two local integrals over b-long spans (no cancellation of
    // large twice-summed values; b = 0 is the box exactly).
    if (clut_.empty()) return kBlack;
    const double n = double(size());
    const double Wa = tableWidth(wx, size()), Wb = tableWidth(wy, size());
    const double a = std::max(Wa, Wb), b = std::min(Wa, Wb);
    if (a <= 0.0) return sample(f);
    double u = tableCoord(f, size());
    if (wrap_ == WrapMode::Mod) u -= n * std::floor(u / n);  // exact f mod 1
    const double al = u - 0.5 * b;
    const glm::dvec4 box = filterBox(al / n, a / n);
    if (!(a * b > 0.0)) return box;  // b = 0, or a b below the smallest double (0/0 below)

    // J over a span of length b: in mod mode whole periods in closed form, the rest walked.
    auto J = [&](double s) -> glm::dvec4 {
        if (wrap_ == WrapMode::Mod) s -= n * std::floor(s / n);  // J is periodic in s
        const double e = s + b;
        if (wrap_ == WrapMode::Clamp) return rampIntegral(s, e, e);
        const double q = std::floor(b / n), r = b - q * n;
        glm::dvec4 j = rampIntegral(s, s + r, e);  // the remainder [s, s + r)
        if (q > 0) {
            // Period k (k = 0..q-1) starts at s' = s + r + k N; there e - t = (q - k) N - x for
            // t = s' + x, so it adds (q - k) N T - M1 with T the period's sum and
            // M1 = int_0^N x c(s' + x) dx (the same for every period).
            const double s0 = s + r;
            const glm::dvec4 T = csat_.back();
            // rampIntegral(s0, s0 + N, s0 + N) = int c(t) (s0 + N - t) dt = N T - M1.
            const glm::dvec4 M1 = n * T - rampIntegral(s0, s0 + n, s0 + n);
            j += (0.5 * q * (q + 1) * n) * T - q * M1;
        }
        return j;
    };
    const glm::dvec4 jHi = J(al + 0.5 * a), jLo = J(al - 0.5 * a);
    return box + (jHi - jLo) / (a * b);
}

}  // namespace pst

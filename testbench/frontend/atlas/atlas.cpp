#include "atlas.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/mat2x2.hpp>

#include "input_error.h"
#include "mesh.h"

namespace pst {

bool parseAtlasKind(const std::string& name, AtlasKind* out) {
    if (name == "uniform") *out = AtlasKind::Uniform;
    else if (name == "area") *out = AtlasKind::Area;
    else if (name == "length") *out = AtlasKind::Length;
    else return false;
    return true;
}

const char* toString(AtlasKind k) {
    switch (k) {
        case AtlasKind::Uniform: return "uniform";
        case AtlasKind::Area: return "area";
        case AtlasKind::Length: return "length";
    }
    return "?";
}

bool parseMagnification(const std::string& name, Magnification* out) {
    if (name == "nearest") *out = Magnification::Nearest;
    else if (name == "bilinear") *out = Magnification::Bilinear;
    else return false;
    return true;
}

const char* toString(Magnification m) { return m == Magnification::Nearest ? "nearest" : "bilinear"; }

double AtlasTriangle::area() const { return 0.5 * glm::length(glm::cross(x[1] - x[0], x[2] - x[0])); }

double AtlasTriangle::longestEdge() const {
    return std::max({glm::length(x[1] - x[0]), glm::length(x[2] - x[1]), glm::length(x[0] - x[2])});
}

namespace {

double area2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

// The margin m of the seam-free footprint: how far past the hypotenuse the filter reads.
int margin(const AtlasOptions& o) { return o.magnification == Magnification::Bilinear ? 1 : 0; }

// Rotates the vertices so that x[0] (the chart's right angle) is opposite the longest edge:
// the hypotenuse then carries the longest edge, which keeps the distortion small.
void rightAngleOppositeLongest(AtlasTriangle& t) {
    const double e0 = glm::length(t.x[2] - t.x[1]), e1 = glm::length(t.x[0] - t.x[2]),
                 e2 = glm::length(t.x[1] - t.x[0]);
    const int k = e0 >= e1 && e0 >= e2 ? 0 : e1 >= e2 ? 1 : 2;
    std::rotate(t.x.begin(), t.x.begin() + k, t.x.end());
    std::rotate(t.s.begin(), t.s.begin() + k, t.s.end());
}

// A strip of pair cells, all with the same legs.
struct Strip {
    int legs = 0;
    size_t first = 0, count = 0;  // triangles order[first .. first + count)
};

// Places the strips top-down; false if they run past the bottom row.
bool packStrips(Atlas& a, const std::vector<Strip>& strips, const std::vector<size_t>& order) {
    const int H = a.size();
    int y = 0;
    for (const Strip& s : strips) {
        const glm::ivec2 cell = a.cellSize(s.legs);
        if (y + cell.y > H) return false;
        for (size_t k = 0; k < s.count; ++k) {
            const size_t t = order[s.first + k];
            Chart& c = a.charts[t];
            c.legs = s.legs;
            c.cell = glm::ivec2(int(k / 2) * cell.x, y);
            c.second = (k % 2) == 1;
        }
        y += cell.y;
    }
    return true;
}

// Uniform atlas: the largest legs L such that every pair gets an L cell (section 4.1).
std::vector<Strip> uniformStrips(const Atlas& a, size_t M, int* legsOut) {
    const int H = a.size();
    auto pairsHeld = [&](int L) {
        const glm::ivec2 c = a.cellSize(L);
        return c.x > H || c.y > H ? 0LL : (long long)(H / c.x) * (H / c.y);
    };
    const long long pairs = (long long)(M + 1) / 2;
    if (pairsHeld(kMinLegs) < pairs) return {};
    int lo = kMinLegs, hi = H;  // pairsHeld falls as L grows
    while (lo < hi) {
        const int mid = (lo + hi + 1) / 2;
        if (pairsHeld(mid) >= pairs) lo = mid;
        else hi = mid - 1;
    }
    *legsOut = lo;
    const glm::ivec2 cell = a.cellSize(lo);
    const size_t perStrip = size_t(2 * (H / cell.x));
    std::vector<Strip> strips;
    for (size_t i = 0; i < M; i += perStrip) strips.push_back({lo, i, std::min(perStrip, M - i)});
    return strips;
}

// Non-uniform atlas with scale k (section 4.2): triangles in non-increasing weight order, each
// strip's legs k times the RMS weight of the triangles it holds (so the strip's relative scale
// is near one), at least kMinLegs.
std::vector<Strip> weightedStrips(const Atlas& a, const std::vector<double>& w, const std::vector<size_t>& order,
                                  double k) {
    const int H = a.size();
    int maxLegs = kMinLegs;
    while (a.cellSize(maxLegs + 1).x <= H && a.cellSize(maxLegs + 1).y <= H) ++maxLegs;
    auto legsFor = [&](double wt, int cap) { return std::clamp(int(std::floor(k * wt)), kMinLegs, cap); };
    std::vector<Strip> strips;
    const size_t M = order.size();
    for (size_t i = 0; i < M;) {
        const int L0 = legsFor(w[order[i]], maxLegs);
        size_t n = std::min(M - i, size_t(2 * (H / a.cellSize(L0).x)));
        double sum2 = 0;
        for (size_t j = i; j < i + n; ++j) sum2 += w[order[j]] * w[order[j]];
        const int L = legsFor(std::sqrt(sum2 / double(n)), L0);
        n = std::min(M - i, size_t(2 * (H / a.cellSize(L).x)));
        strips.push_back({L, i, n});
        i += n;
    }
    return strips;
}

int stripsHeight(const Atlas& a, const std::vector<Strip>& strips) {
    int h = 0;
    for (const Strip& s : strips) h += a.cellSize(s.legs).y;
    return h;
}

// The chart vertices of a placed chart.
void placeVertices(const Atlas& a, Chart& c) {
    const double L = c.legs;
    const glm::dvec2 o(c.cell);
    if (!a.options.seamFree) {
        // Fig. 2: vertices on texel corners, the pair sharing the cell's diagonal.
        c.u = c.second ? std::array<glm::dvec2, 3>{o + glm::dvec2(L, L), o + glm::dvec2(0, L), o + glm::dvec2(L, 0)}
                       : std::array<glm::dvec2, 3>{o, o + glm::dvec2(L, 0), o + glm::dvec2(0, L)};
        return;
    }
    // Fig. 4c: vertices on texel centres; the second triangle rotated into the cell's far end.
    const glm::ivec2 cell = a.cellSize(c.legs);
    if (c.second) {
        const glm::dvec2 p = o + glm::dvec2(cell.x - 0.5, L + 0.5);
        c.u = {p, p - glm::dvec2(L, 0), p - glm::dvec2(0, L)};
    } else {
        const glm::dvec2 p = o + glm::dvec2(0.5, 0.5);
        c.u = {p, p + glm::dvec2(L, 0), p + glm::dvec2(0, L)};
    }
    const glm::dvec2 g = (c.u[0] + c.u[1] + c.u[2]) / 3.0;
    for (auto& u : c.u) u = g + (u - g) * (1.0 - kChartInset);
}

}  // namespace

void Atlas::placeCharts() {
    for (Chart& c : charts) placeVertices(*this, c);
}

glm::ivec2 Atlas::cellSize(int legs) const {
    if (mipCell > 0) {
        const int side = legs + (options.seamFree ? 2 + 2 * margin(options) : 0);  // a power of two
        return {side, side};
    }
    if (!options.seamFree) return {legs, legs};
    return {legs + 2 + 2 * margin(options), legs + 1};
}

std::vector<glm::ivec2> Atlas::footprint(int t) const {
    const Chart& c = charts[size_t(t)];
    const int L = c.legs;
    std::vector<glm::ivec2> out;
    if (!options.seamFree) {
        // Texels whose centre lies in the triangle; the diagonal's centres go to the first.
        for (int j = 0; j < L; ++j)
            for (int i = 0; i < L; ++i)
                if ((i + j + 1 <= L) != c.second) out.push_back(c.cell + glm::ivec2(i, j));
        return out;
    }
    const int m = margin(options);
    const glm::ivec2 cell = cellSize(L);
    for (int j = 0; j <= L; ++j)
        for (int i = 0; i <= L && i + j <= L + m; ++i)
            out.push_back(c.cell + (c.second ? glm::ivec2(cell.x - 1 - i, L - j) : glm::ivec2(i, j)));
    return out;
}

std::vector<int> Atlas::owners() const {
    std::vector<int> own(size_t(size()) * size(), -1);
    for (size_t t = 0; t < charts.size(); ++t)
        for (const glm::ivec2& p : footprint(int(t))) own[size_t(p.y) * size() + p.x] = int(t);
    return own;
}

void prepareTriangles(std::vector<AtlasTriangle>& tris) {
    for (AtlasTriangle& t : tris) {
        if (zeroArea(t.x[0], t.x[1], t.x[2]))  // sceneTriangles never gives one
            throw InputError("triangle " + std::to_string(t.index) + " of object " + std::to_string(t.object) +
                             ": degenerate (zero area)");
        rightAngleOppositeLongest(t);
    }
}

Atlas buildAtlas(std::vector<AtlasTriangle> tris, const AtlasOptions& opt) {
    Atlas a;
    a.options = opt;
    const size_t M = tris.size();
    if (opt.size < 1) throw InputError("--size: must be at least 1 (got " + std::to_string(opt.size) + ")");
    if (M == 0) throw InputError("--size: no triangles to place");
    prepareTriangles(tris);
    a.triangles = std::move(tris);
    a.charts.assign(M, Chart{});
    // Eq. (3): pairs of triangles in a square grid of ceil(sqrt(M/2)) cells a side.
    a.eq3Edge = double(opt.size) / std::ceil(std::sqrt(double(M) / 2.0));

    std::vector<size_t> order(M);
    std::iota(order.begin(), order.end(), size_t(0));
    std::vector<Strip> strips;
    auto tooMany = [&] {
        const glm::ivec2 c = a.cellSize(kMinLegs);
        const long long held = c.x > opt.size || c.y > opt.size ? 0 : 2LL * (opt.size / c.x) * (opt.size / c.y);
        return InputError("--size: " + std::to_string(M) + " triangles do not fit a " + std::to_string(opt.size) +
                          " x " + std::to_string(opt.size) + " atlas (it holds " + std::to_string(held) +
                          " at the smallest " + std::to_string(c.x) + " x " + std::to_string(c.y) + " pair cell)");
    };
    if (opt.kind == AtlasKind::Uniform) {
        int L = 0;
        strips = uniformStrips(a, M, &L);
        if (strips.empty()) throw tooMany();
    } else {
        std::vector<double> w(M);
        for (size_t t = 0; t < M; ++t)
            w[t] = opt.kind == AtlasKind::Area ? std::sqrt(a.triangles[t].area()) : a.triangles[t].longestEdge();
        // Sorted by non-increasing area (or longest edge); ties keep mesh order.
        std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) { return w[i] > w[j]; });
        if (stripsHeight(a, weightedStrips(a, w, order, 0.0)) > opt.size) throw tooMany();
        // The largest scale k whose strips fit (bisection; the height grows with k).
        double lo = 0.0, hi = 2.0 * opt.size / w[order.back()];
        for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            if (stripsHeight(a, weightedStrips(a, w, order, mid)) <= opt.size) lo = mid;
            else hi = mid;
        }
        strips = weightedStrips(a, w, order, lo);
    }
    if (!packStrips(a, strips, order)) throw tooMany();
    a.stripCount = int(strips.size());
    a.placeCharts();
    return a;
}

double coverage(const Atlas& a) {
    double c = 0;
    for (const Chart& ch : a.charts) c += area2(ch.u[0], ch.u[1], ch.u[2]);
    return c / (double(a.size()) * a.size());
}

std::vector<double> triangleScales(const Atlas& a) {
    double total = 0;
    for (const AtlasTriangle& t : a.triangles) total += t.area();
    std::vector<double> r(a.triangles.size());
    const double unit = 1.0 / (double(a.size()) * a.size());
    for (size_t t = 0; t < r.size(); ++t) {
        const Chart& c = a.charts[t];
        r[t] = std::sqrt(total * area2(c.u[0], c.u[1], c.u[2]) * unit / a.triangles[t].area());
    }
    return r;
}

double relativeScale(const Atlas& a) {
    // Eq. (2): S^2 = sum_j A(x_j) * (1/M) sum_j A(u_j)/A(x_j), the mean of the squared
    // per-triangle scales.
    double s2 = 0;
    for (double r : triangleScales(a)) s2 += r * r;
    return std::sqrt(s2 / double(a.triangles.size()));
}

double texelUse(const Atlas& a) {
    size_t n = 0;
    for (size_t t = 0; t < a.charts.size(); ++t) n += a.footprint(int(t)).size();
    return double(n) / (double(a.size()) * a.size());
}

std::vector<AtlasTexel> atlasTexels(const Atlas& a) {
    std::vector<AtlasTexel> out;
    for (size_t t = 0; t < a.charts.size(); ++t) {
        const Chart& c = a.charts[t];
        const AtlasTriangle& tri = a.triangles[t];
        // The chart map is affine: beta = E^-1 (u - u0), s = s0 + [s1 - s0, s2 - s0] beta, so
        // ds/du and ds/dv are the columns of [s1 - s0, s2 - s0] E^-1 (per texel).
        const glm::dmat2 E(c.u[1] - c.u[0], c.u[2] - c.u[0]);
        const glm::dmat2 Ei = glm::inverse(E);
        const glm::dvec3 e1 = tri.s[1] - tri.s[0], e2 = tri.s[2] - tri.s[0];
        const glm::dvec3 dsdu = e1 * Ei[0][0] + e2 * Ei[0][1];
        const glm::dvec3 dsdv = e1 * Ei[1][0] + e2 * Ei[1][1];
        for (const glm::ivec2& p : a.footprint(int(t))) {
            const glm::dvec2 beta = Ei * (glm::dvec2(p.x + 0.5, p.y + 0.5) - c.u[0]);
            out.push_back({p.x, p.y, int(t), tri.s[0] + e1 * beta.x + e2 * beta.y, dsdu, dsdv});
        }
    }
    return out;
}

glm::dvec2 chartPoint(const Atlas& a, int t, const glm::dvec3& b) {
    const Chart& c = a.charts[size_t(t)];
    return c.u[0] * b[0] + c.u[1] * b[1] + c.u[2] * b[2];
}

AtlasLookup lookupAtlas(const std::vector<float>& rgba, const std::vector<int>& owners, int size, int t,
                        const glm::dvec2& u, Magnification filter) {
    AtlasLookup r;
    auto texel = [&](int i, int j, double weight) {
        i = std::clamp(i, 0, size - 1);
        j = std::clamp(j, 0, size - 1);
        const size_t k = size_t(j) * size + i;
        if (weight > 0 && owners[k] != t) r.touchedForeign = true;
        for (int ch = 0; ch < 4; ++ch) r.rgba[ch] += weight * rgba[k * 4 + ch];
    };
    if (filter == Magnification::Nearest) {
        texel(int(std::floor(u.x)), int(std::floor(u.y)), 1.0);
        return r;
    }
    // Bilinear: the four texel centres around u.
    const double x = u.x - 0.5, y = u.y - 0.5;
    const int i = int(std::floor(x)), j = int(std::floor(y));
    const double fx = x - i, fy = y - j;
    texel(i, j, (1 - fx) * (1 - fy));
    texel(i + 1, j, fx * (1 - fy));
    texel(i, j + 1, (1 - fx) * fy);
    texel(i + 1, j + 1, fx * fy);
    return r;
}

}  // namespace pst

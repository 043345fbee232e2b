// Worley's 1996 cellular basis; see worley.h.
#include "worley.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace pst {
namespace {

constexpr uint32_t kHashI = 702395077u, kHashJ = 915488749u, kHashK = 2120969693u;
constexpr uint32_t kLcgMul = 1402024253u, kLcgAdd = 586950981u;

uint32_t lcg(uint32_t s) { return kLcgMul * s + kLcgAdd; }  // mod 2^32 by unsigned wrap-around

std::array<uint8_t, 256> makePoissonTable() {
    std::array<uint8_t, 256> t{};
    for (int e = 0; e < 256; ++e) {
        const double target = (e + 0.5) / 256.0;
        double pm = std::exp(-kWorleyDensity), cdf = pm;  // P(0)
        int m = 0;
        while (cdf <= target && m < 100) {
            ++m;
            pm *= kWorleyDensity / m;
            cdf += pm;
        }
        t[e] = static_cast<uint8_t>(std::clamp(m, kWorleyMinPoints, kWorleyMaxPoints));
    }
    return t;
}

// Exact periodic reduction by the hash period 2^32 (see worley.h, Domain).
double reduce(double x) {
    if (std::abs(x) < 2147483648.0) return x;
    double r = std::fmod(x, 4294967296.0);
    return r < 0 ? r + 4294967296.0 : r;
}

}  // namespace

const std::array<uint8_t, 256>& worleyPoissonTable() {
    static const std::array<uint8_t, 256> table = makePoissonTable();
    return table;
}

WorleyCube worleyCube(int64_t i, int64_t j, int64_t k) {
    WorleyCube c;
    const uint32_t seed = kHashI * static_cast<uint32_t>(i) + kHashJ * static_cast<uint32_t>(j) +
                          kHashK * static_cast<uint32_t>(k);
    uint32_t s = lcg(seed);
    c.count = worleyPoissonTable()[s >> 24];
    for (int n = 0; n < c.count; ++n) {
        c.id[n] = seed + static_cast<uint32_t>(n);
        for (int a = 0; a < 3; ++a) {
            s = lcg(s);
            c.offset[n][a] = (s + 0.5) * (1.0 / 4294967296.0);
        }
    }
    return c;
}

int worleyRomIndex(int64_t i, int64_t j, int64_t k) {
    const auto& P = NoiseTables::get().perm;
    const int off = int(NoiseTables::kLatticeOffset) % 4096;  // 576, as the hardware's L
    auto idx = [&](int64_t x) { return int((x + off) & 0xff); };
    return P[size_t(P[size_t(P[size_t(idx(i))] ^ idx(j))] ^ idx(k))];
}

std::array<uint8_t, 3 * kWorleyMaxPoints> worleyRomBytes(int entry) {
    // The top bytes of the LCG values of cube (entry, 0, 0), as worleyCube draws them.
    std::array<uint8_t, 3 * kWorleyMaxPoints> b{};
    uint32_t s = lcg(kHashI * static_cast<uint32_t>(entry));
    for (int n = 0; n < kWorleyMaxPoints; ++n)
        for (int a = 0; a < 3; ++a) {
            s = lcg(s);
            b[size_t(3 * n + a)] = uint8_t(s >> 24);
        }
    return b;
}

WorleyCube worleyRomCube(int entry, int maxPoints) {
    WorleyCube c = worleyCube(entry, 0, 0);
    const auto b = worleyRomBytes(entry);
    c.count = std::min(c.count, std::clamp(maxPoints, 1, kWorleyMaxPoints));
    for (int n = 0; n < kWorleyMaxPoints; ++n)
        for (int a = 0; a < 3; ++a) c.offset[size_t(n)][a] = (2.0 * b[size_t(3 * n + a)] + 1.0) / 512.0;
    return c;
}

WorleySearch worleySearchOf(const NoiseOptions& opt) {
    WorleySearch s;
    s.radius = opt.search == WorleySearchKind::Cube27 ? 1 : -1;
    s.octant = opt.search == WorleySearchKind::Octant;
    s.maxPoints = opt.maxPoints;
    s.cubes = opt.cubes;
    return s;
}

double worleyCellValue(uint32_t id) { return lcg(id) * (1.0 / 4294967296.0); }

WorleyResult worley(const glm::dvec3& pIn, int order, WorleyMetric metric) {
    return worley(pIn, order, metric, WorleySearch{});
}

WorleyResult worley(const glm::dvec3& pIn, int order, WorleyMetric metric, const WorleySearch& search) {
    WorleyResult r;
    order = std::clamp(order, 1, kWorleyMaxOrder);
    if (!std::isfinite(pIn.x) || !std::isfinite(pIn.y) || !std::isfinite(pIn.z)) return r;
    const glm::dvec3 p(reduce(pIn.x), reduce(pIn.y), reduce(pIn.z));
    const glm::dvec3 base = glm::floor(p);
    const glm::dvec3 fr = p - base;  // exact
    const int64_t b[3] = {static_cast<int64_t>(base.x), static_cast<int64_t>(base.y), static_cast<int64_t>(base.z)};
    const bool euclid = metric == WorleyMetric::Euclid;

    // The `order` best so far, sorted by distance (squared for Euclid): d, delta = x - point, id.
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::array<double, kWorleyMaxOrder> best;
    best.fill(kInf);
    std::array<glm::dvec3, kWorleyMaxOrder> delta{};
    std::array<uint32_t, kWorleyMaxOrder> id{};
    auto metricOf = [&](const glm::dvec3& d) {
        return euclid ? d.x * d.x + d.y * d.y + d.z * d.z : std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    };
    auto visit = [&](int ox, int oy, int oz) {
        // Nearest face of the cube: skip it if it cannot hold a point closer than best[order-1].
        const int o[3] = {ox, oy, oz};
        glm::dvec3 gap(0.0);
        for (int a = 0; a < 3; ++a) gap[a] = o[a] > 0 ? o[a] - fr[a] : (o[a] < 0 ? fr[a] - (o[a] + 1) : 0.0);
        if (metricOf(gap) >= best[order - 1]) return;
        const WorleyCube c = search.cubes == WorleyCubes::Rom256
                                 ? worleyRomCube(worleyRomIndex(b[0] + ox, b[1] + oy, b[2] + oz), search.maxPoints)
                                 : worleyCube(b[0] + ox, b[1] + oy, b[2] + oz);
        const int count = std::min(c.count, std::max(search.maxPoints, 1));
        for (int n = 0; n < count; ++n) {
            const glm::dvec3 d = fr - (glm::dvec3(ox, oy, oz) + c.offset[n]);
            const double m = metricOf(d);
            if (!(m < best[order - 1])) continue;
            int at = order - 1;
            while (at > 0 && m < best[at - 1]) {
                best[at] = best[at - 1];
                delta[at] = delta[at - 1];
                id[at] = id[at - 1];
                --at;
            }
            best[at] = m;
            delta[at] = d;
            id[at] = c.id[n];
        }
    };
    // Shells of cubes by Chebyshev distance r from the home cube. Every cube of shell r is at
    // least r - 1 + min(fr, 1 - fr) away along one axis; stop when that is no closer than the
    // order-th best. With at least one point per cube this ends by r = 4 (Euclid) or 6.
    double edge = 1.0;
    for (int a = 0; a < 3; ++a) edge = std::min({edge, fr[a], 1.0 - fr[a]});
    if (search.octant) {
        // The hardware's 8 cubes, c = bx + 2 by + 4 bz, o_a = b_a (fr_a >= 1/2 ? +1 : -1).
        int dir[3];
        for (int a = 0; a < 3; ++a) dir[a] = fr[a] >= 0.5 ? 1 : -1;
        for (int c = 0; c < 8; ++c) visit((c & 1) * dir[0], ((c >> 1) & 1) * dir[1], ((c >> 2) & 1) * dir[2]);
    } else if (search.radius >= 0) {
        // (2 radius + 1)^3 cubes, x fastest (the hardware's order for radius 1).
        const int rr = search.radius;
        for (int oz = -rr; oz <= rr; ++oz)
            for (int oy = -rr; oy <= rr; ++oy)
                for (int ox = -rr; ox <= rr; ++ox) visit(ox, oy, oz);
    }
    const int maxR = search.radius < 0 && !search.octant ? 63 : -1;
    for (int rr = 0; rr <= maxR; ++rr) {
        if (rr > 0) {
            const double lb = rr - 1 + edge;
            if ((euclid ? lb * lb : lb) >= best[order - 1]) break;
        }
        for (int ox = -rr; ox <= rr; ++ox)
            for (int oy = -rr; oy <= rr; ++oy)
                for (int oz = -rr; oz <= rr; ++oz)
                    if (std::max({std::abs(ox), std::abs(oy), std::abs(oz)}) == rr) visit(ox, oy, oz);
    }

    for (int n = 0; n < order; ++n) {
        const glm::dvec3& d = delta[n];
        r.id[n] = id[n];
        r.delta[n] = d;
        if (!std::isfinite(best[n])) {  // a cut search saw fewer than n + 1 points
            r.F[n] = best[n];
        } else if (euclid) {
            r.F[n] = std::sqrt(best[n]);
            r.grad[n] = r.F[n] > 0 ? d / r.F[n] : glm::dvec3(0.0);
        } else {
            r.F[n] = best[n];
            for (int a = 0; a < 3; ++a) r.grad[n][a] = d[a] > 0 ? 1.0 : (d[a] < 0 ? -1.0 : 0.0);
        }
    }
    return r;
}

double worleyBasis(const glm::dvec3& p, const NoiseOptions& opt, glm::dvec3* grad) {
    int order = 1;
    for (int k = 0; k < kWorleyMaxOrder; ++k)
        if (opt.coef[k] != 0.0) order = k + 1;
    const WorleyResult r = worley(p, order, opt.metric, worleySearchOf(opt));
    double n = 0.0;
    glm::dvec3 g(0.0);
    for (int k = 0; k < order; ++k) {
        n += opt.coef[k] * r.F[k];
        g += opt.coef[k] * r.grad[k];
    }
    if (opt.cell != 0.0) n += opt.cell * worleyCellValue(r.id[0]);
    if (grad) *grad = g;
    return n;
}

}  // namespace pst

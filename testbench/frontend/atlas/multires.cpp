#include "multires.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include <metis.h>

#include "input_error.h"

namespace pst {
namespace {

struct Vec3Less {
    bool operator()(const glm::dvec3& a, const glm::dvec3& b) const {
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    }
};

// Pairs triangles across shared edges (greedy: the triangle with the fewest free neighbours
// first, matched to its free neighbour with the fewest free neighbours). Unmatched triangles
// stay alone (a pair of one).
std::vector<std::array<int, 2>> pairTriangles(const std::vector<std::vector<int>>& dual) {
    const int n = int(dual.size());
    std::vector<int> mate(size_t(n), -1);
    auto freeDegree = [&](int t) {
        int d = 0;
        for (int u : dual[size_t(t)]) d += mate[size_t(u)] < 0;
        return d;
    };
    std::vector<int> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return dual[size_t(a)].size() < dual[size_t(b)].size(); });
    for (int t : order) {
        if (mate[size_t(t)] >= 0) continue;
        int best = -1, bestDeg = 1 << 30;
        for (int u : dual[size_t(t)])
            if (u != t && mate[size_t(u)] < 0) {
                const int d = freeDegree(u);
                if (d < bestDeg) best = u, bestDeg = d;
            }
        if (best >= 0) mate[size_t(t)] = best, mate[size_t(best)] = t;
    }
    std::vector<std::array<int, 2>> pairs;
    for (int t = 0; t < n; ++t) {
        if (mate[size_t(t)] < 0) pairs.push_back({t, -1});
        else if (t < mate[size_t(t)]) pairs.push_back({t, mate[size_t(t)]});
    }
    return pairs;
}

// Splits `items` (vertices of graph g) into 4 parts of at most `cap` vertices each: METIS
// k-way on the induced subgraph, balancing the vertex weights `vwgt` (one per item; contiguous
// parts asked for), then vertices moved out of parts over capacity, one at a time to an adjacent part with
// room, and if none is adjacent, the rest in order into the first part with room.
std::array<std::vector<int>, 4> split4(const std::vector<int>& items, const std::vector<std::vector<int>>& g,
                                       const std::vector<idx_t>& vwgt, size_t cap) {
    std::array<std::vector<int>, 4> parts;
    const idx_t n = idx_t(items.size());
    std::vector<idx_t> part(items.size(), 0);
    std::map<int, idx_t> local;
    for (idx_t i = 0; i < n; ++i) local[items[size_t(i)]] = i;
    if (n <= 4) {
        for (idx_t i = 0; i < n; ++i) part[size_t(i)] = i;
    } else {
        std::vector<idx_t> xadj{0}, adj, weights(vwgt);
        for (int v : items) {
            for (int u : g[size_t(v)])
                if (auto it = local.find(u); it != local.end()) adj.push_back(it->second);
            xadj.push_back(idx_t(adj.size()));
        }
        idx_t ncon = 1, nparts = 4, objval = 0, nv = n;
        idx_t options[METIS_NOPTIONS];
        METIS_SetDefaultOptions(options);
        // Contiguous parts when the subgraph is connected (METIS refuses, loudly, otherwise).
        std::vector<char> seen(items.size(), 0);
        std::vector<idx_t> stack{0};
        seen[0] = 1;
        idx_t reached = 1;
        while (!stack.empty()) {
            const idx_t v = stack.back();
            stack.pop_back();
            for (idx_t e = xadj[size_t(v)]; e < xadj[size_t(v) + 1]; ++e)
                if (!seen[size_t(adj[size_t(e)])]) {
                    seen[size_t(adj[size_t(e)])] = 1;
                    ++reached;
                    stack.push_back(adj[size_t(e)]);
                }
        }
        options[METIS_OPTION_CONTIG] = reached == n ? 1 : 0;
        options[METIS_OPTION_UFACTOR] = 1;  // 0.1 % imbalance
        options[METIS_OPTION_SEED] = 1;
        int rc = adj.empty() ? METIS_ERROR
                             : METIS_PartGraphKway(&nv, &ncon, xadj.data(), adj.data(), weights.data(), nullptr,
                                                   nullptr, &nparts, nullptr, nullptr, options, &objval, part.data());
        if (rc != METIS_OK)
            for (idx_t i = 0; i < n; ++i) part[size_t(i)] = idx_t(size_t(i) * 4 / size_t(n));
    }
    // Capacity: each quadrant holds `cap` cells.
    std::array<size_t, 4> count{};
    for (idx_t p : part) ++count[size_t(p)];
    for (int over = 0; over < 4; ++over)
        while (count[size_t(over)] > cap) {
            // A vertex of `over` next to a part with room, else any vertex of `over`.
            idx_t pick = -1, to = -1;
            for (idx_t i = 0; i < n && pick < 0; ++i) {
                if (part[size_t(i)] != over) continue;
                for (int u : g[size_t(items[size_t(i)])])
                    if (auto it = local.find(u); it != local.end() && count[size_t(part[size_t(it->second)])] < cap) {
                        pick = i, to = part[size_t(it->second)];
                        break;
                    }
            }
            if (pick < 0) {
                for (idx_t i = 0; i < n && pick < 0; ++i)
                    if (part[size_t(i)] == over) pick = i;
                for (int q = 0; q < 4; ++q)
                    if (count[size_t(q)] < cap) to = q;
            }
            part[size_t(pick)] = to;
            --count[size_t(over)];
            ++count[size_t(to)];
        }
    for (idx_t i = 0; i < n; ++i) parts[size_t(part[size_t(i)])].push_back(items[size_t(i)]);
    return parts;
}

// The quadtree placement (section 4.3) of the pairs: their graph, each pair's cell side, the
// side its weight asks for (k w_p + pad, section 4.2; empty for the uniform atlas, whose cells
// are fixed), the smallest cell, and where each pair's cell lands.
struct Quadtree {
    const std::vector<std::vector<int>>& graph;
    std::vector<int>& cell;
    const std::vector<double>& target;
    int minCell = 1;
    std::vector<glm::ivec2> origin;

    // Resizes the non-uniform cells of one quadrant's pairs to its side x side texels: the most
    // over-sized (cell over target) halved while they overflow it, then the most under-sized
    // doubled while they fit. The partition decides which pairs share a quadrant, and the cells
    // follow, so a quadrant never holds pairs from elsewhere on the surface.
    void fit(const std::vector<int>& items, int side) {
        long long load = 0;
        for (int p : items) {
            cell[size_t(p)] = std::min(cell[size_t(p)], side);
            load += (long long)cell[size_t(p)] * cell[size_t(p)];
        }
        const long long cap = (long long)side * side;
        auto ratio = [&](int p) { return cell[size_t(p)] / target[size_t(p)]; };
        while (load > cap) {
            int pick = -1;
            for (int p : items)
                if (cell[size_t(p)] > minCell && (pick < 0 || ratio(p) > ratio(pick))) pick = p;
            const long long c = cell[size_t(pick)];
            cell[size_t(pick)] /= 2;
            load -= 3 * c * c / 4;
        }
        for (;;) {
            int pick = -1;
            for (int p : items) {
                const long long c = cell[size_t(p)];
                if (2 * c <= side && load + 3 * c * c <= cap && (pick < 0 || ratio(p) < ratio(pick))) pick = p;
            }
            if (pick < 0) break;
            const long long c = cell[size_t(pick)];
            cell[size_t(pick)] *= 2;
            load += 3 * c * c;
        }
    }

    // Places `items` in the side x side block at (x0, y0): a pair alone takes the block's corner,
    // more are split into the four quadrants (METIS balancing the cells' texels).
    void place(const std::vector<int>& items, int x0, int y0, int side) {
        if (items.empty()) return;
        if (items.size() == 1) {
            origin[size_t(items[0])] = {x0, y0};
            return;
        }
        const int h = side / 2;
        std::vector<idx_t> vwgt(items.size(), 1);
        if (!target.empty())
            for (size_t i = 0; i < items.size(); ++i)
                vwgt[i] = idx_t((long long)cell[size_t(items[i])] * cell[size_t(items[i])] / minCell / minCell);
        const int unit = target.empty() ? cell[size_t(items[0])] : minCell;
        const auto parts = split4(items, graph, vwgt, size_t(h / unit) * size_t(h / unit));
        for (int q = 0; q < 4; ++q) {
            if (!target.empty()) fit(parts[size_t(q)], h);
            place(parts[size_t(q)], x0 + (q % 2) * h, y0 + (q / 2) * h, h);
        }
    }
};

// The non-uniform multiresolution atlas's pair cells before placement (section 4.2's weighting
// with section 4.3's power-of-two cells): pair p gets the largest power of two a_p <= k w_p + pad
// (legs near k w_p) within [minCell, H], for the largest scale k whose cells' texels sum to at
// most H^2. Returns the targets k w_p + pad; the quadtree then fits the cells quadrant by
// quadrant (Quadtree::fit).
std::vector<double> weightedCells(const std::vector<double>& w, int H, int pad, int minCell, std::vector<int>& cell) {
    const long long H2 = (long long)H * H;
    auto sideFor = [&](double k, double wt) {
        const double target = k * wt + pad;
        int c = minCell;
        while (c * 2 <= H && c * 2 <= target) c *= 2;
        return c;
    };
    auto texels = [&](double k) {
        long long sum = 0;
        for (double wt : w) sum += (long long)sideFor(k, wt) * sideFor(k, wt);
        return sum;
    };
    const double wMin = *std::min_element(w.begin(), w.end());
    double lo = 0.0, hi = 2.0 * H / wMin;
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (texels(mid) <= H2) lo = mid;
        else hi = mid;
    }
    std::vector<double> target(w.size());
    cell.resize(w.size());
    for (size_t p = 0; p < w.size(); ++p) cell[p] = sideFor(lo, w[p]), target[p] = lo * w[p] + pad;
    return target;
}

bool isPow2(int v) { return v > 0 && (v & (v - 1)) == 0; }


// The mesh's edges (vertices welded by position), each with the triangles on it.
std::map<std::pair<int, int>, std::vector<int>> edgeUses(const std::vector<AtlasTriangle>& tris) {
    std::map<glm::dvec3, int, Vec3Less> weld;
    auto id = [&](const glm::dvec3& p) { return weld.emplace(p, int(weld.size())).first->second; };
    std::map<std::pair<int, int>, std::vector<int>> edges;
    for (size_t t = 0; t < tris.size(); ++t) {
        int v[3];
        for (int k = 0; k < 3; ++k) v[k] = id(tris[t].x[size_t(k)]);
        for (int k = 0; k < 3; ++k) {
            const int a = v[k], b = v[(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].push_back(int(t));
        }
    }
    return edges;
}

}  // namespace

MeshEdges meshEdges(const std::vector<AtlasTriangle>& tris) {
    MeshEdges m;
    for (const auto& [e, ts] : edgeUses(tris)) {
        if (ts.size() == 1) {
            ++m.open;
        } else if (ts.size() > 2) {
            if (m.nonManifold++ == 0) m.firstNonManifold = ts[0];
            m.mostTriangles = std::max(m.mostTriangles, int(ts.size()));
        }
    }
    return m;
}

std::vector<std::vector<int>> dualGraph(const std::vector<AtlasTriangle>& tris) {
    std::vector<std::vector<int>> g(tris.size());
    for (const auto& [e, ts] : edgeUses(tris)) {
        if (ts.size() > 2)
            throw InputError("--mip: triangle " + std::to_string(tris[size_t(ts[0])].index) + " of object " +
                             std::to_string(tris[size_t(ts[0])].object) + ": an edge shared by " +
                             std::to_string(ts.size()) + " triangles (non-manifold); the partition needs a manifold mesh");
        if (ts.size() == 2 && ts[0] != ts[1]) {
            g[size_t(ts[0])].push_back(ts[1]);
            g[size_t(ts[1])].push_back(ts[0]);
        }
    }
    return g;
}

Atlas buildMultiresAtlas(std::vector<AtlasTriangle> tris, const AtlasOptions& opt) {
    if (!isPow2(opt.size))
        throw InputError("--size: " + std::to_string(opt.size) + " is not a power of two (the MIP levels halve it)");
    if (tris.empty()) throw InputError("--size: no triangles to place");
    prepareTriangles(tris);
    Atlas a;
    a.options = opt;
    a.triangles = std::move(tris);
    a.charts.assign(a.triangles.size(), Chart{});
    a.eq3Edge = double(opt.size) / std::ceil(std::sqrt(double(a.triangles.size()) / 2.0));
    const std::vector<std::vector<int>> dual = dualGraph(a.triangles);
    const std::vector<std::array<int, 2>> pairs = pairTriangles(dual);
    const int P = int(pairs.size());
    // A pair's shared edge becomes both charts' hypotenuse, end to end: the first triangle's
    // x[1], x[2] are the second's x[2], x[1], so the texels either side of the cell's diagonal
    // (which MIP levels up to lg a average) are neighbours on the surface.
    for (const auto& pr : pairs) {
        if (pr[1] < 0) continue;
        AtlasTriangle& A = a.triangles[size_t(pr[0])];
        AtlasTriangle& B = a.triangles[size_t(pr[1])];
        auto onB = [&](const glm::dvec3& p) { return p == B.x[0] || p == B.x[1] || p == B.x[2]; };
        int k = 0;
        while (k < 3 && onB(A.x[size_t(k)])) ++k;
        std::rotate(A.x.begin(), A.x.begin() + k, A.x.end());
        std::rotate(A.s.begin(), A.s.begin() + k, A.s.end());
        const AtlasTriangle old = B;
        int j = 0;
        while (j < 3 && (old.x[size_t(j)] == A.x[1] || old.x[size_t(j)] == A.x[2])) ++j;
        B.x[0] = old.x[size_t(j)];
        B.s[0] = old.s[size_t(j)];
        for (int i = 0; i < 3; ++i) {
            if (old.x[size_t(i)] == A.x[2]) B.x[1] = old.x[size_t(i)], B.s[1] = old.s[size_t(i)];
            if (old.x[size_t(i)] == A.x[1]) B.x[2] = old.x[size_t(i)], B.s[2] = old.s[size_t(i)];
        }
    }
    // Pair cells are a x a texels, a a power of two, legs a - pad inside (seam-free: the
    // overscan and the bilinear border; the standard layout's charts fill the cell).
    const int m = opt.magnification == Magnification::Bilinear ? 1 : 0;
    const int pad = opt.seamFree ? 2 + 2 * m : 0;
    int minCell = 1;
    while (minCell < kMinLegs + pad) minCell *= 2;
    const long long H2 = (long long)opt.size * opt.size;
    if (minCell > opt.size || (long long)P * minCell * minCell > H2) {
        const long long held = minCell > opt.size ? 0 : H2 / ((long long)minCell * minCell);
        throw InputError("--size: " + std::to_string(a.triangles.size()) + " triangles (" + std::to_string(P) +
                         " pairs) do not fit a " + std::to_string(opt.size) + " x " + std::to_string(opt.size) +
                         " multiresolution atlas (it holds " + std::to_string(held) + " pairs in " +
                         std::to_string(minCell) + " x " + std::to_string(minCell) + " cells)");
    }
    std::vector<int> cell(static_cast<size_t>(P));
    std::vector<double> target;  // non-uniform: the side each pair's weight asks for
    if (opt.kind == AtlasKind::Uniform) {
        // Section 4.3: the largest power of two a with (H / a)^2 >= P cells.
        int c = opt.size;
        while ((long long)(opt.size / c) * (opt.size / c) < P) c /= 2;
        std::fill(cell.begin(), cell.end(), c);
    } else {
        // Section 4.2's weights on pairs: the RMS of the pair's sqrt(area) or longest edge.
        std::vector<double> w(static_cast<size_t>(P));
        for (int p = 0; p < P; ++p) {
            double sum2 = 0;
            int count = 0;
            for (int t : pairs[size_t(p)])
                if (t >= 0) {
                    const AtlasTriangle& tr = a.triangles[size_t(t)];
                    const double wt = opt.kind == AtlasKind::Area ? std::sqrt(tr.area()) : tr.longestEdge();
                    sum2 += wt * wt, ++count;
                }
            w[size_t(p)] = std::sqrt(sum2 / count);
        }
        target = weightedCells(w, opt.size, pad, minCell, cell);
    }
    // The pairs' graph: adjacent when any of their triangles are.
    std::vector<int> pairOf(a.triangles.size());
    for (int p = 0; p < P; ++p)
        for (int t : pairs[size_t(p)])
            if (t >= 0) pairOf[size_t(t)] = p;
    std::vector<std::vector<int>> pg(static_cast<size_t>(P));
    for (size_t t = 0; t < dual.size(); ++t)
        for (int u : dual[t])
            if (pairOf[t] != pairOf[size_t(u)]) pg[size_t(pairOf[t])].push_back(pairOf[size_t(u)]);
    for (auto& v : pg) {
        std::sort(v.begin(), v.end());
        v.erase(std::unique(v.begin(), v.end()), v.end());
    }
    std::vector<int> all(static_cast<size_t>(P));
    std::iota(all.begin(), all.end(), 0);
    Quadtree tree{pg, cell, target, minCell, std::vector<glm::ivec2>(static_cast<size_t>(P))};
    if (!target.empty()) tree.fit(all, opt.size);
    tree.place(all, 0, 0, opt.size);
    const std::vector<glm::ivec2>& origin = tree.origin;
    a.mipCell = *std::max_element(cell.begin(), cell.end());
    for (int p = 0; p < P; ++p)
        for (int k = 0; k < 2; ++k) {
            const int t = pairs[size_t(p)][size_t(k)];
            if (t < 0) continue;
            Chart& c = a.charts[size_t(t)];
            c.legs = cell[size_t(p)] - pad;
            c.cell = origin[size_t(p)];
            c.second = k == 1;
        }
    a.stripCount = 0;
    a.placeCharts();
    return a;
}

std::vector<Image> mipLevels(const Image& texels, const std::vector<int>& owners) {
    // Channel 4: the written texels' share of the texel (0 = background), the lookup's weight.
    Image base(texels.width, texels.height, 5);
    for (int y = 0; y < texels.height; ++y)
        for (int x = 0; x < texels.width; ++x) {
            const bool written = owners[size_t(y) * texels.width + x] >= 0;
            for (int c = 0; c < 4; ++c) base.pixel(x, y)[c] = written ? texels.pixel(x, y)[c] : 0.f;
            base.pixel(x, y)[4] = written ? 1.f : 0.f;
        }
    std::vector<Image> levels{base};
    while (levels.back().width > 1) {
        const Image& lo = levels.back();
        const int W = lo.width / 2;
        Image hi(W, W, 5);
        for (int y = 0; y < W; ++y)
            for (int x = 0; x < W; ++x) {
                double acc[4] = {0, 0, 0, 0}, w = 0;
                for (int k = 0; k < 4; ++k) {
                    const float* p = lo.pixel(2 * x + (k & 1), 2 * y + (k >> 1));
                    for (int c = 0; c < 4; ++c) acc[c] += double(p[4]) * p[c];
                    w += p[4];
                }
                float* q = hi.pixel(x, y);
                for (int c = 0; c < 4; ++c) q[c] = w > 0 ? float(acc[c] / w) : 0.f;
                q[4] = float(w / 4);
            }
        levels.push_back(std::move(hi));
    }
    return levels;
}

std::vector<long long> mipMixing(const Atlas& a, const std::vector<std::vector<int>>& dual) {
    const std::vector<int> own = a.owners();
    const int H = a.size();
    std::vector<long long> out;
    for (int s = 1; s <= H; s *= 2) {
        long long bad = 0;
        for (int by = 0; by < H; by += s)
            for (int bx = 0; bx < H; bx += s) {
                std::vector<int> ts;
                for (int y = by; y < by + s; ++y)
                    for (int x = bx; x < bx + s; ++x)
                        if (int t = own[size_t(y) * H + x]; t >= 0) ts.push_back(t);
                std::sort(ts.begin(), ts.end());
                ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
                if (ts.size() < 2) continue;
                // Connected within the block's triangles? (a search from the first)
                std::vector<char> seen(ts.size(), 0);
                std::vector<size_t> stack{0};
                seen[0] = 1;
                size_t reached = 1;
                while (!stack.empty()) {
                    const size_t i = stack.back();
                    stack.pop_back();
                    for (int u : dual[size_t(ts[i])]) {
                        auto it = std::lower_bound(ts.begin(), ts.end(), u);
                        if (it != ts.end() && *it == u && !seen[size_t(it - ts.begin())]) {
                            seen[size_t(it - ts.begin())] = 1;
                            ++reached;
                            stack.push_back(size_t(it - ts.begin()));
                        }
                    }
                }
                bad += reached != ts.size();
            }
        out.push_back(bad);
    }
    return out;
}

glm::dvec4 lookupTrilinear(const std::vector<Image>& levels, const glm::dvec2& u, const glm::dvec2& dudx,
                           const glm::dvec2& dudy) {
    auto bilinear = [&](int l, const glm::dvec2& p) {
        const Image& im = levels[size_t(l)];
        const double x = p.x - 0.5, y = p.y - 0.5;
        const int i = int(std::floor(x)), j = int(std::floor(y));
        const double fx = x - i, fy = y - j;
        // Weighted by the texels' written share, so background never darkens a chart's edge.
        glm::dvec4 c(0.0);
        double wsum = 0;
        auto tap = [&](int ii, int jj, double w) {
            ii = std::clamp(ii, 0, im.width - 1);
            jj = std::clamp(jj, 0, im.height - 1);
            const float* px = im.pixel(ii, jj);
            c += w * px[4] * glm::dvec4(px[0], px[1], px[2], px[3]);
            wsum += w * px[4];
        };
        tap(i, j, (1 - fx) * (1 - fy));
        tap(i + 1, j, fx * (1 - fy));
        tap(i, j + 1, (1 - fx) * fy);
        tap(i + 1, j + 1, fx * fy);
        return wsum > 0 ? c / wsum : c;
    };
    // Level of detail: lg of the longer screen-pixel step in texels (the usual MIP rule).
    const double rho = std::max(std::hypot(dudx.x, dudx.y), std::hypot(dudy.x, dudy.y));
    const double lambda = std::clamp(rho > 0 ? std::log2(rho) : 0.0, 0.0, double(levels.size() - 1));
    const int l0 = int(std::floor(lambda));
    const int l1 = std::min(l0 + 1, int(levels.size()) - 1);
    const double f = lambda - l0;
    const glm::dvec4 c0 = bilinear(l0, u / double(1 << l0));
    if (f == 0 || l1 == l0) return c0;
    return c0 * (1 - f) + bilinear(l1, u / double(1 << l1)) * f;
}

}  // namespace pst

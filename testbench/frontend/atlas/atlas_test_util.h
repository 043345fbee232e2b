// Helpers of the atlas tests (atlas_test.cpp, multires_test.cpp): triangles, options, packing checks.
#pragma once

#include "atlas.h"
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include "atlas_render.h"
#include "input_error.h"
#include "mesh.h"
#include "multires.h"

namespace pst::atlas_test {


// A right triangle in the z = 0 plane with legs (p, q): area p q / 2, longest edge sqrt(p^2+q^2).
inline AtlasTriangle rightTriangle(double p, double q, int index) {
    AtlasTriangle t;
    t.index = index;
    t.x = {glm::dvec3(0, 0, 0), glm::dvec3(p, 0, 0), glm::dvec3(0, q, 0)};
    t.s = t.x;
    return t;
}

inline std::vector<AtlasTriangle> meshTriangles(const Mesh& m) {
    std::vector<AtlasTriangle> out;
    for (size_t i = 0; i < m.triangles.size(); ++i) {
        const auto& tr = m.triangles[i];
        if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2]) continue;
        AtlasTriangle t;
        t.index = int(i);
        for (int k = 0; k < 3; ++k) {
            t.x[size_t(k)] = m.positions[tr[size_t(k)]];
            t.s[size_t(k)] = m.texcoords[tr[size_t(k)]];
        }
        out.push_back(t);
    }
    return out;
}

inline AtlasOptions opts(AtlasKind k, int size, Magnification m, bool seamFree = true) {
    AtlasOptions o;
    o.kind = k;
    o.size = size;
    o.magnification = m;
    o.seamFree = seamFree;
    return o;
}

// Chart images scale by (1 - kChartInset) about their centroid: areas by its square.
constexpr double kInsetArea = (1 - kChartInset) * (1 - kChartInset);

// Every texel claimed by at most one chart, and every claimed texel inside the atlas.
inline void expectPacked(const Atlas& a) {
    std::vector<int> claims(size_t(a.size()) * a.size(), 0);
    for (size_t t = 0; t < a.charts.size(); ++t) {
        for (const glm::ivec2& p : a.footprint(int(t))) {
            ASSERT_GE(p.x, 0);
            ASSERT_GE(p.y, 0);
            ASSERT_LT(p.x, a.size());
            ASSERT_LT(p.y, a.size());
            ++claims[size_t(p.y) * a.size() + p.x];
        }
        for (const glm::dvec2& u : a.charts[t].u) {
            EXPECT_GE(u.x, 0.0);
            EXPECT_GE(u.y, 0.0);
            EXPECT_LE(u.x, a.size());
            EXPECT_LE(u.y, a.size());
        }
    }
    for (int c : claims) ASSERT_LE(c, 1);
}

// The seam rule (Fig. 2, 4c, section 6.3): a lookup anywhere on a chart (inside, on its edges
// and at its vertices) reads only the chart's own texels with the seam-free layout for its
// filter; the standard layout, and bilinear lookups into the nearest layout, read others.
inline size_t seamLookups(const Atlas& a, Magnification filter) {
    const std::vector<int> own = a.owners();
    const std::vector<float> rgba(own.size() * 4, 0.f);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    size_t seams = 0;
    for (int t = 0; t < int(a.charts.size()); ++t) {
        std::vector<glm::dvec3> bs = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
        for (int k = 0; k < 200; ++k) {
            double p = U(rng), q = U(rng);
            if (p + q > 1) p = 1 - p, q = 1 - q;
            bs.push_back({1 - p - q, p, q});
            bs.push_back({1 - p, p, 0});  // on the edges
            bs.push_back({0, p, 1 - p});
            bs.push_back({1 - p, 0, p});
        }
        for (const glm::dvec3& b : bs)
            seams += lookupAtlas(rgba, own, a.size(), t, chartPoint(a, t, b), filter).touchedForeign;
    }
    return seams;
}

}  // namespace pst::atlas_test

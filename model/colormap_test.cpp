// Tests of the colour map filters against hand-computed values and brute-force averages.
#include "colormap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

namespace pst {
namespace {

std::vector<glm::dvec4> randomEntries(int n, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> d(0.0, 1.0);
    std::vector<glm::dvec4> e(n);
    for (auto& c : e) c = glm::dvec4(d(rng), d(rng), d(rng), d(rng));
    return e;
}

// Brute-force extension of the table (independent of ColorMap::at).
glm::dvec4 entry(const std::vector<glm::dvec4>& e, long long i, WrapMode wrap) {
    const long long n = static_cast<long long>(e.size());
    if (wrap == WrapMode::Mod) {
        while (i < 0) i += n * (1 + (-i) / n);
        return e[i % n];
    }
    return e[i < 0 ? 0 : (i >= n ? n - 1 : i)];
}

// Box: exact per-entry overlap of [u - W/2, u + W/2].
glm::dvec4 bruteBox(const std::vector<glm::dvec4>& e, WrapMode wrap, double f, double w) {
    const double n = double(e.size()), u = f * n, W = w * n;
    const double a = u - W / 2, b = u + W / 2;
    glm::dvec4 sum(0.0);
    for (long long i = (long long)std::floor(a); i <= (long long)std::floor(b); ++i) {
        const double len = std::min(b, double(i + 1)) - std::max(a, double(i));
        if (len > 0) sum += len * entry(e, i, wrap);
    }
    return sum / (b - a);
}

// Sat: loop sum of entries lo+1..hi over hi - lo (entry hi if empty).
glm::dvec4 bruteSat(const std::vector<glm::dvec4>& e, WrapMode wrap, double f, double w) {
    const double n = double(e.size()), u = f * n, W = w * n;
    const long long lo = (long long)std::floor(u - 0.5 * W);
    const long long hi = (long long)std::floor(u + 0.5 * W);
    if (hi == lo) return entry(e, hi, wrap);
    glm::dvec4 sum(0.0);
    for (long long i = lo + 1; i <= hi; ++i) sum += entry(e, i, wrap);
    return sum / double(hi - lo);
}

// Mip: levels by brute averaging 2^L level-0 entries.
glm::dvec4 bruteMip(const std::vector<glm::dvec4>& e, WrapMode wrap, double f, double w,
                    bool blend) {
    const long long n = (long long)e.size();
    const double u = f * n, W = w * n;
    if (W <= 1) return entry(e, (long long)std::floor(u), wrap);
    int lgN = 0;
    while ((1LL << lgN) < n) ++lgN;
    auto level = [&](int L) {
        const long long span = 1LL << L, m = n / span;
        long long j = (long long)std::floor(u / double(span));
        j = wrap == WrapMode::Mod ? ((j % m) + m) % m : std::min(std::max(j, 0LL), m - 1);
        glm::dvec4 s(0.0);
        for (long long k = 0; k < span; ++k) s += e[j * span + k];
        return s / double(span);
    };
    const double Lf = std::log2(W);
    int L = (int)std::floor(Lf);
    if (L >= lgN) return level(lgN);
    if (!blend) return level(L);
    const double t = Lf - L;
    return (1 - t) * level(L) + t * level(L + 1);
}

void expectNear(const glm::dvec4& a, const glm::dvec4& b, double tol, const char* what,
                double f, double w) {
    for (int c = 0; c < 4; ++c)
        ASSERT_NEAR(a[c], b[c], tol) << what << " f = " << f << " w = " << w << " channel " << c;
}

// A scalar map c = {1, 2, 4, 8} in every channel (scaled per channel) for hand-computed cases.
ColorMap handMap(WrapMode wrap) {
    std::vector<glm::dvec4> e;
    for (double c : {1.0, 2.0, 4.0, 8.0}) e.push_back(glm::dvec4(c, 10 * c, -c, 1.0));
    return ColorMap(e, wrap);
}
glm::dvec4 scalar(double c) { return glm::dvec4(c, 10 * c, -c, 1.0); }

// N = 4: f = u / 4, w = W / 4.
TEST(ColorMap, HandComputedMod) {
    const ColorMap m = handMap(WrapMode::Mod);
    const double eps = 1e-12;
    auto F = [](double u) { return u / 4; };
    // point samples: entry floor(u) mod 4
    expectNear(m.sample(F(2.5)), scalar(4), eps, "sample", 2.5, 0);
    expectNear(m.sample(F(-0.5)), scalar(8), eps, "sample", -0.5, 0);
    expectNear(m.sample(F(4.0)), scalar(1), eps, "sample", 4, 0);
    // Sat: W >= N -> table mean 15/4
    expectNear(m.filterSat(F(1.3), F(5)), scalar(3.75), eps, "sat w>=N", 1.3, 5);
    // Sat eq. 15: u=0.5, W=3: lo=-1, hi=2 -> (1+2+4)/3
    expectNear(m.filterSat(F(0.5), F(3)), scalar(7.0 / 3), eps, "sat", 0.5, 3);
    // Sat past the upper end: u=3.5, W=2: entries 3,4 -> (8+1)/2
    expectNear(m.filterSat(F(3.5), F(2)), scalar(4.5), eps, "sat hi>=N", 3.5, 2);
    // Sat past the lower end: u=0.25, W=3: lo=-2, hi=1 -> entries -1,0,1 -> (8+1+2)/3
    expectNear(m.filterSat(F(0.25), F(3)), scalar(11.0 / 3), eps, "sat lo<-1", 0.25, 3);
    // Sat, same case far from [0, 1): shifted by 37 periods
    expectNear(m.filterSat(F(0.25 - 4 * 37), F(3)), scalar(11.0 / 3), eps, "sat far", -147.75, 3);
    // Sat window inside one entry: entry hi
    expectNear(m.filterSat(F(2.5), F(0.5)), scalar(4), eps, "sat narrow", 2.5, 0.5);
    expectNear(m.filterSat(F(2.9), F(0.5)), scalar(8), eps, "sat narrow next", 2.9, 0.5);
    // Box: [2.5, 4.5] -> (0.5*4 + 8 + 0.5*1)/2
    expectNear(m.filterBox(F(3.5), F(2)), scalar(5.25), eps, "box", 3.5, 2);
    // Box: [-0.75, 1.25] -> (0.75*8 + 1 + 0.25*2)/2
    expectNear(m.filterBox(F(0.25), F(2)), scalar(3.75), eps, "box", 0.25, 2);
    // Box: W = 2.5 periods + ... [0, 10] -> 2 periods (30) + 1 + 2 = 33 / 10
    expectNear(m.filterBox(F(5), F(10)), scalar(3.3), eps, "box periods", 5, 10);
    // Mip: levels {1,2,4,8}, {1.5, 6}, {3.75}
    expectNear(m.filterMip(F(2.5), F(0.5), false), scalar(4), eps, "mip W<1", 2.5, 0.5);
    expectNear(m.filterMip(F(2.5), F(2.5), false), scalar(6), eps, "mip L1", 2.5, 2.5);
    const double t = std::log2(2.5) - 1;
    expectNear(m.filterMip(F(2.5), F(2.5), true), scalar(6 + t * (3.75 - 6)), eps, "mip blend",
               2.5, 2.5);
    expectNear(m.filterMip(F(-0.5), F(3), false), scalar(6), eps, "mip wrap", -0.5, 3);
    expectNear(m.filterMip(F(-0.5), F(100), true), scalar(3.75), eps, "mip top", -0.5, 100);
}

TEST(ColorMap, HandComputedClamp) {
    const ColorMap m = handMap(WrapMode::Clamp);
    const double eps = 1e-12;
    auto F = [](double u) { return u / 4; };
    expectNear(m.sample(F(-0.5)), scalar(1), eps, "sample", -0.5, 0);
    expectNear(m.sample(F(4.0)), scalar(8), eps, "sample", 4, 0);
    // Sat past the upper end: entries 3,4 -> (8+8)/2
    expectNear(m.filterSat(F(3.5), F(2)), scalar(8), eps, "sat hi>=N", 3.5, 2);
    // Sat past the lower end: entries -1,0,1 -> (1+1+2)/3
    expectNear(m.filterSat(F(0.25), F(3)), scalar(4.0 / 3), eps, "sat lo<-1", 0.25, 3);
    // Sat past both ends (W >= N is NOT the table mean): u=2, W=8: entries -1..6
    // -> (1 + 15 + 3*8)/8
    expectNear(m.filterSat(F(2), F(8)), scalar(5), eps, "sat both", 2, 8);
    // Entirely past one end
    expectNear(m.filterSat(F(4e6), F(3)), scalar(8), eps, "sat above", 4e6, 3);
    expectNear(m.filterSat(F(-149.2), F(3)), scalar(1), eps, "sat below", -149.2, 3);
    // Box: [2.5, 4.5] -> (0.5*4 + 8 + 0.5*8)/2
    expectNear(m.filterBox(F(3.5), F(2)), scalar(7), eps, "box", 3.5, 2);
    // Box: [-1.25, 1.75] -> (1.25*1 + 1 + 0.75*2)/3
    expectNear(m.filterBox(F(0.25), F(3)), scalar(1.25), eps, "box", 0.25, 3);
    // Box: [-2, 6] -> (2*1 + 15 + 2*8)/8
    expectNear(m.filterBox(F(2), F(8)), scalar(33.0 / 8), eps, "box both", 2, 8);
    // Mip clamps at each level's own size
    expectNear(m.filterMip(F(-0.5), F(3), false), scalar(1.5), eps, "mip clamp", -0.5, 3);
    expectNear(m.filterMip(F(9.5), F(3), false), scalar(6), eps, "mip clamp", 9.5, 3);
}

TEST(ColorMap, Construction) {
    EXPECT_THROW(ColorMap({}, WrapMode::Mod), std::invalid_argument);
    EXPECT_THROW(ColorMap(std::vector<glm::dvec4>(3), WrapMode::Mod), std::invalid_argument);
    EXPECT_THROW(ColorMap(std::vector<glm::dvec4>(6), WrapMode::Clamp), std::invalid_argument);
    std::mt19937_64 rng(1);
    for (int n : {1, 2, 8, 256}) {
        auto e = randomEntries(n, rng);
        ColorMap m(e, WrapMode::Clamp);
        ASSERT_EQ(m.size(), n);
        int lgN = 0;
        while ((1 << lgN) < n) ++lgN;
        ASSERT_EQ(m.mipLevels(), lgN + 1);
        glm::dvec4 acc(0.0);
        for (int i = 0; i < n; ++i) {
            acc += e[i];
            expectNear(m.sat()[i], acc, 1e-12, "csat", i, 0);  // eq. 13
        }
        for (int L = 0; L <= lgN; ++L) {
            const int span = 1 << L;
            ASSERT_EQ((int)m.mipLevel(L).size(), n >> L);
            for (int j = 0; j < (n >> L); ++j) {
                glm::dvec4 s(0.0);
                for (int k = 0; k < span; ++k) s += e[j * span + k];
                expectNear(m.mipLevel(L)[j], s / double(span), 1e-12, "mip level", L, j);
            }
        }
    }
    // An empty map gives transparent black.
    ColorMap empty;
    EXPECT_EQ(empty.sample(0.3), glm::dvec4(0.0));
    EXPECT_EQ(empty.filter(0.3, 0.1, FilterKind::Box), glm::dvec4(0.0));
}

// Every filter against brute force for random (f, w) over all table sizes and wrap modes.
TEST(ColorMap, FiltersMatchBruteForce) {
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n : {1, 2, 8, 256})
        for (WrapMode wrap : {WrapMode::Mod, WrapMode::Clamp}) {
            const auto e = randomEntries(n, rng);
            const ColorMap m(e, wrap);
            glm::dvec4 mean(0.0);
            for (const auto& c : e) mean += c / double(n);
            int cases[6] = {};  // W<1, W in [1,N), W>=N, past upper, past lower, past both
            for (int k = 0; k < 20000; ++k) {
                // f: mostly near [0, 1], sometimes far outside.
                double f;
                switch (k % 8) {
                case 0: f = -37.3 + unit(rng) * 0.1; break;
                case 1: f = 1e6 + unit(rng); break;
                case 2: f = unit(rng) < 0.5 ? unit(rng) * 0.05 : 1.0 - unit(rng) * 0.05; break;
                default: f = -0.5 + 2.0 * unit(rng);
                }
                // W = w N: log-uniform over [1e-3, 6 N].
                const double W = std::exp(std::log(1e-3) + unit(rng) * std::log(6e3 * n));
                const double w = W / n;
                const double u = f * n;
                cases[W < 1 ? 0 : (W < n ? 1 : 2)]++;
                const bool up = u + W / 2 >= n, down = u - W / 2 < 0;
                if (up && down) cases[5]++;
                else if (up) cases[3]++;
                else if (down) cases[4]++;

                // Box: exact; tolerance covers the rounding of u +- W/2 at large |u|.
                const double tolBox = 1e-10 + 64 * 2.2e-16 * (std::abs(u) + W) / W;
                expectNear(m.filterBox(f, w), bruteBox(e, wrap, f, w), tolBox, "box", f, w);
                // Sat: the paper's integer form; w >= N in mod is the table mean.
                const glm::dvec4 sat =
                    wrap == WrapMode::Mod && W >= n ? mean : bruteSat(e, wrap, f, w);
                expectNear(m.filterSat(f, w), sat, 1e-9, "sat", f, w);
                expectNear(m.filterSat3N(f, w), sat, 1e-9, "sat3N", f, w);
                expectNear(m.filterMip(f, w, false), bruteMip(e, wrap, f, w, false), 1e-12,
                           "mip", f, w);
                expectNear(m.filterMip(f, w, true), bruteMip(e, wrap, f, w, true), 1e-12,
                           "mip_linear", f, w);
                expectNear(m.filter(f, w, FilterKind::Box), m.filterBox(f, w), 0, "dispatch", f, w);
            }
            for (int c = 0; c < 6; ++c)  // (W in [1, N) is empty for N = 1)
                if (!(c == 1 && n == 1)) {
                    EXPECT_GT(cases[c], 100) << "case " << c << " N " << n;
                }
        }
}

// Trapezoid: the mean of bruteBox(width Wa) over centres in [u - Wb/2, u + Wb/2]. bruteBox is
// linear in the centre between the breakpoints k +- Wa/2 (k integer), so the trapezoid rule over
// the breakpoints is exact.
glm::dvec4 bruteTrapezoid(const std::vector<glm::dvec4>& e, WrapMode wrap, double f, double wa, double wb) {
    const double n = double(e.size()), u = f * n, Wa = wa * n, Wb = wb * n;
    if (Wb <= 0) return bruteBox(e, wrap, f, wa);
    const double lo = u - Wb / 2, hi = u + Wb / 2;
    std::vector<double> xs{lo, hi};
    for (double h : {Wa / 2, -Wa / 2})
        for (double k = std::ceil(lo - h); k + h < hi; ++k) xs.push_back(k + h);
    std::sort(xs.begin(), xs.end());
    glm::dvec4 sum(0.0);
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
        const double a = xs[i], b = xs[i + 1];
        if (b > a) sum += 0.5 * (b - a) * (bruteBox(e, wrap, a / n, wa) + bruteBox(e, wrap, b / n, wa));
    }
    return sum / Wb;
}

TEST(ColorMap, TrapezoidMatchesBruteForce) {
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n : {1, 2, 8, 64})
        for (WrapMode wrap : {WrapMode::Mod, WrapMode::Clamp}) {
            const auto e = randomEntries(n, rng);
            const ColorMap m(e, wrap);
            int wide = 0;
            for (int k = 0; k < 300; ++k) {
                double f = k % 5 == 0 ? -3.3 + unit(rng) : -0.5 + 2.0 * unit(rng);
                // Widths in entries log-uniform over [1e-3, 2.5 N], one of them 0 now and then.
                auto width = [&] { return std::exp(std::log(1e-3) + unit(rng) * std::log(2.5e3 * n)) / n; };
                const double wx = k % 7 == 0 ? 0.0 : width(), wy = width();
                wide += std::max(wx, wy) * n >= n;
                const glm::dvec4 want = bruteTrapezoid(e, wrap, f, std::max(wx, wy), std::min(wx, wy));
                expectNear(m.filterTrapezoid(f, wx, wy), want, 1e-9, "trapezoid", f, wx);
                expectNear(m.filterTrapezoid(f, wy, wx), want, 1e-9, "trapezoid swapped", f, wy);
            }
            EXPECT_GT(wide, 30) << "N " << n;
        }
    // One width 0: the box; both 0: the point sample.
    const ColorMap m(randomEntries(16, rng), WrapMode::Mod);
    EXPECT_EQ(m.filterTrapezoid(0.3, 0.2, 0.0), m.filterBox(0.3, 0.2));
    EXPECT_EQ(m.filterTrapezoid(0.3, 0.0, 0.0), m.sample(0.3));
    EXPECT_EQ(m.filter(0.3, 0.2, FilterKind::Trapezoid), m.filterBox(0.3, 0.2));
}

// Mod, many periods wide (the closed form for whole periods): the brute force over a 64-entry
// table with widths up to 9 periods.
// Widths so small that their product underflows (a filtered-away noise's gradient): the point
// sample's box, not 0/0.
TEST(ColorMap, TrapezoidOfVanishingWidthsIsFinite) {
    std::mt19937_64 rng(5);
    for (WrapMode wrap : {WrapMode::Mod, WrapMode::Clamp}) {
        const ColorMap m(randomEntries(16, rng), wrap);
        const glm::dvec4 c = m.filterTrapezoid(0.37, 1e-170, 1e-200), box = m.filterBox(0.37, 1e-170);
        for (int k = 0; k < 4; ++k) {
            EXPECT_TRUE(std::isfinite(c[k]));
            EXPECT_NEAR(c[k], box[k], 1e-12);
        }
    }
}

TEST(ColorMap, TrapezoidManyPeriods) {
    std::mt19937_64 rng(78);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto e = randomEntries(8, rng);
    const ColorMap m(e, WrapMode::Mod);
    for (int k = 0; k < 200; ++k) {
        const double f = -2 + 4 * unit(rng), wa = 9 * unit(rng), wb = wa * unit(rng);
        expectNear(m.filterTrapezoid(f, wa, wb), bruteTrapezoid(e, WrapMode::Mod, f, wa, wb), 1e-9, "periods", f, wa);
    }
}

// The reason for the filter: f linear over a square pixel, f = f0 + gx (x - 1/2) + gy (y - 1/2),
// point-sampled on a fine grid, averages to the trapezoid; the box of the euclidean width does not.
TEST(ColorMap, TrapezoidIsTheLinearPixelMean) {
    std::mt19937_64 rng(79);
    const auto e = randomEntries(8, rng);
    const ColorMap m(e, WrapMode::Mod);
    const int G = 1000;
    double worstTrap = 0, worstBox = 0;
    for (auto [f0, gx, gy] : {std::tuple{0.41, 0.3, 0.3}, std::tuple{0.1, 0.5, 0.2}, std::tuple{0.77, 0.12, 0.9}}) {
        glm::dvec4 mean(0.0);
        for (int i = 0; i < G; ++i)
            for (int j = 0; j < G; ++j)
                mean += m.sample(f0 + gx * ((i + 0.5) / G - 0.5) + gy * ((j + 0.5) / G - 0.5));
        mean /= double(G) * G;
        const glm::dvec4 trap = m.filterTrapezoid(f0, gx, gy), box = m.filterBox(f0, std::hypot(gx, gy));
        for (int c = 0; c < 4; ++c) {
            worstTrap = std::max(worstTrap, std::abs(trap[c] - mean[c]));
            worstBox = std::max(worstBox, std::abs(box[c] - mean[c]));
        }
    }
    EXPECT_LT(worstTrap, 2e-3);  // the grid's own error: O(1 / G) per entry crossing
    EXPECT_GT(worstBox, 2e-2);
}

TEST(ColorMap, SatMeanOfWholeTable) {
    // Mod, W >= N: csat[N-1]/N exactly as the paper says; Box agrees when W is whole periods.
    std::mt19937_64 rng(4);
    for (int n : {1, 2, 8, 256}) {
        const auto e = randomEntries(n, rng);
        const ColorMap m(e, WrapMode::Mod);
        glm::dvec4 mean(0.0);
        for (auto& c : e) mean += c;
        mean /= double(n);
        for (double f : {-37.3, 0.2, 1e6}) {
            expectNear(m.filterSat(f, 1.0), mean, 1e-12, "sat", f, 1.0);
            expectNear(m.filterSat(f, 3.7), mean, 1e-12, "sat", f, 3.7);
            expectNear(m.filterBox(f, 3.0), mean, 1e-9, "box", f, 3.0);
            expectNear(m.filterMip(f, 1.0, true), mean, 1e-12, "mip", f, 1.0);
        }
    }
}

TEST(ColorMap, DegenerateInputs) {
    std::mt19937_64 rng(6);
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (WrapMode wrap : {WrapMode::Mod, WrapMode::Clamp}) {
        const auto e = randomEntries(8, rng);
        const ColorMap m(e, wrap);
        const FilterKind kinds[] = {FilterKind::None, FilterKind::MipNearest, FilterKind::MipLinear,
                                    FilterKind::Sat, FilterKind::Box, FilterKind::Trapezoid};
        for (FilterKind k : kinds) {
            // w <= 0 (or NaN) is the point sample for every kind.
            for (double w : {0.0, -1.0, nan})
                for (double f : {0.3, -2.7, 1e6})
                    EXPECT_EQ(m.filter(f, w, k), m.sample(f)) << toString(k);
            // Non-finite and huge inputs do not crash and stay within the table's range.
            for (double f : {nan, inf, -inf, 1e300, -1e300})
                for (double w : {0.01, 1e300, inf}) {
                    const glm::dvec4 c = m.filter(f, w, k);
                    for (int ch = 0; ch < 4; ++ch) EXPECT_TRUE(c[ch] >= -1e-9 && c[ch] <= 1 + 1e-9);
                }
        }
        EXPECT_EQ(m.sample(nan), m.sample(0.0));
        EXPECT_EQ(m.sample(inf), m.at(wrap == WrapMode::Clamp ? 7 : 0));
        if (wrap == WrapMode::Clamp) {
            EXPECT_EQ(m.sample(-inf), e[0]);
        }
    }
}

TEST(ColorMap, EnumNamesRoundTrip) {
    for (WrapMode v : {WrapMode::Mod, WrapMode::Clamp}) {
        WrapMode r;
        ASSERT_TRUE(parseWrapMode(toString(v), &r));
        EXPECT_EQ(r, v);
    }
    for (FilterKind v : {FilterKind::None, FilterKind::MipNearest, FilterKind::MipLinear,
                         FilterKind::Sat, FilterKind::Box, FilterKind::Trapezoid}) {
        FilterKind r;
        ASSERT_TRUE(parseFilterKind(toString(v), &r));
        EXPECT_EQ(r, v);
    }
    EXPECT_STREQ(toString(FilterKind::MipNearest), "mip");
    EXPECT_STREQ(toString(FilterKind::MipLinear), "mip_linear");
    EXPECT_STREQ(toString(WrapMode::Clamp), "clamp");
    WrapMode w;
    FilterKind k;
    EXPECT_FALSE(parseWrapMode("wrap", &w));
    EXPECT_FALSE(parseFilterKind("trilinear", &k));
}

}  // namespace
}  // namespace pst

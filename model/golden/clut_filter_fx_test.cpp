// Golden colour-table filter against the double reference (model/colormap.cpp) on the SAME
// quantized colours, for the profiles' N and a few synthetic profiles (other N, FFrac < Log2Clut).
//
// Bounds (in LSBs of ColourBits, reference value v = ColorMap result * (2^CB - 1)):
//   point (kind 0, MIP with W < 1), SAT single-entry cases: exact.
//   SAT mod W >= N (whole-table mean, the paper's rule, also the reference's): <= 1/2.
//   SAT otherwise: <= 1/2 + v |c recip[c] - 2^RF| / 2^RF (final rounding + reciprocal rounding,
//     c = count); the integer window sum itself is checked EXACTLY against a brute-force sum
//     of the extended map over the reference's own window (floor(u -+ W/2) in double).
//     Full profile: the bound stays below 1 LSB everywhere (checked); the reduced profile's
//     12-bit reciprocal gives larger errors for wide windows (reported, bounded per vector).
//   MIP nearest: <= 1/2 (levels are rounded once from the exact mean).
//   MIP blended: by design t is linear (W / 2^L - 1), not lg W - L: <= 1 against the same
//     lerp with linear t in double (its own rule), and <= 1 + 0.0861 |b - a| against filterMip.
#include "clut_filter_fx.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "colormap.h"
#include "contract.h"
#include "fixed.h"
#include "profile.h"
#include "source_dir.h"

namespace pst {
namespace {

using fx::i128;

Profile namedProfile(const std::string& name) { return loadNamedProfile(name, sourceDir()); }

// Synthetic profiles: other table sizes and the case FFrac < Log2Clut.
Profile synthetic(const std::string& name, int log2N, int cb, int fInt, int fFrac, int wf, int rf) {
    Profile p;
    p.name = name;
    p.log2Clut = log2N;
    p.colourBits = cb;
    p.f = {fInt, fFrac};
    p.widthFrac = wf;
    p.filterRecipFrac = rf;
    return p;
}

std::vector<Profile> allProfiles() {
    return {namedProfile("full"),
            namedProfile("reduced"),
            synthetic("n2", 1, 8, 6, 10, 3, 16),
            synthetic("n8", 3, 5, 4, 6, 2, 14),
            synthetic("n32_coarse_f", 5, 8, 8, 3, 4, 20),   // FFrac < Log2Clut
            synthetic("n2048", 11, 8, 4, 16, 6, 24)};
}

uint32_t ch(uint32_t rgba, int c, int cb) { return (rgba >> (c * cb)) & ((1u << cb) - 1); }

std::vector<glm::dvec4> randomColours(int n, std::mt19937_64& rng, int style) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::vector<glm::dvec4> c(n);
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < 4; ++k) {
            double v;
            switch (style % 3) {
                case 0: v = U(rng); break;                                     // noise
                case 1: v = U(rng) < 0.5 ? 0.0 : 1.0; break;                   // harsh (zebra)
                default: v = double((i * (k + 1)) % n) / double(n) + 0.01 * U(rng); break;  // ramps
            }
            c[i][k] = v;
        }
    }
    return c;
}

struct ClutSetup {
    Profile p;
    ClutTables tables;
    ClutFilterFx fx;
    ColorMap mod, clamp;
    double maxC;
    ClutSetup(const Profile& prof, const std::vector<glm::dvec4>& colours)
        : p(prof), tables(buildClutTables(prof, colours)), fx(prof), maxC(double((1u << prof.colourBits) - 1)) {
        for (const auto& w : clutRegisterWrites(p, tables)) fx.write(w.first, w.second);
        std::vector<glm::dvec4> q(p.clutSize());
        for (int e = 0; e < p.clutSize(); ++e)
            for (int c = 0; c < 4; ++c) q[e][c] = double(ch(tables.clut[e], c, p.colourBits)) / maxC;
        mod = ColorMap(q, WrapMode::Mod);
        clamp = ColorMap(q, WrapMode::Clamp);
    }
    double fd(int64_t f) const { return fx::toDouble(f, p.f.fracBits); }
    double wd(int64_t W) const { return fx::toDouble(W, p.widthFrac) / double(p.clutSize()); }  // colour-index units
};

// Random (f, W) covering every case; `cat` picks the family.
struct Vec {
    int64_t f, W;
};

Vec randomVector(const Profile& p, std::mt19937_64& rng, int cat) {
    const int N = p.clutSize(), fw = p.f.width(), ww = p.widthBits();
    const int64_t fMin = fx::minSigned(fw), fMax = fx::maxSigned(fw);
    const int64_t wMax = fx::maxUnsigned(ww);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto fromU = [&](double u) {  // u = f N in entries -> f, rounded to the format, saturated
        return fx::satSigned(i128(std::llround(std::ldexp(u / N, p.f.fracBits))), fw);
    };
    auto fromW = [&](double W) { return fx::satUnsigned(i128(std::llround(std::ldexp(W, p.widthFrac))), ww); };
    auto pick = [&](int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(rng); };

    Vec v{0, 0};
    // f families.
    switch (cat % 7) {
        case 0: v.f = pick(fMin, fMax); break;                             // anywhere, mostly far outside
        case 1: v.f = fromU(-N + 3.0 * N * U(rng)); break;                 // [-N, 2N)
        case 2: v.f = fromU(N * U(rng)); break;                            // inside
        case 3: v.f = fromU(double(pick(-3, N + 3))); break;               // on an entry boundary
        case 4: v.f = fromU((U(rng) < 0.5 ? 0.0 : double(N)) + 16.0 * (U(rng) - 0.5)); break;  // near the ends
        case 5: {
            const int64_t s[] = {fMin, fMin + 1, fMax, fMax - 1, 0, 1, -1};
            v.f = s[pick(0, 6)];
            break;
        }
        default: v.f = fromU(double(pick(-3, N + 3)) + 0.5); break;       // half-way
    }
    // W families.
    switch ((cat / 7) % 8) {
        case 0: v.W = 0; break;
        case 1: v.W = pick(0, (int64_t(1) << p.widthFrac) - 1); break;     // W < 1
        case 2: v.W = (int64_t(1) << p.widthFrac) + pick(-1, 1); break;    // W ~ 1
        case 3: v.W = fromW(std::exp2(std::log2(4.0 * N) * U(rng))); break;  // log-uniform [1, 4N)
        case 4: v.W = (int64_t(N) << p.widthFrac) + pick(-2, 2); break;    // W ~ N
        case 5: v.W = wMax - pick(0, 16); break;                           // W ~ 4N
        case 6: v.W = pick(0, 4 * N - 1) << p.widthFrac; break;            // integer W
        default: v.W = pick(0, wMax); break;
    }
    v.W = std::clamp<int64_t>(v.W, 0, wMax);
    return v;
}

// Brute-force integer sum of channel c of the extended quantized map over entries lo+1..hi.
uint64_t bruteSum(const ClutSetup& s, bool clamp, long long lo, long long hi, int c) {
    const long long N = s.p.clutSize();
    uint64_t sum = 0;
    // Long windows in clamp mode: count the entries below 0 / above N-1 without looping.
    const long long a = lo + 1, b = hi;
    if (clamp) {
        if (a < 0) sum += uint64_t(std::min(b, -1LL) - a + 1) * ch(s.tables.clut[0], c, s.p.colourBits);
        for (long long k = std::max(a, 0LL); k <= std::min(b, N - 1); ++k) sum += ch(s.tables.clut[k], c, s.p.colourBits);
        if (b >= N) sum += uint64_t(b - std::max(a, N) + 1) * ch(s.tables.clut[N - 1], c, s.p.colourBits);
    } else {
        for (long long k = a; k <= b; ++k) sum += ch(s.tables.clut[((k % N) + N) % N], c, s.p.colourBits);
    }
    return sum;
}

long long floorDivLL(long long a, long long b) {
    long long q = a / b;
    return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

struct Stats {
    std::map<std::string, long> cases;
    double maxSatErr = 0, maxSatBound = 0, maxMipErr = 0, maxBlendLinErr = 0, maxBlendLogErr = 0;
    long vectors = 0;
};

// Checks one (f, W) against the reference for both modes and all kinds.
void checkVector(const ClutSetup& s, const Vec& v, Stats& st) {
    const Profile& p = s.p;
    const int N = p.clutSize(), cb = p.colourBits, L = p.log2Clut, rf = p.filterRecipFrac;
    const double f = s.fd(v.f), w = s.wd(v.W), W = fx::toDouble(v.W, p.widthFrac);
    ++st.vectors;
    for (int mode = 0; mode < 2; ++mode) {
        const bool clamp = mode == 1;
        const ColorMap& ref = clamp ? s.clamp : s.mod;
        std::ostringstream ctx;
        ctx << p.name << (clamp ? " clamp" : " mod") << " f=" << v.f << " (" << f << ") W=" << v.W << " (" << W << ")";

        // kind 0: exact point sample.
        const uint32_t g0 = s.fx.filter(v.f, v.W, clamp, 0);
        const glm::dvec4 r0 = ref.sample(f);
        for (int c = 0; c < 4; ++c) ASSERT_EQ(double(ch(g0, c, cb)), std::round(r0[c] * s.maxC)) << ctx.str() << " point";

        // SAT.
        ClutTrace tr;
        const uint32_t g3 = s.fx.filter(v.f, v.W, clamp, 3, &tr);
        st.cases[std::string(clamp ? "clamp " : "mod ") + toString(tr.kase)]++;
        const glm::dvec4 r3 = ref.filterSat(f, w);
        const double u = f * N;
        const long long lo = (long long)std::floor(u - 0.5 * W), hi = (long long)std::floor(u + 0.5 * W);
        ASSERT_EQ(tr.lo, lo) << ctx.str();
        ASSERT_EQ(tr.hi, hi) << ctx.str();
        for (int c = 0; c < 4; ++c) {
            const double gv = ch(g3, c, cb), rv = r3[c] * s.maxC;
            double bound;
            if (tr.kase == ClutCase::SatEntry) {
                bound = 1e-6;
            } else if (tr.kase == ClutCase::SatMean) {
                bound = 0.5 + 1e-6;
            } else {
                ASSERT_EQ(tr.sum[c], bruteSum(s, clamp, lo, hi, c)) << ctx.str() << " channel " << c << " "
                                                                       << toString(tr.kase);
                const double cnt = double(tr.count);
                ASSERT_EQ(tr.count, uint32_t(hi - lo));
                bound = 0.5 + rv * std::abs(cnt * tr.recip - std::ldexp(1.0, rf)) / std::ldexp(1.0, rf) + 1e-6;
                // The result also equals the documented division of the exact sum.
                const uint64_t q = uint64_t((i128(tr.sum[c]) * tr.recip + (i128(1) << (rf - 1))) >> rf);
                ASSERT_EQ(gv, double(std::min<uint64_t>(q, (1u << cb) - 1))) << ctx.str();
            }
            st.maxSatErr = std::max(st.maxSatErr, std::abs(gv - rv));
            st.maxSatBound = std::max(st.maxSatBound, bound);
            ASSERT_LE(std::abs(gv - rv), bound) << ctx.str() << " SAT channel " << c << " " << toString(tr.kase)
                                                << " count " << tr.count << " golden " << gv << " ref " << rv;
        }

        // MIP nearest and blended.
        const uint32_t g1 = s.fx.filter(v.f, v.W, clamp, 1);
        const uint32_t g2 = s.fx.filter(v.f, v.W, clamp, 2, &tr);
        const glm::dvec4 r1 = ref.filterMip(f, w, false), r2 = ref.filterMip(f, w, true);
        if (W < 1.0) {
            for (int c = 0; c < 4; ++c) {
                ASSERT_EQ(ch(g1, c, cb), ch(g0, c, cb)) << ctx.str();
                ASSERT_EQ(ch(g2, c, cb), ch(g0, c, cb)) << ctx.str();
            }
            continue;
        }
        // Own rule for the blend: the reference's levels, linear t.
        const long long i = (long long)std::floor(u);
        const int Lw = int(std::floor(std::log2(W))), Lc = std::min(Lw, L), Lb = std::min(Lc + 1, L);
        auto level = [&](int k) {
            const auto& tab = ref.mipLevel(k);
            const long long n = (long long)tab.size();
            long long j = floorDivLL(i, 1LL << k);
            j = clamp ? std::clamp(j, 0LL, n - 1) : ((j % n) + n) % n;
            return tab[j];
        };
        const double t = Lw < L ? W / std::ldexp(1.0, Lw) - 1.0 : 0.0;
        const glm::dvec4 a = level(Lc), b = level(Lb);
        for (int c = 0; c < 4; ++c) {
            const double e1 = std::abs(ch(g1, c, cb) - r1[c] * s.maxC);
            st.maxMipErr = std::max(st.maxMipErr, e1);
            ASSERT_LE(e1, 0.5 + 1e-6) << ctx.str() << " MIP nearest channel " << c;
            const double lin = (a[c] + (b[c] - a[c]) * t) * s.maxC;
            const double e2 = std::abs(ch(g2, c, cb) - lin);
            st.maxBlendLinErr = std::max(st.maxBlendLinErr, e2);
            ASSERT_LE(e2, 1.0 + 1e-6) << ctx.str() << " MIP blended (linear t) channel " << c;
            const double e3 = std::abs(ch(g2, c, cb) - r2[c] * s.maxC);
            st.maxBlendLogErr = std::max(st.maxBlendLogErr, e3);
            ASSERT_LE(e3, 1.0 + 0.0861 * std::abs(b[c] - a[c]) * s.maxC + 1e-6)
                << ctx.str() << " MIP blended vs filterMip channel " << c;
        }
    }
}

TEST(ClutFilterFx, TablesAreQuantizedSummedAndMipMapped) {
    std::mt19937_64 rng(12345);
    for (const Profile& p : allProfiles()) {
        SCOPED_TRACE(p.name);
        const int N = p.clutSize(), cb = p.colourBits;
        const auto colours = randomColours(N, rng, 0);
        const ClutTables t = buildClutTables(p, colours);
        ASSERT_EQ(int(t.clut.size()), N);
        ASSERT_EQ(int(t.sat.size()), N);
        ASSERT_EQ(int(t.mip.size()), N - 1);
        const double maxC = double((1u << cb) - 1);
        uint64_t acc[4] = {0, 0, 0, 0};
        for (int e = 0; e < N; ++e)
            for (int c = 0; c < 4; ++c) {
                EXPECT_EQ(ch(t.clut[e], c, cb), uint32_t(std::llround(colours[e][c] * maxC)));
                acc[c] += ch(t.clut[e], c, cb);
                EXPECT_EQ(t.sat[e][c], acc[c]);
            }
        // MIP levels within 1/2 LSB of the exact means of the quantized entries.
        std::vector<glm::dvec4> q(N);
        for (int e = 0; e < N; ++e)
            for (int c = 0; c < 4; ++c) q[e][c] = ch(t.clut[e], c, cb);
        const ColorMap cm(q, WrapMode::Mod);
        for (int k = 1; k <= p.log2Clut; ++k)
            for (int j = 0; j < (N >> k); ++j)
                for (int c = 0; c < 4; ++c) {
                    const double exact = cm.mipLevel(k)[j][c];
                    const uint32_t m = ch(t.mip[N - (N >> (k - 1)) + j], c, cb);
                    EXPECT_EQ(m, uint32_t(std::floor(exact + 0.5))) << "level " << k << " entry " << j;
                }
        // Register writes: addresses and count.
        const auto w = clutRegisterWrites(p, t);
        ASSERT_EQ(int(w.size()), N + 4 * N + N - 1);
        EXPECT_EQ(w.front().first, contract::kRegClut);
        EXPECT_EQ(w[N].first, contract::kRegSat);
        EXPECT_EQ(w[5 * N].first, contract::kRegMip);
        EXPECT_EQ(w.back().first, contract::kRegMip + N - 2);
        ClutFilterFx fx(p);
        for (const auto& x : w) fx.write(x.first, x.second);
        EXPECT_EQ(fx.tables().clut, t.clut);
        EXPECT_EQ(fx.tables().sat, t.sat);
        for (int e = 0; e < N - 1; ++e) EXPECT_EQ(fx.tables().mip[e], t.mip[e]);
    }
}

TEST(ClutFilterFx, QuantizeRoundsAndClamps) {
    const Profile p = namedProfile("full");
    EXPECT_EQ(quantizeColour(p, glm::dvec4(0.0, 1.0, -0.5, 2.0)), 0xFF00FF00u);
    EXPECT_EQ(quantizeColour(p, glm::dvec4(0.25, 0.75, std::nan(""), 0.5)), 0x8000BF40u);  // 63.75, 191.25, NaN, 127.5
    EXPECT_THROW(buildClutTables(p, std::vector<glm::dvec4>(3)), std::invalid_argument);
}

TEST(ClutFilterFx, OtherAddressesAreIgnored) {
    for (const Profile& p : allProfiles()) {
        SCOPED_TRACE(p.name);
        const int N = p.clutSize();
        ClutFilterFx fx(p);
        using namespace contract;
        const uint16_t outside[] = {0x0000,
                                    uint16_t(kRegClut - 1),
                                    uint16_t(kRegClut + N),
                                    uint16_t(kRegSat - 1),
                                    uint16_t(kRegSat + kRegSatStride * N),
                                    uint16_t(kRegMip - 1),
                                    uint16_t(kRegMip + N),
                                    0x8000,
                                    0xFFFF};
        for (uint16_t a : outside) {
            // Skip what is a table address for this N (the SAT's end is the MIP range at N = 2048).
            if (!isClutTableAddress(p, a)) fx.write(a, 0xFFFFFFFFu);
        }
        for (int e = 0; e < N; ++e) {
            ASSERT_EQ(fx.tables().clut[e], 0u);
            ASSERT_EQ(fx.tables().mip[e], 0u);
            for (int c = 0; c < 4; ++c) ASSERT_EQ(fx.tables().sat[e][c], 0u);
        }
        // Data is truncated to the RAM widths.
        fx.write(contract::kRegSat, 0xFFFFFFFFu);
        EXPECT_EQ(fx.tables().sat[0][0], (1u << (p.colourBits + p.log2Clut)) - 1);
    }
}

// Hand-worked examples on N = 8 (profile n8: CB 5, f Q4.6, WidthFrac 2, RF 14).
TEST(ClutFilterFx, HandWorkedCases) {
    const Profile p = synthetic("n8", 3, 5, 4, 6, 2, 14);
    std::vector<glm::dvec4> c(8);
    for (int i = 0; i < 8; ++i) c[i] = glm::dvec4(double(i) / 31.0, double(31 - i) / 31.0, i == 0 ? 1.0 : 0.0, i == 7 ? 1.0 : 0.0);
    ClutFilterFx fx(p);
    fx.load(buildClutTables(p, c));
    auto R = [&](uint32_t rgba) { return int(ch(rgba, 0, 5)); };
    auto fOf = [&](double u) { return int64_t(std::llround(u / 8.0 * 64.0)); };  // f = u / N at 6 bits
    auto wOf = [&](double W) { return int64_t(std::llround(W * 4.0)); };
    ClutTrace tr;
    // Point: u = 3.5 -> entry 3; clamp far below -> 0, far above -> 7; mod wraps.
    EXPECT_EQ(R(fx.filter(fOf(3.5), 0, false, 0)), 3);
    EXPECT_EQ(R(fx.filter(fOf(-1.0), 0, false, 0)), 7);
    EXPECT_EQ(R(fx.filter(fOf(-1.0), 0, true, 0)), 0);
    EXPECT_EQ(R(fx.filter(fx::minSigned(10), 0, true, 0)), 0);
    EXPECT_EQ(R(fx.filter(fx::maxSigned(10), 0, true, 0)), 7);
    EXPECT_EQ(R(fx.filter(fx::maxSigned(10), 0, false, 0)), 7);  // u = 63.875: entry 63 mod 8
    // SAT inside: u = 4, W = 2: lo = 3, hi = 5: entries 4, 5 -> 4.5 -> 5 (round half up).
    EXPECT_EQ(R(fx.filter(fOf(4.0), wOf(2.0), false, 3, &tr)), 5);
    EXPECT_EQ(tr.kase, ClutCase::SatInside);
    EXPECT_EQ(tr.count, 2u);
    // SAT mod wrap: u = 0.25, W = 3: lo = -2, hi = 1: entries -1 (=7), 0, 1 -> 8/3 -> 3.
    EXPECT_EQ(R(fx.filter(fOf(0.25), wOf(3.0), false, 3, &tr)), 3);
    EXPECT_EQ(tr.kase, ClutCase::SatWrap);
    // SAT clamp below: same window: entries 0 (for -1), 0, 1 -> 1/3 -> 0.
    EXPECT_EQ(R(fx.filter(fOf(0.25), wOf(3.0), true, 3, &tr)), 0);
    EXPECT_EQ(tr.kase, ClutCase::SatBelow);
    // u = 0.5, W = 3: lo = -1 exactly (csat[-1] = 0, no extension): entries 0, 1, 2 -> 1.
    EXPECT_EQ(R(fx.filter(fOf(0.5), wOf(3.0), true, 3, &tr)), 1);
    EXPECT_EQ(tr.kase, ClutCase::SatInside);
    EXPECT_EQ(R(fx.filter(fOf(0.5), wOf(3.0), false, 3, &tr)), 1);
    EXPECT_EQ(tr.kase, ClutCase::SatWrap);  // lo mod N = 7 stands for csat[-1]
    // SAT clamp above: u = 7, W = 4: lo = 5, hi = 9: entries 6, 7, 7, 7 -> 27/4 = 6.75 -> 7.
    EXPECT_EQ(R(fx.filter(fOf(7.0), wOf(4.0), true, 3, &tr)), 7);
    EXPECT_EQ(tr.kase, ClutCase::SatAbove);
    EXPECT_EQ(tr.count, 4u);
    // Mod: entries 6, 7, 0, 1 -> 14/4 = 3.5 -> 4.
    EXPECT_EQ(R(fx.filter(fOf(7.0), wOf(4.0), false, 3, &tr)), 4);
    EXPECT_EQ(tr.kase, ClutCase::SatWrap);
    // SAT clamp both: u = 4, W = 16: lo = -4, hi = 12: 3 x 0 + 28 + 5 x 7 = 63 / 16 -> 3.94 -> 4.
    EXPECT_EQ(R(fx.filter(fOf(4.0), wOf(16.0), true, 3, &tr)), 4);
    EXPECT_EQ(tr.kase, ClutCase::SatBoth);
    // SAT mod W >= N: mean 28 / 8 = 3.5 -> 4.
    EXPECT_EQ(R(fx.filter(fOf(4.0), wOf(8.0), false, 3, &tr)), 4);
    EXPECT_EQ(tr.kase, ClutCase::SatMean);
    // SAT clamp window entirely past the top / bottom: the end entry.
    EXPECT_EQ(R(fx.filter(fOf(20.0), wOf(4.0), true, 3, &tr)), 7);
    EXPECT_EQ(tr.kase, ClutCase::SatEntry);
    EXPECT_EQ(R(fx.filter(fOf(-20.0), wOf(4.0), true, 3, &tr)), 0);
    // MIP: W = 2 -> level 1, entry 4 >> 1 = 2 = mean(4, 5) = 4.5 -> 5. W = 3 blended: t = 0.5
    // between level 1 (5) and level 2 entry 1 = mean(4..7) = 5.5 -> 6: 5.5 -> 6.
    EXPECT_EQ(R(fx.filter(fOf(4.0), wOf(2.0), false, 1, &tr)), 5);
    EXPECT_EQ(tr.level, 1);
    EXPECT_EQ(R(fx.filter(fOf(4.0), wOf(3.0), false, 2, &tr)), 6);
    EXPECT_EQ(tr.t, uint64_t(1) << (fx.tFrac() - 1));
    // MIP level 3 (one entry, mean 3.5 -> 4) for W >= 8, any u, either mode.
    EXPECT_EQ(R(fx.filter(fOf(-50.0), wOf(31.75), true, 2, &tr)), 4);
    EXPECT_EQ(tr.level, 3);
}

TEST(ClutFilterFx, MatchesReferenceOnRandomTablesAndVectors) {
    const uint64_t seed = 20240611;
    std::printf("seed %llu\n", (unsigned long long)seed);
    std::mt19937_64 rng(seed);
    for (const Profile& p : allProfiles()) {
        Stats st;
        const int tables = p.log2Clut >= 11 ? 2 : 6;
        const int perTable = p.log2Clut >= 11 ? 20000 : 40000;
        for (int k = 0; k < tables; ++k) {
            ClutSetup s(p, randomColours(p.clutSize(), rng, k));
            for (int n = 0; n < perTable; ++n) {
                const Vec v = randomVector(p, rng, int(rng() % 56));
                checkVector(s, v, st);
                if (::testing::Test::HasFatalFailure()) return;
            }
        }
        std::printf("%-13s %ld vectors x 2 modes: max |golden - ref| SAT %.3f (bound %.3f), MIP %.3f, "
                    "blended vs linear-t %.3f, vs lg %.3f\n",
                    p.name.c_str(), st.vectors, st.maxSatErr, st.maxSatBound, st.maxMipErr, st.maxBlendLinErr,
                    st.maxBlendLogErr);
        for (const auto& kv : st.cases) std::printf("    %-34s %ld\n", kv.first.c_str(), kv.second);
        // Every SAT branch is exercised in both modes.
        for (const char* name : {"mod sat mean (mod, W >= N)", "mod sat single entry", "mod sat inside",
                                 "mod sat wrap (mod)", "clamp sat single entry", "clamp sat inside",
                                 "clamp sat past bottom (clamp)", "clamp sat past top (clamp)",
                                 "clamp sat past both ends (clamp)"})
            EXPECT_GE(st.cases[name], 100) << p.name << ": " << name;
        if (p.name == "full") {
            EXPECT_LT(st.maxSatErr, 1.0);  // the full profile is within 1 LSB
        }
    }
}

}  // namespace
}  // namespace pst

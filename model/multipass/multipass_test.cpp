// Tests of the multipass noise's program and CPU model (Hart 2001, sections 3, 4, 7) against
// values derived here independently: integer shifts, the paper's Figure 3 formula evaluated in
// double precision with a derived error bound, exact lattice values, pass counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "cpu_model.h"
#include "noise.h"
#include "program.h"
#include "tables.h"

namespace pst::multipass {
namespace {

struct Input {
    Image8 s, t, r;
};

Input randomInput(int w, int h, uint32_t seed) {
    std::mt19937 gen(seed);
    Input in;
    for (Image8* im : {&in.s, &in.t, &in.r}) {
        im->width = w;
        im->height = h;
        im->px.resize(size_t(w) * h);
        for (uint32_t& v : im->px) v = gen() & 255;
    }
    return in;
}

// Figure 3 with section 4.3's randomization, in double precision: the weighted sum over the
// eight corners of nran[sran[i] + tran[j] + rran[k]] / 255, weights u or 1 - u with
// u = frac(S / 2^b_f) 2^b_f / (2^b_f - 1) (section 4.2's fracshift), or SCURVE(u) (section 7).
double figure3(const Tables& T, const Format& f, Interp interp, int S, int Tc, int R) {
    const int c[3] = {S, Tc, R};
    int K[3];
    double u[3];
    for (int a = 0; a < 3; ++a) {
        K[a] = c[a] / (1 << f.bf);
        u[a] = double(c[a] - K[a] * (1 << f.bf)) / ((1 << f.bf) - 1);
        if (interp == Interp::Scurve) u[a] = u[a] * u[a] * (3.0 - 2.0 * u[a]);
    }
    double n = 0.0;
    for (int k = 0; k < 8; ++k) {
        const int sum = T[Sran][K[0] + (k & 1)] + T[Tran][K[1] + (k >> 1 & 1)] +
                        T[Rran][K[2] + (k >> 2 & 1)];
        double w = 1.0;
        for (int a = 0; a < 3; ++a) w *= (k >> a & 1) ? u[a] : 1.0 - u[a];
        n += T[Nran][sum] / 255.0 * w;
    }
    return n;
}

TEST(Multipass, PassCountsAreThePapers) {
    // 4 passes per coordinate (shift right, shift left, subtract, fracshift), 11 per corner
    // (3 lookups, 3 draws of the sum, nran, 3 weights, the add into the noise); SCURVE 4 more
    // per weight image (section 7).
    Params p;
    EXPECT_EQ(sgiProgram(p).draws(), 3 * 4 + 8 * 11);
    p.interp = Interp::Scurve;
    EXPECT_EQ(sgiProgram(p).draws(), 3 * 8 + 8 * 11);
    p.format.bf = 0;
    EXPECT_THROW(sgiProgram(p), std::invalid_argument);
}

TEST(Multipass, TablesInRangeAndPeriodic) {
    for (int bf : {1, 4, 7}) {
        Params p;
        p.format.bf = bf;
        const Tables T = makeTables(p);
        const int cells = 1 << p.format.bi();
        for (int tb : {Sran, Tran, Rran}) {
            EXPECT_LE(*std::max_element(T[tb].begin(), T[tb].end()), 85);  // [0, 1/3]
            for (int i = cells; i < 256; ++i) EXPECT_EQ(T[tb][i], T[tb][i % cells]);
        }
        // nran spans [0, 1]: with 256 draws, both quarters at the ends are hit
        EXPECT_LT(*std::min_element(T[Nran].begin(), T[Nran].end()), 64);
        EXPECT_GT(*std::max_element(T[Nran].begin(), T[Nran].end()), 191);
    }
    Params a, b;
    b.seed = 2;
    EXPECT_NE(makeTables(a).t, makeTables(b).t);
}

// Section 4.2 exactly: si = S >> b_f and the weight round((S mod 2^b_f) 255 / (2^b_f - 1)),
// for every byte and every b_f, with every stored value far from a rounding tie.
TEST(Multipass, DecompositionIsExactForEveryByte) {
    Image8 all{256, 1, {}};
    for (int v = 0; v < 256; ++v) all.px.push_back(uint8_t(v));
    for (int bf = 1; bf <= 8; ++bf) {
        Params p;
        p.format.bf = bf;
        State st;
        Stats stats;
        runCpu(sgiProgram(p), makeTables(p), all, all, all, &stats, &st);
        const int m = (1 << bf) - 1;
        for (int v = 0; v < 256; ++v) {
            ASSERT_EQ(st.img[TexSI].px[v], v >> bf) << "b_f " << bf << " S " << v;
            const int F = v & m;
            ASSERT_EQ(st.img[TexTF].px[v], (2 * F * 255 + m) / (2 * m)) << "b_f " << bf << " S " << v;
        }
        EXPECT_GE(stats.minTieMargin, 1.0 / 512) << "b_f " << bf;
    }
}

// At a lattice point (every fraction 0) the weights are exactly 0 and 1 - 0 = 1, so the noise
// is exactly the corner's random value; at the largest fraction (weight 255/255) the far corner's.
TEST(Multipass, LatticePointsAreTheTableValues) {
    for (Interp interp : {Interp::Linear, Interp::Scurve}) {
        Params p;
        p.interp = interp;
        const Tables T = makeTables(p);
        const int m = (1 << p.format.bf) - 1;
        Image8 s{64, 1, {}}, t{64, 1, {}}, r{64, 1, {}};
        std::mt19937 gen(7);
        std::vector<int> far;
        for (int i = 0; i < 64; ++i) {
            const int f = (i & 1) ? m : 0;
            far.push_back(f != 0);
            s.px.push_back(uint8_t((gen() & 15) << p.format.bf | f));
            t.px.push_back(uint8_t((gen() & 15) << p.format.bf | f));
            r.px.push_back(uint8_t((gen() & 15) << p.format.bf | f));
        }
        const Image8 n = runCpu(sgiProgram(p), T, s, t, r);
        for (int i = 0; i < 64; ++i) {
            const int d = far[i];
            const int sum = T[Sran][(s.px[i] >> 4) + d] + T[Tran][(t.px[i] >> 4) + d] +
                            T[Rran][(r.px[i] >> 4) + d];
            EXPECT_EQ(n.px[i], T[Nran][sum]) << "pixel " << i;
        }
    }
}

// The model against Figure 3 in double precision. Bound, in LSB (1/255): each corner is
// v Wq + three roundings of at most 1/2 scaled by weights <= 1 (1.5 per corner, 12 for eight);
// the quantized weights Wq differ from the exact ones by e per axis, and their pairs (u, 1 - u)
// sum to 1 exactly, so sum_c |prod Wq - prod W| <= 2 sum_axes |e|: linear |e| <= 1/2 -> 3;
// SCURVE |e| <= 5.75 (3/4 - u/2 rounded (1/4), two products rounded (1/2 each) at 1/4 scale,
// times 4 -> 5, plus u's own 1/2 LSB times max SCURVE' = 3/2) -> 34.5.
TEST(Multipass, CpuModelWithinBoundOfFigure3) {
    const uint32_t seed = 20011;
    std::printf("seed %u\n", seed);
    const Input in = randomInput(128, 128, seed);
    for (Interp interp : {Interp::Linear, Interp::Scurve}) {
        for (int bf = 1; bf <= 7; ++bf) {
            Params p;
            p.format.bf = bf;
            p.interp = interp;
            const Tables T = makeTables(p);
            const Image8 n = runCpu(sgiProgram(p), T, in.s, in.t, in.r);
            double maxErr = 0.0, sq = 0.0;
            for (size_t i = 0; i < n.px.size(); ++i) {
                const double e = std::fabs(n.px[i] / 255.0 -
                                           figure3(T, p.format, interp, in.s.px[i], in.t.px[i], in.r.px[i]));
                maxErr = std::max(maxErr, e);
                sq += e * e;
            }
            const double bound = (interp == Interp::Linear ? 15.0 : 12.0 + 34.5) / 255.0;
            std::printf("%s b_f %d: max %.2f LSB, rms %.2f LSB\n", interp == Interp::Linear ? "linear" : "scurve",
                        bf, maxErr * 255, std::sqrt(sq / n.px.size()) * 255);
            EXPECT_LE(maxErr, bound) << "b_f " << bf;
        }
    }
}

TEST(Multipass, ToFixedWraps) {
    Format f;
    EXPECT_EQ(toFixed(0.0, f), 0);
    EXPECT_EQ(toFixed(15.9375, f), 255);
    EXPECT_EQ(toFixed(16.0, f), 0);
    EXPECT_EQ(toFixed(-0.0625, f), 255);
    EXPECT_EQ(toFixed(1.03, f), 16);
}

// ---- Section 5: the register-combiner variant ----

TEST(MultipassRc, PassCounts) {
    // Per axis b_i shifts (the weight) + 1 (the +1 corner); per corner 3 b_i randoms +
    // 3 (b_i - 1) shifts, 8 randoms + 7 shifts, 3 weights, 1 add.
    for (int bf = 1; bf <= 7; ++bf) {
        Params p;
        p.variant = Variant::Rc;
        p.format.bf = bf;
        const int bi = 8 - bf;
        EXPECT_EQ(rcProgram(p).draws(), 3 * (bi + 1) + 8 * (3 * bi + 3 * (bi - 1) + 15 + 4)) << "b_f " << bf;
    }
    Params p;
    p.variant = Variant::Rc;
    EXPECT_EQ(rcProgram(p).draws(), 335);  // b_f = 4; the paper's is 375 (docs/MULTIPASS.md)
    p.format.bf = 8;
    EXPECT_THROW(rcProgram(p), std::invalid_argument);
    p.format.bf = 4;
    p.interp = Interp::Scurve;
    EXPECT_THROW(rcProgram(p), std::invalid_argument);
}

// 5.2's routine is the logical shift left the paper names it: (2c) mod 256, every byte.
TEST(MultipassRc, ShiftLeftIsLogical) {
    for (int c = 0; c < 256; ++c) ASSERT_EQ(rc::shiftLeft(c), (2 * c) & 255) << c;
}

// The +1 corner: its top b_i bits are K + 1 mod 2^b_i for every byte and b_f.
TEST(MultipassRc, IncWrapTopBits) {
    for (int bf = 1; bf <= 7; ++bf)
        for (int c = 0; c < 256; ++c) {
            const int bi = 8 - bf, k1 = 256 - (1 << bf) - 32;
            ASSERT_EQ(rc::incWrap(c, 1 << bf, k1) >> bf, ((c >> bf) + 1) & ((1 << bi) - 1)) << bf << " " << c;
        }
}

// The register-combiner noise written directly (not as passes): the lattice value of
// (i, j, k) is two bit-serial randomizations (5.3) -- twelve (3 b_i) blends by the bits of
// i, j, k (high bit first, s t r interleaved), then eight by the bits of the result -- each
// blend acc = round(a c / 255) + round((255 - a) acc / 255), c = ranone or ranzero; the
// noise is the sum over the corners of the lattice value times the weights F << b_i or
// 255 - that, each multiply rounded to the nearest byte, as Figure 3.
struct RcReference {
    RcConstants c;
    int bf, bi;
    explicit RcReference(const Params& p) : c(rcConstants(p)), bf(p.format.bf), bi(p.format.bi()) {}
    static int lerp(int col, int acc) {
        const int a = RcConstants::alpha;
        return int(std::lround(a * col / 255.0)) + int(std::lround((255 - a) * acc / 255.0));
    }
    int lattice(int i, int j, int k) const {
        const int K[3] = {i, j, k};
        int acc = RcConstants::start;
        for (int kk = 0; kk < bi; ++kk)
            for (int a = 0; a < 3; ++a)
                acc = lerp((K[a] >> (bi - 1 - kk) & 1) ? c.ranone[a][kk] : c.ranzero[a][kk], acc);
        int acc2 = RcConstants::start;
        for (int b = 0; b < 8; ++b) acc2 = lerp((acc >> (7 - b) & 1) ? c.ranone2[b] : c.ranzero2[b], acc2);
        return acc2;
    }
    int noise(int S, int T, int R) const {
        const int v[3] = {S, T, R}, cells = 1 << bi;
        int sum = 0;
        for (int corner = 0; corner < 8; ++corner) {
            int K[3];
            for (int a = 0; a < 3; ++a) K[a] = ((v[a] >> bf) + (corner >> a & 1)) % cells;
            int x = lattice(K[0], K[1], K[2]);
            for (int a = 0; a < 3; ++a) {
                const int w = (v[a] << bi) & 255;  // F 2^b_i
                x = int(std::lround(x * double((corner >> a & 1) ? w : 255 - w) / 255.0));
            }
            sum = std::min(255, sum + x);
        }
        return sum;
    }
};

TEST(MultipassRc, CpuModelEqualsTheDirectFormula) {
    const Input in = randomInput(64, 64, 4242);
    for (int bf = 1; bf <= 7; ++bf) {
        Params p;
        p.variant = Variant::Rc;
        p.format.bf = bf;
        const RcReference ref(p);
        const Image8 n = runCpu(rcProgram(p), makeTables(p), in.s, in.t, in.r);
        int bad = 0;
        for (size_t i = 0; i < n.px.size(); ++i)
            bad += n.px[i] != ref.noise(in.s.px[i], in.t.px[i], in.r.px[i]);
        EXPECT_EQ(bad, 0) << "b_f " << bf;
    }
}

// At a lattice point (fraction 0) the noise is the lattice value; the lattice wraps.
TEST(MultipassRc, LatticePointsAndWrap) {
    Params p;
    p.variant = Variant::Rc;
    const RcReference ref(p);
    Image8 s{16, 1, {}}, t = s, r = s;
    for (int i = 0; i < 16; ++i) s.px.push_back(uint8_t(i << 4)), t.px.push_back(uint8_t((15 - i) << 4)), r.px.push_back(uint8_t((i * 7 & 15) << 4));
    const Image8 n = runCpu(rcProgram(p), makeTables(p), s, t, r);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(n.px[i], ref.lattice(i, 15 - i, i * 7 & 15)) << i;
}

// ---- Section 6.3's proposal: exclusive-or randomization (Variant::Xor) ----

TEST(MultipassXor, PassCounts) {
    Params p;
    p.variant = Variant::Xor;
    EXPECT_EQ(xorProgram(p).draws(), 3 * 4 + 4 + 8 * 9);
    p.interp = Interp::Scurve;
    EXPECT_EQ(xorProgram(p).draws(), 3 * 8 + 4 + 8 * 9);
}

// Rayshade's value noise with the 8-bit hash (model/noise.h: NoiseHash::Perm256, corners
// Value) is the reference, pointwise: n + 1/2 against the byte / 255. At lattice points the
// weights are exactly 0 and 1 and the only error is the value table's byte (<= 1/2 LSB);
// elsewhere, as CpuModelWithinBoundOfFigure3: 12 LSB of product roundings, 3 of weights.
TEST(MultipassXor, EqualsRayshadePerm256ValueNoise) {
    NoiseOptions ro;
    ro.interp = NoiseInterp::Linear;
    ro.corner = NoiseCorner::Value;
    ro.hash = NoiseHash::Perm256;
    for (int bf = 1; bf <= 7; ++bf) {
        Params p;
        p.variant = Variant::Xor;
        p.format.bf = bf;
        const Input in = randomInput(64, 64, 77 + bf);
        Image8 s = in.s, t = in.t, r = in.r;
        for (int i = 0; i < 64; ++i)  // the first row: lattice points
            s.px[i] &= uint8_t(~0u << bf), t.px[i] &= uint8_t(~0u << bf), r.px[i] &= uint8_t(~0u << bf);
        Stats stats;
        const Image8 n = runCpu(xorProgram(p), makeTables(p), s, t, r, &stats);
        EXPECT_GE(stats.minTieMargin, 1.0 / 512) << "b_f " << bf;
        double sq = 0, mx = 0;
        for (size_t i = 0; i < n.px.size(); ++i) {
            const glm::dvec3 q = glm::dvec3(s.px[i], t.px[i], r.px[i]) / double(1 << bf);
            const double e = std::fabs(n.px[i] / 255.0 - (noise(q, ro) + 0.5)) * 255;
            if (i < 64) ASSERT_LE(e, 0.5 + 1e-9) << "lattice point " << i << " b_f " << bf;
            sq += e * e, mx = std::max(mx, e);
        }
        std::printf("xor b_f %d: vs Rayshade (Perm256, value, linear) rms %.2f LSB, max %.2f LSB\n", bf,
                    std::sqrt(sq / n.px.size()), mx);
        EXPECT_LE(mx, 15.0) << "b_f " << bf;
    }
}

// Section 6.1's precision: the exclusive-or variant at b = 10, 16 and 24 (the packed 24-bit
// luminance) against Rayshade, the error bound of the test above in units of 1/(2^b - 1).
TEST(MultipassXor, WiderFormatsApproachRayshade) {
    NoiseOptions ro;
    ro.interp = NoiseInterp::Linear;
    ro.corner = NoiseCorner::Value;
    ro.hash = NoiseHash::Perm256;
    std::mt19937 gen(99);
    for (int b : {10, 16, 24})
        for (int bi : {4, 7}) {
            Params p;
            p.variant = Variant::Xor;
            p.format.b = b;
            p.format.bf = b - bi;
            const double M = p.format.max();
            Image8 s{32, 32, {}}, t = s, r = s;
            for (Image8* im : {&s, &t, &r})
                for (int i = 0; i < 32 * 32; ++i) im->px.push_back(gen() & uint32_t(M));
            Stats stats;
            const Image8 n = runCpu(xorProgram(p), makeTables(p), s, t, r, &stats);
            EXPECT_GT(stats.minTieMargin, 0.0) << "b " << b;
            double mx = 0, sq = 0;
            for (size_t i = 0; i < n.px.size(); ++i) {
                const glm::dvec3 q = glm::dvec3(s.px[i], t.px[i], r.px[i]) / double(1 << p.format.bf);
                const double e = std::fabs(n.px[i] / M - (noise(q, ro) + 0.5)) * M;
                mx = std::max(mx, e), sq += e * e;
            }
            std::printf("xor b %d b_i %d: vs Rayshade rms %.2f, max %.2f (1/(2^b - 1) units)\n", b, bi,
                        std::sqrt(sq / n.px.size()), mx);
            EXPECT_LE(mx, 15.0) << "b " << b << " b_i " << bi;
        }
}

}  // namespace
}  // namespace pst::multipass

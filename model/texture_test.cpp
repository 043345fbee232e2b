// Tests of the texture function, its gradient (eq. 10-12) and the filter width.
#include "texture.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "worley.h"

namespace pst {
namespace {

Quadric fullQuadric() {
    Quadric q;
    q.A = 1.5; q.B = -0.7; q.C = 0.3; q.D = 2.1; q.E = -0.9;
    q.F = 0.45; q.G = -1.3; q.H = 0.8; q.I = 0.6; q.J = -0.25;
    return q;
}

Texture testTexture(const NoiseOptions& opt) {
    Texture tex;
    tex.quadric = fullQuadric();
    tex.noise = opt;
    double amp = 0.8, freq = 1.7;
    for (int i = 0; i < 4; ++i) {
        Octave o;
        o.amplitude = amp;
        // A rotation-ish, non-symmetric matrix scaled by the octave frequency.
        o.M = freq * glm::dmat3(glm::dvec3(0.9, 0.3, -0.2 + 0.1 * i),   // column 0
                                glm::dvec3(-0.25, 1.1, 0.4),           // column 1
                                glm::dvec3(0.15 * i, -0.35, 0.95));    // column 2
        o.offset = glm::dvec3(3.1 * i - 2.0, -1.7 * i, 0.37 + i);
        tex.octaves.push_back(o);
        amp *= 0.5;
        freq *= 2.03;
    }
    return tex;
}

TEST(Texture, QuadricMatchesMatrixForm) {
    const Quadric q = fullQuadric();
    const glm::dmat4 Q = q.matrix();
    // Eq. 4 layout (symmetric, GLM column-major m[col][row]).
    EXPECT_EQ(Q[0][0], q.A); EXPECT_EQ(Q[1][0], q.B); EXPECT_EQ(Q[2][0], q.C);
    EXPECT_EQ(Q[3][0], q.D); EXPECT_EQ(Q[1][1], q.E); EXPECT_EQ(Q[2][1], q.F);
    EXPECT_EQ(Q[3][1], q.G); EXPECT_EQ(Q[2][2], q.H); EXPECT_EQ(Q[3][2], q.I);
    EXPECT_EQ(Q[3][3], q.J);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_EQ(Q[c][r], Q[r][c]);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> d(-3.0, 3.0);
    for (int k = 0; k < 200; ++k) {
        const glm::dvec3 s(d(rng), d(rng), d(rng));
        const glm::dvec4 h(s, 1.0);
        EXPECT_NEAR(q.value(s), glm::dot(h, Q * h), 1e-12);  // eq. 3 == eq. 4
        // Gradient against central differences (q is quadratic: FD is exact up to rounding).
        const glm::dvec3 g = q.gradient(s);
        for (int a = 0; a < 3; ++a) {
            glm::dvec3 sp = s, sm = s;
            sp[a] += 1e-4;
            sm[a] -= 1e-4;
            EXPECT_NEAR(g[a], (q.value(sp) - q.value(sm)) / 2e-4, 1e-8);
        }
    }
    // Linear terms are kept (eq. 11 as printed would drop them): grad at 0 is 2 (D, G, I).
    EXPECT_EQ(q.gradient(glm::dvec3(0.0)), 2.0 * glm::dvec3(q.D, q.G, q.I));
}

// True if any octave's lattice coordinate is within `margin` of a lattice plane.
bool nearLatticePlane(const Texture& tex, const glm::dvec3& s, double margin) {
    for (const Octave& o : tex.octaves) {
        const glm::dvec3 p = o.M * s + o.offset;
        for (int a = 0; a < 3; ++a)
            if (std::abs(p[a] - std::round(p[a])) < margin) return true;
    }
    return false;
}

TEST(Texture, GradientMatchesFiniteDifferences) {
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> d(-4.0, 4.0);
    // h = 1e-5: the noise input is rounded to the 2^-33 grid of x = p + 1e6, so a smaller
    // step loses digits; the truncation error h^2 f'''/6 is still ~1e-8.
    const double h = 1e-5;
    for (NoiseInterp in : {NoiseInterp::Scurve, NoiseInterp::Linear})
        for (NoiseCorner co : {NoiseCorner::ValueGradient, NoiseCorner::Value})
            for (NoiseHash ha : {NoiseHash::Rayshade, NoiseHash::Perm256}) {
                const Texture tex = testTexture({in, co, ha});
                int tested = 0;
                for (int k = 0; k < 2000; ++k) {
                    const glm::dvec3 s(d(rng), d(rng), d(rng));
                    // Keep the stencil inside one cell of every octave (Linear is only C0).
                    if (nearLatticePlane(tex, s, 100 * h)) continue;
                    ++tested;
                    glm::dvec3 g;
                    const double f = evalF(tex, s, &g);
                    // f itself is eq. 1 written out.
                    double expect = tex.quadric.value(s);
                    for (const Octave& o : tex.octaves)
                        expect += o.amplitude * noise(o.M * s + o.offset, tex.noise);
                    ASSERT_NEAR(f, expect, 1e-12);
                    EXPECT_EQ(evalF(tex, s), f);
                    for (int a = 0; a < 3; ++a) {
                        glm::dvec3 sp = s, sm = s;
                        sp[a] += h;
                        sm[a] -= h;
                        const double fd = (evalF(tex, sp) - evalF(tex, sm)) / (2 * h);
                        ASSERT_NEAR(g[a], fd, 1e-5 * std::max(1.0, std::abs(fd)))
                            << toString(in) << " " << toString(co) << " " << toString(ha)
                            << " s = " << s.x << " " << s.y << " " << s.z << " axis " << a;
                    }
                }
                EXPECT_GT(tested, 1000);
            }
}

// grad_s f of eq. 10-12 with the other bases: perlin2002 (C2), and worley F2 - F1 (Euclid and
// Manhattan) away from the cell boundaries of every octave.
TEST(Texture, GradientMatchesFiniteDifferencesOtherBases) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> d(-4.0, 4.0);
    const double h = 1e-6;
    NoiseOptions perlin, euclid, manhattan;
    perlin.basis = NoiseBasis::Perlin2002;
    euclid.basis = manhattan.basis = NoiseBasis::Worley;
    euclid.coef = manhattan.coef = {-1.0, 1.0, 0.0, 0.0};
    euclid.cell = 0.3;  // constant per cell: no gradient, no effect inside a cell
    manhattan.metric = WorleyMetric::Manhattan;
    for (const NoiseOptions& opt : {perlin, euclid, manhattan}) {
        const Texture tex = testTexture(opt);
        int tested = 0;
        for (int k = 0; k < 2000; ++k) {
            const glm::dvec3 s(d(rng), d(rng), d(rng));
            bool inside = true;  // F1 < F2 < F3 with margins: the stencil stays in one cell
            if (opt.basis == NoiseBasis::Worley) {
                for (const Octave& o : tex.octaves) {
                    const glm::dvec3 p = o.M * s + o.offset;
                    const WorleyResult r = worley(p, 3, opt.metric);
                    inside = inside && r.F[1] - r.F[0] > 1e-3 && r.F[2] - r.F[1] > 1e-3;
                    // Manhattan: sign(x - p_n) flips on the point's own coordinate planes,
                    // where F_n is only C0: keep the stencil off them too.
                    for (int n = 0; n < 2 && opt.metric == WorleyMetric::Manhattan; ++n)
                        for (int a = 0; a < 3; ++a) inside = inside && std::abs(r.delta[n][a]) > 1e-3;
                }
            }
            if (!inside) continue;
            glm::dvec3 g;
            evalF(tex, s, &g);
            glm::dvec3 fd;
            for (int a = 0; a < 3; ++a) {
                glm::dvec3 sp = s, sm = s;
                sp[a] += h;
                sm[a] -= h;
                fd[a] = (evalF(tex, sp) - evalF(tex, sm)) / (2 * h);
            }
            ++tested;
            for (int a = 0; a < 3; ++a)
                ASSERT_NEAR(g[a], fd[a], 1e-5 * std::max(1.0, std::abs(fd[a])))
                    << toString(opt.basis) << " s = " << s.x << " " << s.y << " " << s.z << " axis " << a;
        }
        EXPECT_GT(tested, 1000) << toString(opt.basis);
    }
}

TEST(Texture, FilterWidthNorms) {
    const glm::dvec3 g(1.0, -2.0, 3.0), dsdx(1.0, 0.0, 0.0), dsdy(0.0, -1.0, -1.0);
    // gx = 1, gy = 2 - 3 = -1.
    EXPECT_DOUBLE_EQ(filterWidth(g, dsdx, dsdy, GradNorm::Euclid), std::sqrt(2.0));
    EXPECT_DOUBLE_EQ(filterWidth(g, dsdx, dsdy, GradNorm::MaxHalfMin), 1.5);
    EXPECT_DOUBLE_EQ(filterWidth(g, dsdx, dsdy, GradNorm::L1), 2.0);
    const glm::dvec3 ex(0.0, 0.0, -1.0), ey(0.5, 0.0, 0.0);  // gx = -3, gy = 0.5
    EXPECT_DOUBLE_EQ(filterWidth(g, ex, ey, GradNorm::Euclid), std::sqrt(9.25));
    EXPECT_DOUBLE_EQ(filterWidth(g, ex, ey, GradNorm::MaxHalfMin), 3.25);
    EXPECT_DOUBLE_EQ(filterWidth(g, ex, ey, GradNorm::L1), 3.5);
    // The approximations bound the exact norm: |g| <= max + min/2 <= L1 (<= sqrt2 |g|).
    std::mt19937_64 rng(3);
    std::normal_distribution<double> d;
    for (int k = 0; k < 1000; ++k) {
        const glm::dvec3 gs(d(rng), d(rng), d(rng)), a(d(rng), d(rng), d(rng)),
            b(d(rng), d(rng), d(rng));
        const double e = filterWidth(gs, a, b, GradNorm::Euclid);
        const double m = filterWidth(gs, a, b, GradNorm::MaxHalfMin);
        const double l = filterWidth(gs, a, b, GradNorm::L1);
        EXPECT_LE(e, m * (1 + 1e-12));
        EXPECT_LE(m, l * (1 + 1e-12));
        EXPECT_LE(l, std::sqrt(2.0) * e * (1 + 1e-12));
    }
}

TEST(Texture, ZonePlate) {
    // Eq. 16: f = 50 s^2 + 50 t^2; section 3.4: grad = (100 s, 100 t), ds/dx = dt/dy = 1/256,
    // filter width (100 s + 100 t) / 256 with the L1 norm.
    Texture tex;
    tex.quadric.A = 50;
    tex.quadric.E = 50;
    tex.norm = GradNorm::L1;
    std::vector<glm::dvec4> zebra;
    for (int i = 0; i < 16; ++i) zebra.push_back(glm::dvec4(i % 2, i % 2, i % 2, 1));
    tex.clut = ColorMap(zebra, WrapMode::Mod);
    tex.filter = FilterKind::Box;
    const glm::dvec3 dsdx(1.0 / 256, 0, 0), dsdy(0, 1.0 / 256, 0);
    for (double s : {0.1, 0.5, 0.9})
        for (double t : {0.2, 0.7}) {
            const TextureSample r = shade(tex, glm::dvec3(s, t, 0.3), dsdx, dsdy);
            EXPECT_NEAR(r.f, 50 * s * s + 50 * t * t, 1e-12);
            EXPECT_NEAR(r.gradS.x, 100 * s, 1e-12);
            EXPECT_NEAR(r.gradS.y, 100 * t, 1e-12);
            EXPECT_EQ(r.gradS.z, 0.0);
            EXPECT_NEAR(r.filterWidth, (100 * s + 100 * t) / 256, 1e-12);
            EXPECT_EQ(r.rgba, tex.clut.filterBox(r.f, r.filterWidth));
            // The wide filter averages the zebra to grey.
            if (r.filterWidth * 16 > 8) {
                EXPECT_NEAR(r.rgba.r, 0.5, 0.05);
            }
        }
}

TEST(Texture, ShadeUsesTheGivenFilter) {
    Texture tex = testTexture({});
    std::mt19937_64 rng(4);
    tex.clut = ColorMap([&] {
        std::vector<glm::dvec4> e(64);
        std::uniform_real_distribution<double> d(0, 1);
        for (auto& c : e) c = glm::dvec4(d(rng), d(rng), d(rng), 1);
        return e;
    }(), WrapMode::Clamp);
    tex.norm = GradNorm::MaxHalfMin;
    const glm::dvec3 s(0.3, -1.2, 2.5), dsdx(0.01, 0.002, 0), dsdy(-0.003, 0.004, 0.02);
    for (FilterKind k : {FilterKind::None, FilterKind::MipNearest, FilterKind::MipLinear,
                         FilterKind::Sat, FilterKind::Box}) {
        tex.filter = k;
        const TextureSample a = shade(tex, s, dsdx, dsdy);
        const TextureSample b = shade(tex, s, dsdx, dsdy, k);
        glm::dvec3 g;
        EXPECT_EQ(a.f, evalF(tex, s, &g));
        EXPECT_EQ(a.gradS, g);
        EXPECT_EQ(a.filterWidth, filterWidth(g, dsdx, dsdy, GradNorm::MaxHalfMin));
        EXPECT_EQ(a.rgba, tex.clut.filter(a.f, a.filterWidth, k));
        EXPECT_EQ(b.rgba, a.rgba);
    }
    EXPECT_EQ(shade(tex, s, dsdx, dsdy, FilterKind::None).rgba,
              tex.clut.sample(evalF(tex, s)));
}

TEST(Texture, BandlimitedOffIsThePointSampleAndFootprintWidensByTheRemovedSpread) {
    Texture tex = testTexture({});
    const glm::dvec3 s(0.3, -1.2, 2.7), mid(0.5, 0, 0), midY(0, 0.01, 0);
    glm::dvec3 g, gb;
    const double f = evalF(tex, s, &g);
    double sd = -1;
    EXPECT_EQ(evalFBandlimited(tex, s, mid, midY, &gb, &sd), f);  // off
    EXPECT_EQ(gb, g);
    EXPECT_EQ(sd, 0.0);
    // The basis's moments (rayshade: mean about 0).
    const NoiseMoments m = noiseMoments(tex.noise);
    EXPECT_LT(std::abs(m.mean), 0.05 * m.sd);
    EXPECT_GT(m.sd, 0.0);
    // Footprint: the box grows to the variance of what was removed, sqrt(w^2 + 12 sd^2).
    tex.bandlimit = Bandlimit::Footprint;
    evalFBandlimited(tex, s, mid, midY, &gb, &sd);
    EXPECT_GT(sd, 0.0);
    const double w = filterWidth(gb, mid, midY, tex.norm);
    EXPECT_DOUBLE_EQ(shade(tex, s, mid, midY).filterWidth, std::sqrt(w * w + 12.0 * sd * sd));
}

// The variance gain of a box average of the noise: 1 for a point, falling like c / nu for long
// segments; checked against an independent Monte Carlo estimate (mt19937 segments).
TEST(Texture, NoiseBoxGain) {
    const NoiseOptions opt;
    EXPECT_EQ(noiseBoxGain(opt, 0.0), 1.0);
    EXPECT_GT(noiseBoxGain(opt, 0.1), 0.9);
    for (double nu : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0})
        EXPECT_LT(noiseBoxGain(opt, 2 * nu), noiseBoxGain(opt, nu)) << nu;
    EXPECT_NEAR(noiseBoxGain(opt, 64.0) * 64.0, noiseBoxGain(opt, 32.0) * 32.0, 1e-12);  // c / nu beyond
    const double g16 = noiseBoxGain(opt, 16.0) * 16.0, g8 = noiseBoxGain(opt, 8.0) * 8.0;
    EXPECT_NEAR(g16 / g8, 1.0, 0.35);  // already ~ c / nu at the table's end
    // Independent estimate at nu = 1 and 4.
    const NoiseMoments m = noiseMoments(opt);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    for (double nu : {1.0, 4.0}) {
        double s2 = 0;
        const int n = 3000, q = 64;
        for (int i = 0; i < n; ++i) {
            const glm::dvec3 p0(100 * u(rng), 100 * u(rng), 100 * u(rng));
            const glm::dvec3 d = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
            double mean = 0;
            for (int j = 0; j < q; ++j) mean += noise(p0 + (j + 0.5) / q * nu * d, opt);
            s2 += std::pow(mean / q - m.mean, 2);
        }
        EXPECT_NEAR(noiseBoxGain(opt, nu), s2 / n / (m.sd * m.sd), 0.15 * noiseBoxGain(opt, nu)) << nu;
    }
}

// Footprint: the full texture for a vanishing footprint; for a long thin footprint the term is
// the mean of its samples along the long edge (checked by hand for one octave).
TEST(Texture, FootprintBandlimit) {
    Texture tex = testTexture({});
    const glm::dvec3 s(0.3, -1.2, 2.7);
    glm::dvec3 g, gb;
    const double f = evalF(tex, s, &g);
    const glm::dvec3 tiny(1e-9, 0, 0), tinyY(0, 1e-9, 0);
    tex.bandlimit = Bandlimit::Footprint;
    double sd = -1;
    EXPECT_NEAR(evalFBandlimited(tex, s, tiny, tinyY, &gb, &sd), f, 1e-6);
    EXPECT_NEAR(glm::length(gb - g), 0.0, 1e-6 * glm::length(g));
    EXPECT_LT(sd, 1e-3);
    Octave o;
    o.amplitude = 1;
    o.M = glm::dmat3(1.0);
    const NoiseOptions opt;
    const NoiseMoments m = noiseMoments(opt);
    const glm::dvec3 dx(3.0, 0, 0), dy(0, 0.01, 0);   // 3 cells along x: K = 6 samples
    double v = 0;
    for (int k = 0; k < 6; ++k) v += noise(s + glm::dvec3(((k + 0.5) / 6 - 0.5) * 3.0, 0, 0), opt);
    v /= 6;
    const double w = std::sqrt(noiseBoxGain(opt, 0.01));     // samples 0.5 cell apart: gK = g(3)
    double kept = 0;
    EXPECT_NEAR(octaveFootprint(o, opt, s, dx, dy, nullptr, &kept), m.mean + w * (v - m.mean), 1e-12);
    EXPECT_NEAR(kept, noiseBoxGain(opt, 3.0) * noiseBoxGain(opt, 0.01), 1e-12);
    // Capped samples (64 cells, 16 samples 4 cells apart): the weight falls by sqrt(g(64) / (1/16)).
    const glm::dvec3 far(64.0, 0, 0);
    v = 0;
    for (int k = 0; k < 16; ++k) v += noise(s + glm::dvec3(((k + 0.5) / 16 - 0.5) * 64.0, 0, 0), opt);
    v /= 16;
    const double wf = std::sqrt(noiseBoxGain(opt, 0.01)) * std::sqrt(noiseBoxGain(opt, 64.0) * 16.0);
    EXPECT_LT(wf, 1.0);
    EXPECT_NEAR(octaveFootprint(o, opt, s, far, dy, nullptr, nullptr), m.mean + wf * (v - m.mean), 1e-12);
}

// The filter-width cap (issue 44 part 2): sqrt(12 sum a_i^2) sd(n) on noise alone (every octave, or
// the first `octaves`), none (infinite) once any of A..I is non-zero (J alone is a constant);
// shade() and capWidth() take w down to it and scale the footprint's two widths by as much.
TEST(Texture, WidthCap) {
    NoiseOptions opt;
    Texture tex = testTexture(opt);
    EXPECT_TRUE(quadricVaries(tex.quadric));
    EXPECT_TRUE(std::isinf(widthCapOf(tex)));
    const double sd = noiseMoments(opt).sd;
    ASSERT_GT(sd, 0.1);
    ASSERT_LT(sd, 0.5);
    tex.quadric = Quadric();
    tex.quadric.J = 0.7;   // a constant: no spread
    EXPECT_FALSE(quadricVaries(tex.quadric));
    double a2 = 0;
    for (const Octave& o : tex.octaves) a2 += o.amplitude * o.amplitude;
    EXPECT_NEAR(widthCapOf(tex), std::sqrt(12 * a2) * sd, 1e-12);
    const double a0 = tex.octaves[0].amplitude;
    EXPECT_NEAR(widthCapOf(tex, 1), std::sqrt(12.0) * std::abs(a0) * sd, 1e-12);
    EXPECT_EQ(widthCapOf(tex, 0), 0.0);
    for (double Quadric::*c : {&Quadric::A, &Quadric::B, &Quadric::C, &Quadric::D, &Quadric::E, &Quadric::F,
                               &Quadric::G, &Quadric::H, &Quadric::I}) {
        Texture t2 = tex;
        t2.quadric.*c = 1e-3;
        EXPECT_TRUE(std::isinf(widthCapOf(t2)));
    }
    // capWidth: below the cap nothing moves; above, w is the cap and wxy scales by cap / w.
    const double cap = widthCapOf(tex);
    double w = 0.5 * cap;
    glm::dvec2 wxy(0.3 * cap, 0.4 * cap);
    capWidth(tex, &w, &wxy);
    EXPECT_EQ(w, 0.5 * cap);
    EXPECT_EQ(wxy.x, 0.3 * cap);
    w = 4 * cap;
    wxy = glm::dvec2(2.4 * cap, 3.2 * cap);
    capWidth(tex, &w, &wxy);
    EXPECT_DOUBLE_EQ(w, cap);
    EXPECT_DOUBLE_EQ(wxy.x, 0.6 * cap);
    EXPECT_DOUBLE_EQ(wxy.y, 0.8 * cap);
    // shade(): the capped width where the gradient's is wider (a minified pixel), the same elsewhere.
    Texture capped = tex;
    capped.widthCap = true;
    const glm::dvec3 s(0.3, 0.2, 0.1);
    for (double scale : {1e-4, 1.0, 100.0}) {
        const glm::dvec3 dx(scale, 0, 0), dy(0, scale, 0);
        const TextureSample a = shade(tex, s, dx, dy), b = shade(capped, s, dx, dy);
        EXPECT_EQ(b.f, a.f);
        EXPECT_DOUBLE_EQ(b.filterWidth, std::min(a.filterWidth, cap));
    }
    EXPECT_GT(shade(tex, s, glm::dvec3(100, 0, 0), glm::dvec3(0, 100, 0)).filterWidth, cap);
}

TEST(Texture, GradNormNamesRoundTrip) {
    for (GradNorm v : {GradNorm::Euclid, GradNorm::MaxHalfMin, GradNorm::L1}) {
        GradNorm r;
        ASSERT_TRUE(parseGradNorm(toString(v), &r));
        EXPECT_EQ(r, v);
    }
    EXPECT_STREQ(toString(GradNorm::MaxHalfMin), "max_half_min");
    GradNorm r;
    EXPECT_FALSE(parseGradNorm("l2", &r));
}

}  // namespace
}  // namespace pst

namespace pst {
namespace {

TEST(Texture, SpectralNormAndFootprintNorm) {
    EXPECT_NEAR(spectralNorm(glm::dmat3(4.0)), 4.0, 1e-12);
    // diag(1, -3, 2) rotated: the largest |singular value| is 3.
    const glm::dmat3 D(1, 0, 0, 0, -3, 0, 0, 0, 2);
    const double c = std::cos(0.7), s = std::sin(0.7);
    const glm::dmat3 R(c, s, 0, -s, c, 0, 0, 0, 1);
    EXPECT_NEAR(spectralNorm(R * D * glm::transpose(R)), 3.0, 1e-9);
    // A rank-one matrix u v^T: |u| |v|.
    const glm::dvec3 u(1, 2, 2), v(0, 3, 4);
    glm::dmat3 uv;
    for (int col = 0; col < 3; ++col) uv[col] = u * v[col];
    EXPECT_NEAR(spectralNorm(uv), 15.0, 1e-9);
    // max + 3/8 (mid + min): exact on an axis, within -2.8 % (1, 1, 0) .. +13.2 % (1, 3/8, 3/8) of |v|.
    EXPECT_DOUBLE_EQ(footprintNorm(glm::dvec3(0, -2, 0)), 2.0);
    EXPECT_DOUBLE_EQ(footprintNorm(glm::dvec3(1, -1, 1)), 1.75);
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 w(std::sin(i * 1.3), std::cos(i * 0.7), std::sin(i * 2.9 + 1));
        const double r = footprintNorm(w) / glm::length(w);
        EXPECT_GE(r, 0.9722);
        EXPECT_LE(r, 1.1320);
    }
}

TEST(Texture, IsotropicBandlimitBoundsEachEdgeAndScalesTermAndGradient) {
    Texture tex = testTexture({});
    tex.octaves.resize(2);
    tex.octaves[0].M = glm::dmat3(1.0);
    tex.octaves[1].M = glm::dmat3(8.0);
    const glm::dvec3 s(0.3, -1.2, 2.7);
    const Octave& o1 = tex.octaves[1];
    // Small footprints keep the term whole (the table's lowest nu, 1/8 cell, as good as a point).
    const glm::dvec3 tiny(1e-6, 0, 0), tinyY(0, 1e-6, 0);
    const double h0 = std::sqrt(noiseBoxGain(tex.noise, 0.125));
    EXPECT_DOUBLE_EQ(octaveIsotropic(o1, tex.noise, tiny, tinyY), h0 * h0);
    EXPECT_GT(h0, 0.99);
    // Each edge by its own bound: nu = 8 |edge| for a scaled identity.
    const glm::dvec3 ex(0.25, 0, 0), ey(0, 0, 0.05);
    EXPECT_DOUBLE_EQ(octaveIsotropic(o1, tex.noise, ex, ey),
                     std::sqrt(noiseBoxGain(tex.noise, 2.0)) * std::sqrt(noiseBoxGain(tex.noise, 0.4)));
    // Above the table (2^5 cells) the fade stops falling.
    EXPECT_DOUBLE_EQ(octaveIsotropic(o1, tex.noise, glm::dvec3(100, 0, 0), tinyY),
                     octaveIsotropic(o1, tex.noise, glm::dvec3(4, 0, 0), tinyY));
    // f and grad: each term a (mean + alpha (n - mean)) (toward the basis's mean), a alpha M^T
    // grad n (toward 0), no widening.
    tex.bandlimit = Bandlimit::Isotropic;
    glm::dvec3 gb;
    double sd = -1;
    const double fb = evalFBandlimited(tex, s, ex, ey, &gb, &sd);
    double f = tex.quadric.value(s);
    glm::dvec3 g = tex.quadric.gradient(s);
    const double mean = noiseMoments(tex.noise).mean;
    for (const Octave& o : tex.octaves) {
        glm::dvec3 gn;
        const double alpha = octaveIsotropic(o, tex.noise, ex, ey), a = o.amplitude * alpha;
        f += o.amplitude * (mean + alpha * (noise(o.M * s + o.offset, tex.noise, &gn) - mean));
        g += a * (glm::transpose(o.M) * gn);
    }
    EXPECT_DOUBLE_EQ(fb, f);
    EXPECT_NEAR(glm::length(gb - g), 0.0, 1e-12);
    EXPECT_EQ(sd, 0.0);
    EXPECT_DOUBLE_EQ(shade(tex, s, ex, ey).filterWidth, filterWidth(gb, ex, ey, tex.norm));
    Bandlimit b;
    ASSERT_TRUE(parseBandlimit("isotropic", &b));
    EXPECT_EQ(b, Bandlimit::Isotropic);
    EXPECT_STREQ(toString(b), "isotropic");
}

// A basis whose mean is not 0 (worley's F1, 0.35): a fully faded octave leaves its mean, not 0.
TEST(Texture, IsotropicBandlimitFadesToTheBasissMean) {
    Texture tex = testTexture({});
    tex.noise.basis = NoiseBasis::Worley;
    tex.octaves.resize(1);
    tex.octaves[0].M = glm::dmat3(8.0);
    tex.octaves[0].amplitude = 0.5;
    tex.bandlimit = Bandlimit::Isotropic;
    const glm::dvec3 s(0.3, -1.2, 2.7), big(100, 0, 0), bigY(0, 100, 0);
    const double alpha = octaveIsotropic(tex.octaves[0], tex.noise, big, bigY);
    const double mean = noiseMoments(tex.noise).mean;
    ASSERT_GT(mean, 0.3);
    ASSERT_LT(alpha, 0.05);
    const double f = evalFBandlimited(tex, s, big, bigY, nullptr, nullptr) - tex.quadric.value(s);
    EXPECT_NEAR(f, 0.5 * mean, 0.5 * alpha * 2.0);  // |n - mean| < 2 for F1
    EXPECT_GT(f, 0.5 * mean * 0.8);
}

}  // namespace
}  // namespace pst

// Tests of the golden octave transform and noise unit (noise_fx.h) against the double
// reference (model/noise.h): same hash indices, exact ROM values, and errors within the bounds
// derived from the formats (noiseFxErrorBound, derivation in noise_fx.cpp).
#include "noise_fx.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "fixed.h"
#include "noise.h"
#include "perlin2002.h"
#include "profile.h"
#include "source_dir.h"

namespace pst {
namespace {

Profile profile(const char* name) { return loadNamedProfile(name, sourceDir()); }

// A profile's formats with another noise variant: its keys, and Profile::noise from them.
void setNoiseKeys(Profile& p, NoiseInterp interp, NoiseCorner corner, NoiseHash hash) {
    p.noiseInterp = interp;
    p.noiseCorner = corner;
    p.noiseHash = hash;
    p.noise = hardwareNoise(p);
}

// A profile's formats with the noise unit in Perlin's 2002 variant (basis perlin2002).
Profile perlinProfile(const char* name) {
    Profile p = profile(name);
    setNoiseKeys(p, NoiseInterp::Quintic, NoiseCorner::Grad12, NoiseHash::Perlin256);
    return p;
}

// The noise unit's input for a point p: s = quantize(p) (Coord), M = identity, o = 0, through
// octaveTransformFx. Also returns the exact point the unit sees (pq) and its lattice cell.
struct UnitInput {
    int lat[3];
    int64_t frac[3];
    double pq[3];
    int64_t cell[3];  // floor(pq)
};

UnitInput unitInput(const Profile& prof, const double p[3]) {
    UnitInput in;
    int64_t s[3], M[9] = {}, o[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) s[k] = fx::quantize(p[k], prof.coord.intBits, prof.coord.fracBits);
    for (int k = 0; k < 3; ++k) M[4 * k] = fx::quantize(1.0, prof.matrix.intBits, prof.matrix.fracBits);
    octaveTransformFx(prof, s, M, o, in.lat, in.frac);
    for (int k = 0; k < 3; ++k) {
        in.cell[k] = int64_t(fx::floorShift(s[k], prof.coord.fracBits));
        in.pq[k] = double(in.cell[k]) + std::ldexp(double(in.frac[k]), -prof.noiseLatticeFrac);
    }
    return in;
}

TEST(NoiseFx, ValueRomIsTheReferenceTable) {
    const auto& R = NoiseTables::get().value;
    Profile prof = profile("full");
    for (int vf : {15, 11, 7, 1}) {
        prof.noiseValueFrac = vf;
        for (int i = 0; i < NoiseTables::kValueSize; ++i) {
            const double v16 = R[i] * 32768.0;
            ASSERT_EQ(v16, std::floor(v16)) << "R[" << i << "] is not Q1.15";
            EXPECT_EQ(noiseValueRom(prof, i), int64_t(std::floor(std::ldexp(R[i], vf)))) << "i " << i;
        }
    }
}

TEST(NoiseFx, OctaveTransformMatchesLongDouble) {
    // acc is at most ~60 bits: exact in long double (64-bit mantissa on x86-64).
    static_assert(std::numeric_limits<long double>::digits >= 64, "needs x87 long double");
    for (const char* name : {"full", "reduced", "balanced"}) {
        const Profile prof = profile(name);
        std::mt19937_64 rng(11);
        auto rnd = [&](const FixedFormat& f) {
            return fx::wrapSigned(int64_t(rng()), f.width());
        };
        for (int it = 0; it < 20000; ++it) {
            int64_t s[3], M[9], o[3];
            for (auto& v : s) v = rnd(prof.coord);
            for (auto& v : M) v = rnd(prof.matrix);
            for (auto& v : o) v = rnd(prof.offset);
            int lat[3];
            int64_t frac[3];
            octaveTransformFx(prof, s, M, o, lat, frac);
            for (int r = 0; r < 3; ++r) {
                long double p = std::ldexp((long double)o[r], -prof.offset.fracBits);
                for (int j = 0; j < 3; ++j)
                    p += std::ldexp((long double)M[3 * r + j] * (long double)s[j],
                                    -(prof.matrix.fracBits + prof.coord.fracBits));
                const long double scaled = std::floor(std::ldexp(p, prof.noiseLatticeFrac));
                const long double ip = std::floor(std::ldexp(scaled, -prof.noiseLatticeFrac));
                const int64_t f = int64_t(scaled - std::ldexp(ip, prof.noiseLatticeFrac));
                const int64_t L = ((int64_t(std::fmod(ip, 4096.0L)) + 576) % 4096 + 4096) % 4096;
                ASSERT_EQ(frac[r], f) << name << " it " << it << " r " << r;
                ASSERT_EQ(lat[r], L) << name << " it " << it << " r " << r;
            }
        }
    }
}

TEST(NoiseFx, HashIsTheReferenceHash) {
    for (const char* name : {"full", "reduced", "balanced"}) {
        for (NoiseHash hash : {NoiseHash::Rayshade, NoiseHash::Perm256, NoiseHash::Perlin256}) {
            Profile prof = profile(name);
            setNoiseKeys(prof, prof.noiseInterp, prof.noiseCorner, hash);
            std::mt19937_64 rng(5);
            // Beyond +-2048 too: the lattice index wraps at 4096 (perm256 at 256).
            std::uniform_real_distribution<double> coord(-50.0, 50.0), wide(-500.0, 500.0);
            for (int it = 0; it < 10000; ++it) {
                double p[3];
                for (double& c : p) c = it % 2 ? coord(rng) : wide(rng);
                const UnitInput in = unitInput(prof, p);
                int64_t n, g[3];
                NoiseFxTrace tr;
                noiseFx(prof, in.lat, in.frac, &n, g, &tr);
                for (int k = 0; k < 3; ++k) ASSERT_EQ(in.lat[k], int((in.cell[k] + 1000000) & 0xfff));
                for (int c = 0; c < 8; ++c) {
                    const int ix = int(in.cell[0]) + 1000000 + (c & 1);
                    const int iy = int(in.cell[1]) + 1000000 + ((c >> 1) & 1);
                    const int iz = int(in.cell[2]) + 1000000 + ((c >> 2) & 1);
                    ASSERT_EQ(tr.m[c], noiseHash(ix, iy, iz, hash)) << name << " corner " << c;
                }
            }
        }
    }
}

TEST(NoiseFx, HashOfLatticeIndexWraps) {
    // lat is the lattice index mod 4096 (mod 256 for perm256 after & 0xff): corner + 1 of
    // 4095 is 0 (and of 255 is 256 -> 0 for perm256), as noiseHash of the unwrapped index.
    const Profile prof = profile("full");
    std::mt19937 rng(3);
    for (NoiseHash hash : {NoiseHash::Rayshade, NoiseHash::Perm256}) {
        Profile p = prof;
        setNoiseKeys(p, p.noiseInterp, p.noiseCorner, hash);
        for (int it = 0; it < 5000; ++it) {
            int lat[3];
            for (int& l : lat) {
                const int pick = int(rng() % 8);
                l = pick == 0 ? 4095 : pick == 1 ? 255 : pick == 2 ? 0 : int(rng() % 4096);
            }
            const int64_t frac[3] = {0, 1, 2};
            int64_t n, g[3];
            NoiseFxTrace tr;
            noiseFx(p, lat, frac, &n, g, &tr);
            for (int c = 0; c < 8; ++c)
                ASSERT_EQ(tr.m[c], noiseHash(lat[0] + (c & 1), lat[1] + ((c >> 1) & 1), lat[2] + (c >> 2), hash));
        }
    }
}

TEST(NoiseFx, LatticePointIsHalfR) {
    // u = 0: every weight is 0, n = 0.5 R[m] of corner 0 exactly (when OF >= VF + 1),
    // and the gradient is (R[m+1], R[m+2], R[m+3]) (plus 0 from ds = 0 for scurve).
    const Profile prof = profile("full");
    const auto& R = NoiseTables::get().value;
    for (int L : {0, 1, 575, 576, 4095}) {
        const int lat[3] = {L, (L * 7) & 4095, (L * 13 + 5) & 4095};
        const int64_t frac[3] = {0, 0, 0};
        int64_t n, g[3];
        NoiseFxTrace tr;
        noiseFx(prof, lat, frac, &n, g, &tr);
        EXPECT_EQ(fx::toDouble(n, prof.noiseOutFrac), 0.5 * R[tr.m[0]]);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(fx::toDouble(g[k], prof.noiseOutFrac), R[tr.m[0] + 1 + k]);
    }
}

// Golden against noise(p_q) (the point the unit sees: arithmetic error only) and against
// noise(p) (plus the input quantization p - p_q), over 10k random points in [-50, 50]^3.
void checkAgainstReference(const Profile& prof, const std::string& label) {
    const NoiseFxErrorBound bound = noiseFxErrorBound(prof);
    std::mt19937_64 rng(1234);
    std::uniform_real_distribution<double> coord(-50.0, 50.0);
    double maxV = 0, maxG = 0, maxVp = 0, maxGp = 0, sumV2 = 0;
    int gradSkipped = 0;
    const int count = 10000;
    for (int it = 0; it < count; ++it) {
        double p[3];
        for (double& c : p) c = coord(rng);
        const UnitInput in = unitInput(prof, p);
        int64_t n, g[3];
        noiseFx(prof, in.lat, in.frac, &n, g);
        const double nf = fx::toDouble(n, prof.noiseOutFrac);
        double gf[3];
        for (int k = 0; k < 3; ++k) gf[k] = fx::toDouble(g[k], prof.noiseOutFrac);

        glm::dvec3 gq, gp;
        const double nq = noise(glm::dvec3(in.pq[0], in.pq[1], in.pq[2]), prof.noise, &gq);
        const double np = noise(glm::dvec3(p[0], p[1], p[2]), prof.noise, &gp);

        const double ev = std::fabs(nf - nq);
        sumV2 += ev * ev;
        maxV = std::max(maxV, ev);
        ASSERT_LE(ev, bound.value) << label << " p = " << p[0] << " " << p[1] << " " << p[2];
        for (int k = 0; k < 3; ++k) {
            const double eg = std::fabs(gf[k] - gq[k]);
            maxG = std::max(maxG, eg);
            ASSERT_LE(eg, bound.grad) << label << " axis " << k << " p = " << p[0] << " " << p[1] << " " << p[2];
        }

        // Input quantization: |n(p) - n(p_q)| <= gMax sum |dp|; the gradient moves by at most
        // hessianRow max|dp| inside one cell (scurve's gradient is continuous across cells;
        // linear's is not, so its gradient is compared only when p and p_q share the cell).
        double sumDp = 0, maxDp = 0;
        bool sameCell = true;
        for (int k = 0; k < 3; ++k) {
            const double dp = std::fabs(p[k] - in.pq[k]);
            sumDp += dp;
            maxDp = std::max(maxDp, dp);
            sameCell = sameCell && std::floor(p[k]) == double(in.cell[k]);
        }
        const double evp = std::fabs(nf - np);
        maxVp = std::max(maxVp, evp);
        ASSERT_LE(evp, bound.value + bound.gradMax * sumDp) << label;
        if (prof.noiseInterp != NoiseInterp::Linear || sameCell) {
            for (int k = 0; k < 3; ++k) {
                const double eg = std::fabs(gf[k] - gp[k]);
                maxGp = std::max(maxGp, eg);
                ASSERT_LE(eg, bound.grad + bound.hessianRow * maxDp) << label << " axis " << k;
            }
        } else {
            ++gradSkipped;
        }
    }
    std::printf("[ noise_fx ] %-44s |n-n(pq)| max %.3g rms %.3g (bound %.3g); |g-g(pq)| max %.3g (bound %.3g); "
                "vs n(p): max %.3g, grad %.3g%s\n",
                label.c_str(), maxV, std::sqrt(sumV2 / count), bound.value, maxG, bound.grad, maxVp, maxGp,
                gradSkipped ? (" (" + std::to_string(gradSkipped) + " cell-crossing grads skipped)").c_str() : "");
}

TEST(NoiseFx, FullProfileTracksReference) {
    const Profile prof = profile("full");
    const NoiseFxErrorBound b = noiseFxErrorBound(prof);
    // The derived bounds for the full formats: about 1.1e-3 (value) and 4e-3 (gradient).
    EXPECT_LT(b.value, 1.2e-3);
    EXPECT_LT(b.grad, 1e-2);
    checkAgainstReference(prof, "full");
}

TEST(NoiseFx, ReducedProfileTracksReference) {
    const Profile prof = profile("reduced");
    checkAgainstReference(prof, "reduced");
}

// Every interpolation / corner / hash variant with each profile's formats.
TEST(NoiseFx, VariantsTrackReference) {
    for (const char* name : {"full", "reduced"}) {
        for (NoiseInterp interp : {NoiseInterp::Scurve, NoiseInterp::Linear})
            for (NoiseCorner corner : {NoiseCorner::ValueGradient, NoiseCorner::Value})
                for (NoiseHash hash : {NoiseHash::Rayshade, NoiseHash::Perm256}) {
                    Profile prof = profile(name);
                    setNoiseKeys(prof, interp, corner, hash);
                    checkAgainstReference(prof, std::string(name) + " formats " + toString(interp) + "/" +
                                                    toString(corner) + "/" + toString(hash));
                }
    }
}

// noise.grad_frac below the node fraction bits (derivative lanes floored to 2^-grad_frac):
// the value is bit for bit the exact unit's, the gradient within the widened bound, and every
// derivative node a multiple of 2^noiseGradFloor; grad_frac >= the node bits changes nothing.
TEST(NoiseFx, GradFracFloorsOnlyTheDerivatives) {
    std::mt19937_64 rng(77);
    for (const char* name : {"full", "reduced"}) {
        for (NoiseInterp interp : {NoiseInterp::Scurve, NoiseInterp::Linear})
            for (NoiseCorner corner : {NoiseCorner::ValueGradient, NoiseCorner::Value}) {
                Profile exact = profile(name);
                setNoiseKeys(exact, interp, corner, NoiseHash::Perm256);
                const int NF = noiseNodeFrac(exact);
                ASSERT_LE(exact.noiseGradFrac, NF) << name;   // full 16 of 20, reduced every node bit
                exact.noiseGradFrac = NF;                        // the exact unit
                ASSERT_EQ(noiseGradFloor(exact), 0);
                Profile wide = exact;
                wide.noiseGradFrac = NF + 5;                     // above NF: the same unit
                Profile cut = exact;
                cut.noiseGradFrac = NF - 8;
                ASSERT_EQ(noiseGradFloor(cut), 8);
                const std::string label = std::string(name) + " " + toString(interp) + "/" + toString(corner) +
                                          " grad_frac " + std::to_string(cut.noiseGradFrac);
                checkAgainstReference(cut, label);
                std::uniform_int_distribution<int> L(0, 4095);
                std::uniform_int_distribution<int64_t> U(0, (int64_t(1) << exact.noiseLatticeFrac) - 1);
                int differ = 0;
                for (int it = 0; it < 2000; ++it) {
                    int lat[3];
                    int64_t frac[3];
                    for (int k = 0; k < 3; ++k) {
                        lat[k] = L(rng);
                        frac[k] = U(rng);
                    }
                    int64_t n0, g0[3], n1, g1[3], n2, g2[3];
                    NoiseFxTrace tr;
                    noiseFx(exact, lat, frac, &n0, g0);
                    noiseFx(wide, lat, frac, &n1, g1);
                    noiseFx(cut, lat, frac, &n2, g2, &tr);
                    ASSERT_EQ(n0, n1);
                    ASSERT_EQ(n0, n2) << label;
                    for (int k = 0; k < 3; ++k) {
                        ASSERT_EQ(g0[k], g1[k]);
                        differ += g0[k] != g2[k];
                    }
                    for (int c = 0; c < 8; ++c)
                        for (int k = 1; k < 4; ++k) ASSERT_EQ(tr.corner[c][k] % 256, 0) << label;
                    for (int i = 0; i < 7; ++i)
                        for (int k = 1; k < 4; ++k) ASSERT_EQ(tr.node[i][k] % 256, 0) << label;
                }
                EXPECT_GT(differ, 0) << label;   // the floor is not a no-op
            }
    }
}

// Perlin's 2002 variant (quintic, grad12, perlin256) against perlin2002() (its reference is
// ImprovedNoise.java bit for bit) with each profile's formats.
TEST(NoiseFx, Perlin2002TracksReference) {
    for (const char* name : {"full", "reduced"}) {
        const Profile prof = perlinProfile(name);
        ASSERT_EQ(prof.noise.basis, NoiseBasis::Perlin2002);
        checkAgainstReference(prof, std::string(name) + " formats perlin2002");
    }
}

// The quintic weights against fade(u) = 6u^5 - 15u^4 + 10u^3 and fade'(u) = 30u^2 (1 - u)^2
// for every u at LF = 2..16: s in (fade - 11q, fade], ds in (fade' - q, fade' + 15q + 30q^2)
// (the intervals noiseFxErrorBound uses), s < 1, ds < 4 (pst_noise_weight's port widths).
TEST(NoiseFx, QuinticWeightsExhaustive) {
    Profile prof = perlinProfile("full");
    for (int LF = 2; LF <= 16; ++LF) {
        prof.noiseLatticeFrac = LF;
        const double q = std::ldexp(1.0, -LF);
        double worstS = 0, worstDs = 0;
        for (int64_t U = 0; U < (int64_t(1) << LF); ++U) {
            const int lat[3] = {100, 200, 300};
            const int64_t frac[3] = {U, 0, 0};
            int64_t n, g[3];
            NoiseFxTrace tr;
            noiseFx(prof, lat, frac, &n, g, &tr);
            const double u = double(U) * q;
            const double fade = u * u * u * (u * (u * 6 - 15) + 10), dfade = 30 * u * u * (1 - u) * (1 - u);
            const double s = double(tr.s[0]) * q, ds = double(tr.ds[0]) * q;
            ASSERT_LT(tr.s[0], int64_t(1) << LF) << "LF " << LF << " U " << U;
            ASSERT_LT(tr.ds[0], int64_t(4) << LF) << "LF " << LF << " U " << U;
            ASSERT_LE(s, fade) << "LF " << LF << " U " << U;
            ASSERT_GT(s, fade - 11 * q) << "LF " << LF << " U " << U;
            ASSERT_GT(ds, dfade - q) << "LF " << LF << " U " << U;
            ASSERT_LT(ds, dfade + 15 * q + 30 * q * q) << "LF " << LF << " U " << U;
            worstS = std::max(worstS, (fade - s) / q);
            worstDs = std::max(worstDs, std::fabs(ds - dfade) / q);
        }
        if (LF == 8 || LF == 16) std::printf("[ noise_fx ] quintic LF %d: s error <= %.2f LSB, ds error <= %.2f LSB\n", LF, worstS, worstDs);
    }
}

// grad12 corners at a lattice point (u = 0): n = grad(m, 0, 0, 0) = 0 and the gradient is
// corner 0's direction, two components +-1 and one 0.
TEST(NoiseFx, Grad12LatticePoint) {
    const Profile prof = perlinProfile("full");
    for (int i = 0; i < 4096; i += 7) {
        const int lat[3] = {i, (i * 5 + 3) & 4095, (i * 11 + 9) & 4095};
        const int64_t frac[3] = {0, 0, 0};
        int64_t n, g[3];
        NoiseFxTrace tr;
        noiseFx(prof, lat, frac, &n, g, &tr);
        EXPECT_EQ(n, 0);
        int ones = 0, zeros = 0;
        for (int k = 0; k < 3; ++k) {
            ones += std::llabs(g[k]) == (int64_t(1) << prof.noiseOutFrac);
            zeros += g[k] == 0;
        }
        EXPECT_EQ(ones, 2);
        EXPECT_EQ(zeros, 1);
        glm::dvec3 gr;
        perlin2002(glm::dvec3(i - 576, ((i * 5 + 3) & 4095) - 576, ((i * 11 + 9) & 4095) - 576), &gr);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(fx::toDouble(g[k], prof.noiseOutFrac), gr[k]) << "lat " << i;
    }
}

}  // namespace
}  // namespace pst

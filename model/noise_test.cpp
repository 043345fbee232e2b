// Tests of the Rayshade noise reference: tables against independent computations, the
// exact Noise3 expression, the analytic gradient against finite differences.
#include "noise.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace pst {
namespace {

// Bitwise CRC-16/ARC (no table): the independent check of crc16() and of R.
uint16_t crcBitwise(const uint8_t* p, size_t n) {
    unsigned crc = 0;
    for (size_t k = 0; k < n; ++k) {
        crc ^= p[k];
        for (int b = 0; b < 8; ++b) crc = (crc & 1) ? (crc >> 1) ^ 0xA001u : crc >> 1;
    }
    return static_cast<uint16_t>(crc);
}

TEST(Noise, CrcTableKnownValues) {
    // crc16 of one byte b is xtab[b] (crc starts at 0).
    auto xtab = [](int b) {
        uint8_t byte = static_cast<uint8_t>(b);
        return crc16(&byte, 1);
    };
    EXPECT_EQ(xtab(0), 0x0000);
    EXPECT_EQ(xtab(1), 0xc0c1);
    EXPECT_EQ(xtab(2), 0xc181);
    EXPECT_EQ(xtab(255), 0x4040);
    // The standard CRC-16/ARC check value of "123456789".
    const char* check = "123456789";
    EXPECT_EQ(crc16(reinterpret_cast<const uint8_t*>(check), 9), 0xBB3D);
}

TEST(Noise, HashTableIsRayshadeShuffle) {
    const auto& T = NoiseTables::get().hash;
    // A permutation of 0..4095.
    std::vector<int> sorted(T.begin(), T.end());
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < NoiseTables::kHashSize; ++i) ASSERT_EQ(sorted[i], i);

    // Rayshade's InitTextureTable() written again with the global srand48/drand48.
    std::vector<short> ref(4096);
    srand48(1);
    for (int i = 0; i < 4096; ++i) ref[i] = static_cast<short>(i);
    for (int i = 4095; i > 0; --i) {
        int j = static_cast<int>(drand48() * 4096);
        std::swap(ref[i], ref[j]);
    }
    for (int i = 0; i < 4096; ++i) ASSERT_EQ(T[i], ref[i]) << "i = " << i;

    // Same for the 256-entry permutation (its own srand48(1) stream).
    const auto& P = NoiseTables::get().perm;
    std::vector<int> pref(256);
    srand48(1);
    for (int i = 0; i < 256; ++i) pref[i] = i;
    for (int i = 255; i > 0; --i) std::swap(pref[i], pref[static_cast<int>(drand48() * 256)]);
    for (int i = 0; i < 256; ++i) ASSERT_EQ(P[i], pref[i]) << "i = " << i;
}

TEST(Noise, ValueTableIsCrcOfScaledVector) {
    const auto& R = NoiseTables::get().value;
    for (int i = 0; i < NoiseTables::kValueSize; ++i) {
        struct { double x, y, z; } v{double(i), double(i), double(i)};
        v.x *= .12345;
        v.y *= .12345;
        v.z *= .12345;
        uint8_t bytes[24];
        std::memcpy(bytes, &v, 24);
        const double expect = crcBitwise(bytes, 24) * (2.0 / 65536.0) - 1.0;
        ASSERT_EQ(R[i], expect) << "i = " << i;
        ASSERT_GE(R[i], -1.0);
        ASSERT_LT(R[i], 1.0);
    }
    EXPECT_EQ(R[0], -1.0);  // the zero vector has CRC 0
}

// Rayshade's Noise3 transcribed literally (macros and all), on our tables.
double rayshadeNoise3(double px, double py, double pz) {
    const auto& hashTable = NoiseTables::get().hash;
    const auto& RTable = NoiseTables::get().value;
#define SCURVE(a) ((a) * (a) * (3.0 - 2.0 * (a)))
#define Hash3d(a, b, c) hashTable[hashTable[hashTable[(a)&0xfff] ^ ((b)&0xfff)] ^ ((c)&0xfff)]
#define INCRSUM(m, s, x, y, z) \
    ((s) * (RTable[m] * 0.5 + RTable[m + 1] * (x) + RTable[m + 2] * (y) + RTable[m + 3] * (z)))
    int ix, iy, iz, jx, jy, jz;
    double x, y, z, sx, sy, sz, tx, ty, tz, sum;
    short m;
    x = px - -1000000;
    y = py - -1000000;
    z = pz - -1000000;
    ix = (int)x;
    iy = (int)y;
    iz = (int)z;
    jx = ix + 1;
    jy = iy + 1;
    jz = iz + 1;
    sx = SCURVE(x - ix);
    sy = SCURVE(y - iy);
    sz = SCURVE(z - iz);
    tx = 1.0 - sx;
    ty = 1.0 - sy;
    tz = 1.0 - sz;
    m = Hash3d(ix, iy, iz) & 0xFF;
    sum = INCRSUM(m, (tx * ty * tz), (x - ix), (y - iy), (z - iz));
    m = Hash3d(jx, iy, iz) & 0xFF;
    sum += INCRSUM(m, (sx * ty * tz), (x - jx), (y - iy), (z - iz));
    m = Hash3d(ix, jy, iz) & 0xFF;
    sum += INCRSUM(m, (tx * sy * tz), (x - ix), (y - jy), (z - iz));
    m = Hash3d(jx, jy, iz) & 0xFF;
    sum += INCRSUM(m, (sx * sy * tz), (x - jx), (y - jy), (z - iz));
    m = Hash3d(ix, iy, jz) & 0xFF;
    sum += INCRSUM(m, (tx * ty * sz), (x - ix), (y - iy), (z - jz));
    m = Hash3d(jx, iy, jz) & 0xFF;
    sum += INCRSUM(m, (sx * ty * sz), (x - jx), (y - iy), (z - jz));
    m = Hash3d(ix, jy, jz) & 0xFF;
    sum += INCRSUM(m, (tx * sy * sz), (x - ix), (y - jy), (z - jz));
    m = Hash3d(jx, jy, jz) & 0xFF;
    sum += INCRSUM(m, (sx * sy * sz), (x - jx), (y - jy), (z - jz));
#undef SCURVE
#undef Hash3d
#undef INCRSUM
    return sum;
}

TEST(Noise, DefaultEqualsRayshadeBitForBit) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> near(-20.0, 20.0), far(-9.9e5, 1e8);
    for (int k = 0; k < 20000; ++k) {
        const bool useFar = k % 4 == 3;
        glm::dvec3 p = useFar ? glm::dvec3(far(rng), far(rng), far(rng))
                              : glm::dvec3(near(rng), near(rng), near(rng));
        const double a = noise(p), b = rayshadeNoise3(p.x, p.y, p.z);
        ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << p.x << " " << p.y << " " << p.z;
        glm::dvec3 g;
        const double c = noise(p, {}, &g);  // asking for the gradient changes nothing
        ASSERT_EQ(std::memcmp(&a, &c, sizeof a), 0);
    }
}

TEST(Noise, LatticePointsAreHalfValue) {
    const auto& T = NoiseTables::get().hash;
    const auto& P = NoiseTables::get().perm;
    const auto& R = NoiseTables::get().value;
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> coord(-5000, 5000);
    for (int k = 0; k < 2000; ++k) {
        const int a = coord(rng), b = coord(rng), c = coord(rng);
        const int ia = a + 1000000, ib = b + 1000000, ic = c + 1000000;
        // Independent hashes written here.
        const int m4096 = T[T[T[ia & 0xfff] ^ (ib & 0xfff)] ^ (ic & 0xfff)] & 0xff;
        const int m256 = P[P[P[ia & 0xff] ^ (ib & 0xff)] ^ (ic & 0xff)];
        ASSERT_EQ(noiseHash(ia, ib, ic, NoiseHash::Rayshade), m4096);
        ASSERT_EQ(noiseHash(ia, ib, ic, NoiseHash::Perm256), m256);
        const glm::dvec3 p(a, b, c);
        for (NoiseInterp in : {NoiseInterp::Scurve, NoiseInterp::Linear})
            for (NoiseCorner co : {NoiseCorner::ValueGradient, NoiseCorner::Value}) {
                ASSERT_EQ(noise(p, {in, co, NoiseHash::Rayshade}), 0.5 * R[m4096]);
                ASSERT_EQ(noise(p, {in, co, NoiseHash::Perm256}), 0.5 * R[m256]);
            }
    }
}

TEST(Noise, Bounded) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> d(-300.0, 300.0);
    double lo = 0, hi = 0;
    for (int k = 0; k < 50000; ++k) {
        const glm::dvec3 p(d(rng), d(rng), d(rng));
        const double n = noise(p);
        ASSERT_LE(std::abs(n), 3.5);
        ASSERT_LE(std::abs(noise(p, {NoiseInterp::Linear, NoiseCorner::Value,
                                     NoiseHash::Perm256})),
                  0.5);
        lo = std::min(lo, n);
        hi = std::max(hi, n);
    }
    // DESIGN.md: sampled range about [-1.06, 1.12].
    EXPECT_LT(lo, -0.7);
    EXPECT_GT(hi, 0.7);
    EXPECT_GT(lo, -1.5);
    EXPECT_LT(hi, 1.5);
}

// Random point whose finite-difference stencil (+-h) stays inside one lattice cell:
// integer part plus a fraction in [margin, 1 - margin], some of them within 1e-3 of a plane.
glm::dvec3 pointInCell(std::mt19937_64& rng, double margin) {
    std::uniform_int_distribution<int> cell(-40, 40);
    std::uniform_real_distribution<double> frac(margin, 1.0 - margin), nearPlane(margin, 1e-3);
    std::uniform_int_distribution<int> kind(0, 3);
    glm::dvec3 p;
    for (int k = 0; k < 3; ++k) {
        double fr = frac(rng);
        const int kd = kind(rng);
        if (kd == 1) fr = nearPlane(rng);
        if (kd == 2) fr = 1.0 - nearPlane(rng);
        p[k] = cell(rng) + fr;
    }
    return p;
}

TEST(Noise, GradientMatchesFiniteDifferences) {
    std::mt19937_64 rng(5);
    const double h = 1e-6;
    for (NoiseInterp in : {NoiseInterp::Scurve, NoiseInterp::Linear})
        for (NoiseCorner co : {NoiseCorner::ValueGradient, NoiseCorner::Value})
            for (NoiseHash ha : {NoiseHash::Rayshade, NoiseHash::Perm256}) {
                const NoiseOptions opt{in, co, ha};
                for (int k = 0; k < 10000; ++k) {
                    const glm::dvec3 p = pointInCell(rng, 4 * h);
                    glm::dvec3 g;
                    noise(p, opt, &g);
                    for (int a = 0; a < 3; ++a) {
                        glm::dvec3 pp = p, pm = p;
                        pp[a] += h;
                        pm[a] -= h;
                        // n is a function of x = p + 1e6: divide by the step x actually
                        // took (p +- h rounds to the 2^-33 grid of x).
                        const double step = (pp[a] + 1e6) - (pm[a] + 1e6);
                        const double fd = (noise(pp, opt) - noise(pm, opt)) / step;
                        ASSERT_NEAR(g[a], fd, 1e-5 * std::max(1.0, std::abs(fd)))
                            << toString(in) << " " << toString(co) << " " << toString(ha)
                            << " p = " << p.x << " " << p.y << " " << p.z << " axis " << a;
                    }
                }
            }
}

TEST(Noise, SCurveGradientContinuousAcrossPlanes) {
    // SCURVE noise is C1: the gradient on either side of a lattice plane agrees.
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> d(-50.0, 50.0);
    for (int k = 0; k < 1000; ++k) {
        glm::dvec3 p(std::round(d(rng)), d(rng), d(rng));
        glm::dvec3 ga, gb;
        noise(p + glm::dvec3(1e-9, 0, 0), {}, &ga);
        noise(p - glm::dvec3(1e-9, 0, 0), {}, &gb);
        for (int a = 0; a < 3; ++a) ASSERT_NEAR(ga[a], gb[a], 1e-6);
    }
}

TEST(Noise, OutOfRangeAndNonFinite) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    glm::dvec3 g(7.0);
    EXPECT_EQ(noise(glm::dvec3(nan, 0, 0), {}, &g), 0.0);
    EXPECT_EQ(g, glm::dvec3(0.0));
    EXPECT_EQ(noise(glm::dvec3(0, inf, 0)), 0.0);
    EXPECT_EQ(noise(glm::dvec3(0, 0, -inf)), 0.0);
    // Huge finite inputs: no UB, bounded.
    for (double v : {1e300, -1e300, 3e9, -3e9, 2147483647.0, -1e6 - 0.5})
        EXPECT_LE(std::abs(noise(glm::dvec3(v, 0.25, v))), 3.5) << v;
    // Below -1e6 the noise is the periodic (period 4096) continuation.
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> d(-100.0, 100.0);
    for (int k = 0; k < 200; ++k) {
        const glm::dvec3 p(d(rng), d(rng), d(rng));
        const glm::dvec3 shift(-4096.0 * 300, 4096.0 * 2, 0.0);  // x below -1e6
        glm::dvec3 ga, gb;
        const double a = noise(p, {}, &ga), b = noise(p + shift, {}, &gb);
        ASSERT_NEAR(a, b, 1e-9);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(ga[c], gb[c], 1e-8);
        // Perm256 repeats every 256 cells.
        const NoiseOptions p256{NoiseInterp::Scurve, NoiseCorner::ValueGradient,
                                NoiseHash::Perm256};
        ASSERT_NEAR(noise(p, p256), noise(p + glm::dvec3(256.0, -512.0, 768.0), p256), 1e-9);
    }
}

TEST(Noise, EnumNamesRoundTrip) {
    for (NoiseInterp v : {NoiseInterp::Scurve, NoiseInterp::Linear}) {
        NoiseInterp r;
        ASSERT_TRUE(parseNoiseInterp(toString(v), &r));
        EXPECT_EQ(r, v);
    }
    for (NoiseCorner v : {NoiseCorner::ValueGradient, NoiseCorner::Value}) {
        NoiseCorner r;
        ASSERT_TRUE(parseNoiseCorner(toString(v), &r));
        EXPECT_EQ(r, v);
    }
    for (NoiseHash v : {NoiseHash::Rayshade, NoiseHash::Perm256}) {
        NoiseHash r;
        ASSERT_TRUE(parseNoiseHash(toString(v), &r));
        EXPECT_EQ(r, v);
    }
    EXPECT_STREQ(toString(NoiseInterp::Scurve), "scurve");
    EXPECT_STREQ(toString(NoiseCorner::Value), "value");
    EXPECT_STREQ(toString(NoiseHash::Perm256), "perm256");
    NoiseInterp i;
    NoiseCorner c;
    NoiseHash h;
    EXPECT_FALSE(parseNoiseInterp("cubic", &i));
    EXPECT_FALSE(parseNoiseCorner("", &c));
    EXPECT_FALSE(parseNoiseHash("Rayshade", &h));
}

}  // namespace
}  // namespace pst

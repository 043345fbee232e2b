// Perlin's 2002 improved noise; see perlin2002.h for where the code came from.
#include "perlin2002.h"

#include <climits>
#include <cmath>
#include <cstring>

namespace pst {
namespace {

// ImprovedNoise.java: permutation[].
constexpr std::array<uint8_t, 256> kPermutation = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

// p[]: static { for (int i=0; i < 256 ; i++) p[256+i] = p[i] = permutation[i]; }
struct Doubled {
    int p[512];
    Doubled() {
        for (int i = 0; i < 256; ++i) p[256 + i] = p[i] = kPermutation[i];
    }
};
const Doubled kP;

// Java's (int) of a double: truncation toward zero, saturating at the int range.
int javaInt(double d) {
    if (d >= 2147483647.0) return INT_MAX;
    if (d <= -2147483648.0) return INT_MIN;
    return static_cast<int>(d);
}

double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double dfade(double t) { return 30 * t * t * (t * (t - 2) + 1); }  // 30 t^2 (t - 1)^2
double lerp(double t, double a, double b) { return a + t * (b - a); }
// Java's grad():
//     int h = hash & 15;                      // CONVERT LO 4 BITS OF HASH CODE
//     double u = h<8 ? x : y,                 // INTO 12 GRADIENT DIRECTIONS.
//            v = h<4 ? y : h==12||h==14 ? x : z;
//     return ((h&1) == 0 ? u : -u) + ((h&2) == 0 ? v : -v);
// without its data-dependent branches (random hashes mispredict; this is 3x faster): u and v
// picked by table, -u as a flip of the sign bit, which is what IEEE negation is. Same bits.
constexpr int kU[16] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1};  // h<8 ? x : y
constexpr int kV[16] = {1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2, 0, 2, 0, 2};  // h<4 ? y : h==12||h==14 ? x : z
double flipSign(double a, int flip) {
    uint64_t b;
    std::memcpy(&b, &a, sizeof b);
    b ^= uint64_t(flip) << 63;
    std::memcpy(&a, &b, sizeof b);
    return a;
}
double grad(int hash, double x, double y, double z) {
    const int h = hash & 15;
    const double c[3] = {x, y, z};
    return flipSign(c[kU[h]], h & 1) + flipSign(c[kV[h]], (h >> 1) & 1);
}
// The direction grad() dots with: d grad(hash, x, y, z) / d(x, y, z).
glm::dvec3 gradDirection(int hash) {
    const int h = hash & 15;
    glm::dvec3 g(0.0);
    g[kU[h]] = flipSign(1.0, h & 1);
    g[kV[h]] = flipSign(1.0, (h >> 1) & 1);
    return g;
}

}  // namespace

const std::array<uint8_t, 256>& perlin2002Permutation() { return kPermutation; }

double perlin2002(const glm::dvec3& pos, glm::dvec3* gradOut) {
    if (gradOut) *gradOut = glm::dvec3(0.0);
    double x = pos.x, y = pos.y, z = pos.z;
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return 0.0;
    const int* p = kP.p;
    int X = javaInt(std::floor(x)) & 255,  // FIND UNIT CUBE THAT
        Y = javaInt(std::floor(y)) & 255,  // CONTAINS POINT.
        Z = javaInt(std::floor(z)) & 255;
    x -= std::floor(x);  // FIND RELATIVE X,Y,Z
    y -= std::floor(y);  // OF POINT IN CUBE.
    z -= std::floor(z);
    double u = fade(x),  // COMPUTE FADE CURVES
        v = fade(y),     // FOR EACH OF X,Y,Z.
        w = fade(z);
    int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z,  // HASH COORDINATES OF
        B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;  // THE 8 CUBE CORNERS,

    const double n = lerp(w, lerp(v, lerp(u, grad(p[AA], x, y, z),             // AND ADD
                                          grad(p[BA], x - 1, y, z)),            // BLENDED
                                  lerp(u, grad(p[AB], x, y - 1, z),             // RESULTS
                                       grad(p[BB], x - 1, y - 1, z))),          // FROM  8
                          lerp(v, lerp(u, grad(p[AA + 1], x, y, z - 1),         // CORNERS
                                       grad(p[BA + 1], x - 1, y, z - 1)),       // OF CUBE
                               lerp(u, grad(p[AB + 1], x, y - 1, z - 1),
                                    grad(p[BB + 1], x - 1, y - 1, z - 1))));
    if (gradOut) {
        // n = sum over corners c of W_c(u, v, w) g_c(d_c), W_c the product of the fade weights
        // (u or 1 - u per axis), g_c linear in d_c = (x, y, z) - c with slope G_c, so
        // grad n = sum_c [ (dW_c/dx, dW_c/dy, dW_c/dz) g_c + W_c G_c ].
        const int hashes[8] = {p[AA], p[BA], p[AB], p[BB], p[AA + 1], p[BA + 1], p[AB + 1], p[BB + 1]};
        const double du = dfade(x), dv = dfade(y), dw = dfade(z);
        glm::dvec3 g(0.0);
        for (int c = 0; c < 8; ++c) {
            const int bx = c & 1, by = (c >> 1) & 1, bz = (c >> 2) & 1;
            const double wx = bx ? u : 1 - u, wy = by ? v : 1 - v, wz = bz ? w : 1 - w;
            const double dwx = bx ? du : -du, dwy = by ? dv : -dv, dwz = bz ? dw : -dw;
            const double gc = grad(hashes[c], x - bx, y - by, z - bz);
            g += gc * glm::dvec3(dwx * wy * wz, wx * dwy * wz, wx * wy * dwz) +
                 (wx * wy * wz) * gradDirection(hashes[c]);
        }
        *gradOut = g;
    }
    return n;
}

}  // namespace pst

// Rayshade 4.0 noise.c in double, with its analytic gradient and cheaper variants.
// See noise.h and DESIGN.md section 2 "Noise".
#include "noise.h"

#include "perlin2002.h"
#include "subband.h"
#include "worley.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace pst {

// ---- enum names ---------------------------------------------------------------------------

bool parseNoiseInterp(const std::string& name, NoiseInterp* out) { return contract::fromName(name, out); }

bool parseNoiseCorner(const std::string& name, NoiseCorner* out) { return contract::fromName(name, out); }

bool parseNoiseHash(const std::string& name, NoiseHash* out) { return contract::fromName(name, out); }

bool parseNoiseBasis(const std::string& name, NoiseBasis* out) {
    if (name == "rayshade") *out = NoiseBasis::Rayshade;
    else if (name == "perlin2002") *out = NoiseBasis::Perlin2002;
    else if (name == "worley") *out = NoiseBasis::Worley;
    else if (name == "subband") *out = NoiseBasis::Subband;
    else return false;
    return true;
}

bool parseSubbandParam(const std::string& name, SubbandParam* out) {
    if (name == "xy") *out = SubbandParam::XY;
    else if (name == "xz") *out = SubbandParam::XZ;
    else if (name == "yz") *out = SubbandParam::YZ;
    else if (name == "sphere") *out = SubbandParam::Sphere;
    else return false;
    return true;
}

bool parseSubbandWeights(const std::string& name, SubbandWeights* out) {
    if (name == "heuristic") *out = SubbandWeights::Heuristic;
    else if (name == "least_squares") *out = SubbandWeights::LeastSquares;
    else return false;
    return true;
}

const char* toString(SubbandParam v) {
    switch (v) {
    case SubbandParam::XY: return "xy";
    case SubbandParam::XZ: return "xz";
    case SubbandParam::YZ: return "yz";
    case SubbandParam::Sphere: return "sphere";
    }
    return "?";
}
const char* toString(SubbandWeights v) { return v == SubbandWeights::Heuristic ? "heuristic" : "least_squares"; }

bool parseWorleyMetric(const std::string& name, WorleyMetric* out) {
    if (name == "euclid") *out = WorleyMetric::Euclid;
    else if (name == "manhattan") *out = WorleyMetric::Manhattan;
    else return false;
    return true;
}

const char* toString(NoiseBasis v) {
    switch (v) {
    case NoiseBasis::Rayshade: return "rayshade";
    case NoiseBasis::Perlin2002: return "perlin2002";
    case NoiseBasis::Worley: return "worley";
    case NoiseBasis::Subband: return "subband";
    }
    return "?";
}
const char* toString(WorleyMetric v) { return v == WorleyMetric::Euclid ? "euclid" : "manhattan"; }

bool parseWorleySearch(const std::string& name, WorleySearchKind* out) {
    if (name == "exact") *out = WorleySearchKind::Exact;
    else if (name == "cube27") *out = WorleySearchKind::Cube27;
    else if (name == "octant") *out = WorleySearchKind::Octant;
    else return false;
    return true;
}
bool parseWorleyCubes(const std::string& name, WorleyCubes* out) {
    if (name == "lcg") *out = WorleyCubes::Lcg;
    else if (name == "rom256") *out = WorleyCubes::Rom256;
    else return false;
    return true;
}
const char* toString(WorleySearchKind v) {
    switch (v) {
    case WorleySearchKind::Exact: return "exact";
    case WorleySearchKind::Cube27: return "cube27";
    case WorleySearchKind::Octant: return "octant";
    }
    return "?";
}
const char* toString(WorleyCubes v) { return v == WorleyCubes::Lcg ? "lcg" : "rom256"; }

const char* toString(NoiseInterp v) { return contract::name(v); }
const char* toString(NoiseCorner v) { return contract::name(v); }
const char* toString(NoiseHash v) { return contract::name(v); }

// ---- tables -------------------------------------------------------------------------------

namespace {

// Rayshade's xtab: CRC-16/ARC table of the reflected polynomial 0xA001.
std::array<uint16_t, 256> makeCrcTable() {
    std::array<uint16_t, 256> t{};
    for (int i = 0; i < 256; ++i) {
        unsigned crc = i;
        for (int b = 0; b < 8; ++b) crc = (crc & 1) ? (crc >> 1) ^ 0xA001u : crc >> 1;
        t[i] = static_cast<uint16_t>(crc);
    }
    return t;
}

const std::array<uint16_t, 256>& crcTable() {
    static const std::array<uint16_t, 256> table = makeCrcTable();
    return table;
}

// InitTextureTable(): srand48(1), then for i = n-1 down to 1 swap entry i with entry
// (int)(drand48() * n). erand48 on a private state seeded like srand48(1) does
// (X = 1 << 16 | 0x330E) gives the same stream without touching the global one.
template <typename T, size_t n>
void shuffleLikeRayshade(std::array<T, n>& table) {
    unsigned short xsubi[3] = {0x330E, 1, 0};
    for (size_t i = 0; i < n; ++i) table[i] = static_cast<T>(i);
    for (int i = static_cast<int>(n) - 1; i > 0; --i) {
        int j = static_cast<int>(erand48(xsubi) * static_cast<double>(n));
        std::swap(table[i], table[j]);
    }
}

NoiseTables makeTables() {
    NoiseTables t;
    shuffleLikeRayshade(t.hash);
    shuffleLikeRayshade(t.perm);
    // NoiseInit(): R[i] = Crc16 of the Vector (i, i, i) * .12345, scaled to [-1, 1).
    for (int i = 0; i < NoiseTables::kValueSize; ++i) {
        double v[3] = {static_cast<double>(i), static_cast<double>(i), static_cast<double>(i)};
        for (double& c : v) c *= .12345;
        uint8_t bytes[sizeof v];
        std::memcpy(bytes, v, sizeof v);
        t.value[i] = crc16(bytes, sizeof bytes) * (2.0 / 65536.0) - 1.0;
    }
    return t;
}

}  // namespace

const NoiseTables& NoiseTables::get() {
    static const NoiseTables tables = makeTables();  // magic static: thread-safe init
    return tables;
}

uint16_t crc16(const uint8_t* bytes, size_t count) {
    const auto& xtab = crcTable();
    unsigned crc = 0;
    while (count--) crc = (crc >> 8) ^ xtab[(crc ^ *bytes++) & 0xff];
    return static_cast<uint16_t>(crc);
}

int noiseHash(int ix, int iy, int iz, NoiseHash hash) {
    const NoiseTables& t = NoiseTables::get();
    if (hash == NoiseHash::Perm256) {
        const auto& P = t.perm;
        return P[P[P[ix & 0xff] ^ (iy & 0xff)] ^ (iz & 0xff)];
    }
    if (hash == NoiseHash::Perlin256) {
        // ImprovedNoise.java's p[p[p[X] + Y] + Z] with X = floor(x) & 255 = (ix - 1e6) & 255
        // (1e6 mod 256 = 64); p doubled there is P[i & 255] here.
        const auto& P = perlin2002Permutation();
        const int X = (ix - 64) & 0xff, Y = (iy - 64) & 0xff, Z = (iz - 64) & 0xff;
        return P[(P[(P[X] + Y) & 0xff] + Z) & 0xff];
    }
    // Rayshade: m = Hash3d(ix, iy, iz) & 0xFF.
    const auto& T = t.hash;
    return T[T[T[ix & 0xfff] ^ (iy & 0xfff)] ^ (iz & 0xfff)] & 0xff;
}

// ---- Noise3 -------------------------------------------------------------------------------

double noise(const glm::dvec3& p, const NoiseOptions& opt, glm::dvec3* grad) {
    if (opt.basis == NoiseBasis::Perlin2002) return perlin2002(p, grad);
    if (opt.basis == NoiseBasis::Worley) return worleyBasis(p, opt, grad);
    if (opt.basis == NoiseBasis::Subband) return subbandNoise(p, opt, SubbandFilterKind::None, {}, {}, grad);
    if (opt.interp == NoiseInterp::Quintic || opt.corner == NoiseCorner::Grad12 || opt.hash == NoiseHash::Perlin256)
        throw std::invalid_argument("noise: quintic / grad12 / perlin256 are basis perlin2002's (NoiseBasis::Perlin2002)");
    if (grad) *grad = glm::dvec3(0.0);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return 0.0;
    const NoiseTables& tables = NoiseTables::get();
    const double* R = tables.value.data();

    // Offset so that (int) truncation floors: x = p.x - MINX with MINX = -1000000.
    double x[3] = {p.x - (-NoiseTables::kLatticeOffset), p.y - (-NoiseTables::kLatticeOffset),
                   p.z - (-NoiseTables::kLatticeOffset)};
    int i0[3];
    double s[3], t[3], ds[3];  // s = weight of the upper corner, t = 1 - s, ds = ds/dx
    for (int k = 0; k < 3; ++k) {
        // Outside Rayshade's range: reduce by the hash period 4096 (exact), see noise.h.
        if (!(x[k] >= 0.0 && x[k] < 2147483647.0)) {
            x[k] = std::fmod(x[k], 4096.0);
            if (x[k] < 0.0) x[k] += 4096.0;
        }
        i0[k] = static_cast<int>(x[k]);
        double u = x[k] - i0[k];
        if (opt.interp == NoiseInterp::Scurve) {
            s[k] = u * u * (3.0 - 2.0 * u);  // SCURVE(u)
            ds[k] = 6.0 * u * (1.0 - u);     // SCURVE'(u)
        } else {
            s[k] = u;
            ds[k] = 1.0;
        }
        t[k] = 1.0 - s[k];
    }

    // Sum the 8 corners in Rayshade's order (x fastest), INCRSUM(m, w, dx, dy, dz).
    double sum = 0.0;
    glm::dvec3 g(0.0);
    for (int c = 0; c < 8; ++c) {
        const int b[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
        const int ix = i0[0] + b[0], iy = i0[1] + b[1], iz = i0[2] + b[2];
        const double wx = b[0] ? s[0] : t[0], wy = b[1] ? s[1] : t[1], wz = b[2] ? s[2] : t[2];
        const double w = wx * wy * wz;
        const double dx = x[0] - ix, dy = x[1] - iy, dz = x[2] - iz;
        const int m = noiseHash(ix, iy, iz, opt.hash);
        const double corner = opt.corner == NoiseCorner::ValueGradient
                                  ? R[m] * 0.5 + R[m + 1] * dx + R[m + 2] * dy + R[m + 3] * dz
                                  : R[m] * 0.5;
        const double term = w * corner;
        sum = c == 0 ? term : sum + term;
        if (grad) {
            // d/dp of w * corner: weight derivative (d t = -d s) plus the corner's own slope.
            const double gx = b[0] ? ds[0] : -ds[0], gy = b[1] ? ds[1] : -ds[1],
                         gz = b[2] ? ds[2] : -ds[2];
            g += corner * glm::dvec3(gx * wy * wz, wx * gy * wz, wx * wy * gz);
            if (opt.corner == NoiseCorner::ValueGradient)
                g += w * glm::dvec3(R[m + 1], R[m + 2], R[m + 3]);
        }
    }
    if (grad) *grad = g;
    return sum;
}

}  // namespace pst

// Rayshade noise (Skinner & Kolb, noise.c of Rayshade 4.0) in double precision,
// with its analytic gradient and the cheaper variants the hardware may use.
// Paper: Hart et al. 1999, section 2.1.3; DESIGN.md section 2 "Noise".
// Two later bases share the entry point noise(p, opt, grad) through NoiseOptions::basis:
// Perlin's 2002 improved noise (perlin2002.h) and Worley's 1996 cellular basis (worley.h).
//
// n(p) = sum over the 8 corners c of the lattice cell of p of
//            w_c(p) * (0.5 R[m_c] + R[m_c+1] dx + R[m_c+2] dy + R[m_c+3] dz),
// with d = p - c, m_c the hashed corner index and w_c = product of SCURVE(u) or 1 - SCURVE(u).
//
// Domain: Rayshade adds 1e6 and truncates with (int), so it is only defined for
// p + 1e6 in [0, 2^31 - 1) per coordinate. The hash reads only the low 12 (or 8) bits of
// the lattice index, so n is exactly periodic with period 4096 in each coordinate; outside
// Rayshade's range we reduce the offset coordinate by that period (exact fmod), which is
// the periodic continuation (no UB, and the gradient stays the gradient). Inside the range
// the result is Rayshade's bit for bit. A non-finite coordinate gives n = 0, grad = 0.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "golden/contract.h"

namespace pst {

// The hardware's noise variants are profile keys (rtl/contract.toml noise.interp, noise.corner,
// noise.hash); their enums are generated from it into golden/contract.h, in the contract's order:
//   NoiseInterp  interpolation of the eight lattice corners:
//                Scurve  Rayshade: weights SCURVE(u) = u^2 (3 - 2u)
//                Linear  reduced hardware: tri-linear weights u
//                Quintic Perlin 2002's fade 6u^5 - 15u^4 + 10u^3 (hardware profiles of basis perlin2002)
//   NoiseCorner  what each lattice corner contributes:
//                ValueGradient  Rayshade: 0.5 R[m] + R[m+1] dx + R[m+2] dy + R[m+3] dz
//                Value          0.5 R[m]
//                Grad12         Perlin 2002's grad(m & 15, dx, dy, dz): +-d_u +-d_v, no value table
//   NoiseHash    how a lattice point (ix, iy, iz) becomes the value-table index m:
//                Rayshade   T[T[T[ix&0xfff]^(iy&0xfff)]^(iz&0xfff)] & 0xff, T a 4096-entry permutation
//                Perm256    P[P[P[ix&0xff]^(iy&0xff)]^(iz&0xff)], P a 256-entry permutation (8-bit ROM)
//                Perlin256  Perlin 2002: P[(P[(P[X] + Y) & 255] + Z) & 255], X = floor(x) & 255, his P
// The three values Quintic, Grad12, Perlin256 come together: they are how a hardware profile
// (rtl/contract.toml) says "basis perlin2002", and the reference for them is perlin2002()
// (NoiseBasis::Perlin2002). noise() with basis Rayshade refuses them (std::invalid_argument).
// Why Perm256: each of the three chained lookups per corner is then a 256x8 ROM (2 kbit)
// instead of a 4096x12 ROM (48 kbit); m is the 8-bit permutation output directly. The
// noise then repeats every 256 lattice cells instead of 4096. P is built like Rayshade's
// table: a fresh srand48(1) stream, for i = 255 down to 1 swap P[i], P[(int)(drand48()*256)].

// The basis function n of eq. 1, chosen per texture (every octave uses the same basis).
enum class NoiseBasis {
    Rayshade,    // the paper's: Rayshade's value-gradient noise (interp, corner, hash apply)
    Perlin2002,  // Perlin's improved noise, bit for bit his ImprovedNoise.java (perlin2002.h)
    Worley,      // Worley's cellular basis sum_k C_k F_k + C_cell cell(ID_1) (worley.h)
    Subband,     // Goldberg et al. 2008: oriented subband tiles on a 2-D parameterization (subband.h)
};

// The subband basis's 2-D parameterization of the octave's point p (subband.h subbandNoise).
enum class SubbandParam { XY, XZ, YZ, Sphere };
// Its filter weights: the paper's heuristic or the least-squares fit (eq. 5).
enum class SubbandWeights { Heuristic, LeastSquares };

// The distance of Worley's basis.
enum class WorleyMetric {
    Euclid,     // |d|_2: cells are Voronoi cells, grad F_k the unit vector from point k
    Manhattan,  // |d|_1: "rigidly rectangular" regions (Worley, Fig. 3), grad F_k = sign(d)
};

// Which cubes Worley's basis searches: the paper's exact search (shells of cubes until no
// nearer point can exist), or a hardware unit's fixed neighbourhood: the 27 cubes around the
// home cube, or the 2 x 2 x 2 cubes on the side of the home cube's nearest faces (octant).
enum class WorleySearchKind { Exact, Cube27, Octant };

// Where a cube's feature points come from: the paper's (Worley's 32-bit cube hash, a Poisson
// count and an LCG for the positions), or the hardware's 256-entry feature-point ROM indexed by
// the 256 x 8 permutation hash of the cube (worley.h, worleyRomCube).
enum class WorleyCubes { Lcg, Rom256 };

struct NoiseOptions {
    NoiseInterp interp = NoiseInterp::Scurve;
    NoiseCorner corner = NoiseCorner::ValueGradient;
    NoiseHash hash = NoiseHash::Rayshade;
    NoiseBasis basis = NoiseBasis::Rayshade;
    // Worley only: n = C1 F1 + C2 F2 + C3 F3 + C4 F4 + cell * cell(ID of the nearest point).
    WorleyMetric metric = WorleyMetric::Euclid;
    std::array<double, 4> coef = {1.0, 0.0, 0.0, 0.0};
    double cell = 0.0;
    // Worley only: the search and the feature points (the paper's: Exact, 9, Lcg; a hardware
    // unit's variant: Octant or Cube27, its maximum points per cube, Rom256).
    WorleySearchKind search = WorleySearchKind::Exact;
    int maxPoints = 9;
    WorleyCubes cubes = WorleyCubes::Lcg;
    // Subband only: orientations K (4 or 8), tile size (a power of two), the white noise's
    // seed, the parameterization and the filter weights.
    int orientations = 8;
    int tileSize = 256;
    uint32_t seed = 1;
    SubbandParam param = SubbandParam::XZ;
    SubbandWeights weights = SubbandWeights::Heuristic;
    double sigma = 1.0;  // the filter's Gaussian in screen pixels (eq. 4; the paper's 1)
};

// Parse/print the enum names used in scene files ("scurve", "linear", "value_gradient",
// "value", "rayshade", "perm256"; the hardware's perlin2002 triple "quintic", "grad12",
// "perlin256"). Parsing returns false on an unknown name.
bool parseNoiseInterp(const std::string& name, NoiseInterp* out);
bool parseNoiseCorner(const std::string& name, NoiseCorner* out);
bool parseNoiseHash(const std::string& name, NoiseHash* out);
bool parseNoiseBasis(const std::string& name, NoiseBasis* out);  // rayshade|perlin2002|worley|subband
bool parseSubbandParam(const std::string& name, SubbandParam* out);      // xy | xz | yz | sphere
bool parseSubbandWeights(const std::string& name, SubbandWeights* out);  // heuristic | least_squares
bool parseWorleyMetric(const std::string& name, WorleyMetric* out);  // euclid | manhattan
bool parseWorleySearch(const std::string& name, WorleySearchKind* out);  // exact | cube27 | octant
bool parseWorleyCubes(const std::string& name, WorleyCubes* out);        // lcg | rom256
const char* toString(NoiseInterp v);
const char* toString(NoiseCorner v);
const char* toString(NoiseHash v);
const char* toString(NoiseBasis v);
const char* toString(WorleyMetric v);
const char* toString(WorleySearchKind v);
const char* toString(WorleyCubes v);
const char* toString(SubbandParam v);
const char* toString(SubbandWeights v);

// The tables of Rayshade's NoiseInit(), built once on first use (thread-safe). The
// srand48(1)/drand48() stream is reproduced with erand48 on a private state, so building
// the tables neither reads nor disturbs the global drand48 state.
struct NoiseTables {
    static constexpr int kHashSize = 4096;   // Rayshade's hashTable
    static constexpr int kValueSize = 267;   // Rayshade's RTable (MAXSIZE)
    static constexpr int kPermSize = 256;    // the Perm256 variant
    // Rayshade's lattice offset: Noise3 adds 1e6 so that (int) truncation floors.
    static constexpr double kLatticeOffset = 1000000.0;

    std::array<uint16_t, kHashSize> hash;   // srand48(1) shuffle of 0..4095
    // R[i] = Crc16(0.12345 i x3) * 2/65536 - 1 = k/32768 - 1: exactly a signed 1.15
    // fixed-point number. Where x = p + 1e6 >= 2^19 (a 2^-33 grid), every corner bracket
    // 0.5 R + R dx + ... is exact in double; only the weights and the corner sum round.
    std::array<double, kValueSize> value;
    std::array<uint8_t, kPermSize> perm;    // shuffle of 0..255 (see noise.cpp)

    static const NoiseTables& get();
};

// CRC-16/ARC (reflected polynomial 0xA001, initial 0) as Rayshade's Crc16().
uint16_t crc16(const uint8_t* bytes, size_t count);

// Value-table index m (0..255) of lattice point (ix, iy, iz), where ix is the lattice index
// after Rayshade's offset, i.e. (int)(x + 1e6) = floor(x) + 1000000. Any int is accepted
// (only the low 12 or 8 bits are used). Perlin256 gives the hash ImprovedNoise.java feeds
// grad() (its low 4 bits pick the direction).
int noiseHash(int ix, int iy, int iz, NoiseHash hash);

// n(p) and, if grad != nullptr, its analytic gradient dn/dp (not Rayshade's DNoise3, which is
// not a gradient). With default options this equals Rayshade's Noise3 bit for bit (for
// p > -1e6, see "Domain" above). |n| <= 3.5 always (ValueGradient; 0.5 for Value).
// The gradient is exact inside a cell; on a lattice plane it is the one-sided derivative
// from the cell above (SCURVE noise is C1 there, Linear noise only C0).
// opt.basis Perlin2002 / Worley hand p to perlin2002() / worleyBasis() (their headers);
// Subband to subbandNoise() unfiltered (a point sample).
double noise(const glm::dvec3& p, const NoiseOptions& opt = {}, glm::dvec3* grad = nullptr);

}  // namespace pst

// Worley's cellular texture basis (Worley, "A Cellular Texture Basis Function", SIGGRAPH
// 1996; seed 002) in double precision: F1..F4, the distances to the four nearest feature
// points, their gradients, and the ID of each point.
//
// Feature points, as the paper describes them:
// - space is cut into unit cubes at the integer lattice; cube (i, j, k) gets the 32-bit seed
//   s = 702395077 i + 915488749 j + 2120969693 k (mod 2^32), the hash of Worley's published
//   cellular.c (Texturing & Modeling, 2nd ed.);
// - the seed starts a linear congruential generator s <- 1402024253 s + 586950981 (mod 2^32)
//   (the same code's LCG). Its first value's top byte indexes a 256-entry table of the
//   Poisson distribution of mean kWorleyDensity = 4 ("in practice we use a density of about
//   4"), clamped to 1..9 ("clamp the points in each cell to range between 1 and 9"): the
//   number of points m of the cube;
// - point j < m of the cube has the ID s_cube + j ("the hashed cube ID plus the index of the
//   feature point") and the position (i, j, k) + (X, Y, Z), X = (s + 1/2) / 2^32 for the next
//   three LCG values s.
// F_n(x) is the n-th smallest distance from x to a feature point (Euclidean or Manhattan).
// The search visits the home cube, then shells of cubes by Chebyshev distance, skips every
// cube whose nearest face is already farther than the current F_order, and stops when a whole
// shell is (exact, not a fixed 27-cube neighbourhood). Distances are in cube units: the mean
// F1 is about 0.35 (Euclidean); scale the octave's matrix to change the density.
//
// Domain: the hash repeats every 2^32 cubes along each axis; coordinates beyond +-2^31 are
// reduced by that period (exact fmod), as Rayshade's noise is. A non-finite coordinate gives
// F = 0 and zero gradients.
#pragma once

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "noise.h"

namespace pst {

constexpr double kWorleyDensity = 4.0;  // Poisson mean (feature points per unit cube)
constexpr int kWorleyMinPoints = 1, kWorleyMaxPoints = 9;
constexpr int kWorleyMaxOrder = 4;

// Table entry e = the smallest m with P(Poisson(4) <= m) > (e + 1/2) / 256, clamped to 1..9.
const std::array<uint8_t, 256>& worleyPoissonTable();

// The feature points of cube (i, j, k) (any 64-bit cube index; the hash takes it mod 2^32):
// their count (1..9), positions relative to the cube's corner (in [0, 1)^3) and IDs.
struct WorleyCube {
    int count = 0;
    std::array<glm::dvec3, kWorleyMaxPoints> offset;
    std::array<uint32_t, kWorleyMaxPoints> id;
};
WorleyCube worleyCube(int64_t i, int64_t j, int64_t k);

struct WorleyResult {
    std::array<double, kWorleyMaxOrder> F{};         // F_1 <= F_2 <= ... (order entries)
    std::array<glm::dvec3, kWorleyMaxOrder> grad{};  // grad F_n: (x - p_n)/|x - p_n| (Euclid),
                                                     // sign(x - p_n) (Manhattan); 0 at p_n
    std::array<uint32_t, kWorleyMaxOrder> id{};      // ID of the n-th nearest point
    std::array<glm::dvec3, kWorleyMaxOrder> delta{}; // x - p_n (Worley's "direction vectors")
};

// F_1..F_order (order 1..4) at p.
WorleyResult worley(const glm::dvec3& p, int order, WorleyMetric metric);

// A hardware unit's cheaper search (the "fixed neighbourhood, fixed maximum points per cube"
// of a worley unit): only the cubes within Chebyshev distance `radius` of the home cube
// (radius 1: the 27-cube neighbourhood), and at most `maxPoints` points per cube (the first
// ones of the cube's LCG stream; the Poisson count is clamped to it). radius < 0 and
// maxPoints >= 9 is the exact search above. F_n is then never smaller than the exact F_n;
// where the search misses a point, F_n is too large (or infinite, and the gradient 0, when
// fewer than n points were seen).
// octant: instead, the 2 x 2 x 2 cubes made of the home cube and its neighbours on the side of
// its nearest faces (o_a in {0, fr_a >= 1/2 ? +1 : -1}; Worley's own shortcut for F1, section
// 4 of the paper, turned into a fixed search). cubes: where the points come from (noise.h).
// A fixed search (radius >= 0 or octant) visits its cubes in the hardware's order (x fastest,
// then y, then z; strict comparisons, so ties keep the earlier point), the exact one in shells.
struct WorleySearch {
    int radius = -1;
    int maxPoints = kWorleyMaxPoints;
    bool octant = false;
    WorleyCubes cubes = WorleyCubes::Lcg;
};
WorleyResult worley(const glm::dvec3& p, int order, WorleyMetric metric, const WorleySearch& search);

// The hardware's feature points (WorleyCubes::Rom256, rtl/noise/pst_worley.sv). Cube (i, j, k) is
// hashed like the noise unit's perm256 lattice hash: X = (i + 576) mod 256 (576 = Rayshade's
// 1e6 offset mod 4096, as in the hardware's lattice index), h = P[P[P[X] ^ Y] ^ Z] with P the
// 256 x 8 permutation (NoiseTables::perm). ROM entry h holds the paper's cube (h, 0, 0)
// (worleyCube: Poisson count, LCG positions) with its count clamped to maxPoints and each
// position coordinate cut to its top 8 bits b and put at the centre of that 1/256 bin,
// (2 b + 1) / 512: exact at kWorleyPointFrac fraction bits. So the hardware's texture repeats
// every 256 cubes and has 256 distinct cube contents (Worley's: 2^32 and a fresh LCG stream).
constexpr int kWorleyPointFrac = 9;
int worleyRomIndex(int64_t i, int64_t j, int64_t k);
WorleyCube worleyRomCube(int entry, int maxPoints);
// The ROM's top bytes b of entry's first `maxPoints` points, 3 per point (x, y, z).
std::array<uint8_t, 3 * kWorleyMaxPoints> worleyRomBytes(int entry);

// The options' search as a WorleySearch (Exact, Cube27 = radius 1, Octant).
WorleySearch worleySearchOf(const NoiseOptions& opt);

// A cell's value in [0, 1) from a point's ID (one more LCG step of the ID, over 2^32): what
// `cell` scales in the texture (constant over each cell, e.g. one colour per flagstone).
double worleyCellValue(uint32_t id);

// The basis as a texture sees it: n = sum_k opt.coef[k] F_{k+1} + opt.cell * cell(ID_1), and
// grad n = sum_k opt.coef[k] grad F_{k+1} (the cell term is piecewise constant). The search
// goes to the highest k with a non-zero coefficient. Paper Figure 4's combinations, e.g.
// F1 = {1}, F2 - F1 = {-1, 1}, 2 F3 - F2 - F1 = {-1, -1, 2}, F1 + F2 = {1, 1}.
double worleyBasis(const glm::dvec3& p, const NoiseOptions& opt, glm::dvec3* grad = nullptr);

}  // namespace pst

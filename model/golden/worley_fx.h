// Golden (bit-accurate) model of the worley unit (rtl/noise/pst_worley.sv): Worley's cellular basis
// n = sum_k C_k F_k and its gradient in fixed point, the hardware variant of model/worley.h
// (a fixed cube search, at most noise.worley_points points per cube from a 256-entry
// feature-point ROM, Euclidean distances). Same steps and floors as the RTL; see worley_fx.cpp.
#pragma once

#include <array>
#include <cstdint>

#include "profile.h"

namespace pst {

// Fraction bits of the unit's distance components d = x - p: max(LF, WorleyPointFrac), so that
// both the lattice fraction u and a feature point's position are exact.
int worleyDistFrac(const Profile& prof);
// Cubes the profile's search visits (8 octant, 27 cube27).
int worleySearchCubes(const Profile& prof);

// Feature-point ROM word `entry` (0..255) for at most maxPoints points per cube:
// bits [3:0] the count (1..maxPoints), then point j's x, y, z bytes at 4 + 24 j + 8 a.
// (sim/tools/pst_roms writes the same words as rtl's worley256_pM.memh.)
struct WorleyRomWord {
    int count = 0;
    std::array<uint8_t, 27> b{};  // b[3 j + a]
};
WorleyRomWord worleyRomWord(int entry, int maxPoints);

struct WorleyFxTrace {
    int cubeHash[27] = {};        // ROM entry of each visited cube, in visiting order
    int64_t S[4] = {};            // squared distances of F1.. at 2 DF fraction bits (exact)
    int64_t d[4][3] = {};         // their x - p at DF fraction bits (exact)
    int64_t F[4] = {};            // F_k at NF fraction bits
    int64_t g[4][3] = {};         // grad F_k at NF fraction bits
};

// In: lat (0..4095) and frac (LF bits) per axis, as noiseFx; coef: the four coefficient
// registers (signed WorleyCoefInt.WorleyCoefFrac, sign-extended). Out: n (Q4.OF), grad (3 x
// Q6.OF), as noiseFx's. Requires prof.noise.basis == Worley (throws std::invalid_argument).
void worleyFx(const Profile& prof, const int lat[3], const int64_t frac[3], const int64_t coef[4], int64_t* n,
              int64_t grad[3], WorleyFxTrace* trace = nullptr);

// Honest worst-case bounds of |worleyFx - worleyBasis(p_q)| for the variant's double
// reference at the exact point the unit sees, for coefficients representable in the register
// format (sumAbsCoef = sum |C_k|); no saturation (|n| < 8, |grad| < 32). Derived in
// worley_fx.cpp.
struct WorleyFxErrorBound {
    double F = 0;      // each F_k
    double grad = 0;   // each component of grad F_k
    double value = 0;  // n
    double gradN = 0;  // each component of grad n
};
WorleyFxErrorBound worleyFxErrorBound(const Profile& prof, double sumAbsCoef);

}  // namespace pst

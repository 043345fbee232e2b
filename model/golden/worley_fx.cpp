// Golden model of the worley unit, bit for bit as rtl/noise/pst_worley.sv.
//
// Notation: LF = NoiseLatticeFrac, OF = NoiseOutFrac, NF = OF + noise.guard_bits,
// DF = max(LF, WorleyPointFrac = 9), CF = WorleyCoefFrac = 12, K = noise.worley_order,
// M = noise.worley_points. U_a = the lattice fraction (LF bits), L_a the lattice index.
//
// 1. Cubes, in visiting order c = 0 .. N-1:
//      octant (N = 8):  o_a = bit a of c ? dir_a : 0, dir_a = U_a >= 2^(LF-1) ? +1 : -1
//      cube27 (N = 27): o = (c mod 3 - 1, (c / 3) mod 3 - 1, c / 9 - 1)
//    (the RTL visits ceil(N / NoiseSteps) cubes per step, in the same order).
// 2. Cube hash: X_a = (L_a + o_a) mod 256, h = P[P[P[X_x] ^ X_y] ^ X_z] (the perm256 chain);
//    ROM word h: count m (1..M) and M points' bytes b (worleyRomWord).
// 3. Candidate j < M of the cube (valid if j < m): p_a = o_a 2^DF + (2 b_a + 1) 2^(DF-9),
//    d_a = U_a 2^(DF-LF) - p_a (x - p, exact), S = d_x^2 + d_y^2 + d_z^2 (exact, 2 DF bits).
// 4. The K smallest S (and their d) in a sorted list, initialised to all-ones S (above every
//    S); a valid candidate with S < list[K-1] is inserted before the first entry it is
//    strictly smaller than (ties keep the earlier candidate).
// 5. Per k < K: R = isqrt(S_k 2^(2 NF)) = floor(sqrt(S_k) 2^(DF+NF)); F_k = floor(R / 2^DF)
//    (NF bits, = floor(F 2^NF)); g_k,a = 0 if R = 0, else
//    sign(d_a) min(floor(|d_a| 2^(2 NF) / R), 2^NF) (NF bits).
// 6. n = sat(floor(sum_k C_k F_k / 2^(CF + NF - OF)), Q4.OF),
//    grad_a = sat(floor(sum_k C_k g_k,a / 2^(CF + NF - OF)), Q6.OF).
#include "worley_fx.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contract.h"
#include "fixed.h"
#include "noise.h"
#include "worley.h"

namespace pst {

using fx::floorShift;
using fx::i128;

namespace {

using u128 = unsigned __int128;

// floor(sqrt(x)), bit by bit (the RTL's restoring square root).
u128 isqrt128(u128 x) {
    u128 r = 0;
    for (int b = 63; b >= 0; --b) {
        const u128 t = r | (u128(1) << b);
        if (t * t <= x) r = t;
    }
    return r;
}

}  // namespace

int worleyDistFrac(const Profile& prof) { return std::max(prof.noiseLatticeFrac, int(contract::kWorleyPointFrac)); }

int worleySearchCubes(const Profile& prof) { return prof.noiseWorleySearch == NoiseWorleySearch::Octant ? 8 : 27; }

WorleyRomWord worleyRomWord(int entry, int maxPoints) {
    WorleyRomWord w;
    const WorleyCube c = worleyRomCube(entry, maxPoints);
    const auto b = worleyRomBytes(entry);
    w.count = c.count;
    for (int i = 0; i < 27; ++i) w.b[size_t(i)] = b[size_t(i)];
    return w;
}

void worleyFx(const Profile& prof, const int lat[3], const int64_t frac[3], const int64_t coef[4], int64_t* n,
              int64_t grad[3], WorleyFxTrace* trace) {
    if (prof.noise.basis != NoiseBasis::Worley) throw std::invalid_argument("worleyFx: the profile has no worley unit");
    const int LF = prof.noiseLatticeFrac, OF = prof.noiseOutFrac, NF = OF + prof.noiseGuardBits;
    const int DF = worleyDistFrac(prof), CF = contract::kWorleyCoefFrac, PF = contract::kWorleyPointFrac;
    const int K = prof.noiseWorleyOrder, M = prof.noiseWorleyPoints, N = worleySearchCubes(prof);
    const auto& P = NoiseTables::get().perm;

    int64_t U[3];
    int L[3], dir[3];
    for (int a = 0; a < 3; ++a) {
        U[a] = frac[a] & ((int64_t(1) << LF) - 1);
        L[a] = lat[a] & ((1 << contract::kLatticeBits) - 1);
        dir[a] = (U[a] >> (LF - 1)) & 1 ? 1 : -1;
    }
    const int64_t kNone = (int64_t(1) << (2 * DF + 4)) - 1;  // all-ones S: no point yet
    int64_t S[4], d[4][3];
    for (int k = 0; k < 4; ++k) {
        S[k] = kNone;
        d[k][0] = d[k][1] = d[k][2] = 0;
    }
    for (int c = 0; c < N; ++c) {
        int o[3];
        if (N == 8) {
            for (int a = 0; a < 3; ++a) o[a] = (c >> a) & 1 ? dir[a] : 0;
        } else {
            o[0] = c % 3 - 1;
            o[1] = (c / 3) % 3 - 1;
            o[2] = c / 9 - 1;
        }
        int X[3];
        for (int a = 0; a < 3; ++a) X[a] = (L[a] + o[a]) & 0xff;
        const int h = P[size_t(P[size_t(P[size_t(X[0])] ^ X[1])] ^ X[2])];
        if (trace) trace->cubeHash[c] = h;
        const WorleyRomWord w = worleyRomWord(h, M);
        for (int j = 0; j < M && j < w.count; ++j) {
            int64_t dj[3], s = 0;
            for (int a = 0; a < 3; ++a) {
                const int64_t p = int64_t(o[a]) * (int64_t(1) << DF) + ((2 * int64_t(w.b[size_t(3 * j + a)]) + 1) << (DF - PF));
                dj[a] = (U[a] << (DF - LF)) - p;
                s += dj[a] * dj[a];
            }
            if (!(s < S[K - 1])) continue;
            int at = K - 1;
            while (at > 0 && s < S[at - 1]) {
                S[at] = S[at - 1];
                for (int a = 0; a < 3; ++a) d[at][a] = d[at - 1][a];
                --at;
            }
            S[at] = s;
            for (int a = 0; a < 3; ++a) d[at][a] = dj[a];
        }
    }

    i128 nAcc = 0, gAcc[3] = {0, 0, 0};
    int64_t F[4] = {}, g[4][3] = {};
    for (int k = 0; k < K; ++k) {
        if (S[k] == kNone) throw std::logic_error("worleyFx: fewer than K points (every cube has one)");
        const u128 R = isqrt128(u128(S[k]) << (2 * NF));
        F[k] = int64_t(R >> DF);
        for (int a = 0; a < 3; ++a) {
            if (R == 0) continue;
            const u128 mag = (u128(d[k][a] < 0 ? -d[k][a] : d[k][a]) << (2 * NF)) / R;
            const int64_t q = int64_t(std::min<u128>(mag, u128(1) << NF));
            g[k][a] = d[k][a] < 0 ? -q : q;
        }
        const int64_t C = fx::wrapSigned(coef[k], contract::kWorleyCoefInt + CF);
        nAcc += i128(C) * F[k];
        for (int a = 0; a < 3; ++a) gAcc[a] += i128(C) * g[k][a];
    }
    const int sh = CF + NF - OF;
    *n = fx::satSigned(floorShift(nAcc, sh), contract::kNoiseIntBits + OF);
    for (int a = 0; a < 3; ++a) grad[a] = fx::satSigned(floorShift(gAcc[a], sh), contract::kNoiseGradIntBits + OF);
    if (trace) {
        for (int k = 0; k < 4; ++k) {
            trace->S[k] = S[k];
            trace->F[k] = F[k];
            for (int a = 0; a < 3; ++a) {
                trace->d[k][a] = d[k][a];
                trace->g[k][a] = g[k][a];
            }
        }
    }
}

// Derivation (e = 2^-NF, o = 2^-OF). The distances S and the selection are exact (integers;
// the double reference computes the same dyadic numbers exactly and visits the cubes in the
// same order with the same strict comparison), so only step 5's floors err:
//  - F_k = floor(sqrt(S) 2^NF) 2^-NF: in (F - e, F].
//  - r = sqrt(S) 2^(DF+NF), R = floor(r) in (r - 1, r]; for S > 0, S >= 2^-2DF so r >= 2^NF
//    and R >= 2^NF. |d| 2^(DF+2NF) / R - |d| 2^(DF+2NF) / r = (|d| / F) 2^NF (r - R) / R
//    < 2^NF / R <= 1 (one LSB), then the floor (one more): |g_fx - g| < 2e; the clamp to
//    2^NF only moves toward the true |g| <= 1. S = 0: both are 0.
//  - n: sum_k C_k (F_fx - F) with |.| <= sum |C_k| e, then the floor to OF (o); grad n the
//    same with 2e.
WorleyFxErrorBound worleyFxErrorBound(const Profile& prof, double sumAbsCoef) {
    const int NF = prof.noiseOutFrac + prof.noiseGuardBits;
    const double e = std::ldexp(1.0, -NF), o = std::ldexp(1.0, -prof.noiseOutFrac);
    WorleyFxErrorBound b;
    b.F = e;
    b.grad = 2 * e;
    b.value = sumAbsCoef * e + o;
    b.gradN = sumAbsCoef * 2 * e + o;
    return b;
}

}  // namespace pst

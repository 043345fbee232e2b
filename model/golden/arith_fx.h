// Golden (bit-accurate) model of the arithmetic units of docs/HARDWARE.md:
//   unit 3  quadric          rtl/octave/pst_quadric.sv       quadricFx
//   unit 4  octave term      rtl/octave/pst_octave_term.sv   octaveTermFx
//           accumulation     rtl/octave/pst_octave_accum.sv  accumulateF / accumulateGrad
//   unit 5  filter width     rtl/width/pst_filter_width.sv   filterWidthFx
//           integer sqrt     rtl/common/pst_isqrt.sv         isqrtFx
// Same steps and rounding as the RTL, bit for bit. Every value is a sign-extended integer of
// its format (value = integer / 2^frac); products and sums are exact in fx::i128 (the bit
// budget of each step is written next to it in arith_fx.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "fixed.h"
#include "profile.h"

namespace pst {

// Unit 3. s: 3 x Coord; coef: A..J of eq. 3 (Quadric format).
//   v = (Q [s 1])_xyz exact (QuadricFrac + CoordFrac fraction bits),
//   q = s . v + (D s + G t + I r + J) exact (QuadricFrac + 2 CoordFrac) = eq. 3,
//   *q = sat_F(floor(q to FFrac)),  gradq[k] = sat_Grad(floor(2 v_k to GradFrac)).
void quadricFx(const Profile& p, const int64_t s[3], const int64_t coef[10], int64_t* q, int64_t gradq[3]);

// Unit 4, one octave. n: Q4.NoiseOutFrac; g: 3 x Q6.NoiseOutFrac; a: Amplitude;
// gm: 9 x GradMatrix, row-major GM = a M^T (gm[3 r + c]).
//   *fterm = sat_F(floor(a n to FFrac)),  gterm[r] = sat_Grad(floor(sum_c gm[3r+c] g[c] to GradFrac)).
void octaveTermFx(const Profile& p, int64_t n, const int64_t g[3], int64_t a, const int64_t gm[9],
                  int64_t* fterm, int64_t gterm[3]);

// Unit 4, the accumulation (done by the integrator, pst_top): the exact sum of q and the
// active octaves' terms (wide enough for 16 terms), saturated once at the end.
//   accumulateF    = sat_F(q + sum terms)
//   accumulateGrad = sat_Grad(gradq_k + sum terms_k), one component.
// Unit 4, bandlimited octaves (filter.bandlimit = isotropic; rtl/octave/pst_fade_lg.sv and
// rtl/octave/pst_octave_fade.sv). Per pixel, one Jacobian column e (3 x Jacobian):
//   v_k = |e_k|, mx = max v_k, r = sum v_k - mx, L = mx + floor(r / 4) + floor(r / 8)  (max + 3/8 (mid + min))
//   fadeLgFx = lg L with FadeLgFrac fraction bits by Mitchell's approximation: 2^FadeLgFrac
//   (P - JacobianFrac) + the FadeLgFrac bits below L's leading one (bit P); L = 0 counts as L = 1.
int64_t fadeLgFx(const Profile& p, const int64_t e[3]);
// Its second half: lg L of a length L (JacobianFrac fraction bits; 0 counts as 1) by Mitchell's
// approximation, FadeLgFrac fraction bits (rtl/octave/pst_fade_lg.sv).
int64_t mitchellLgFx(const Profile& p, uint64_t len);
// Per octave: lg nu_x = lgx + lgm (lgm = lg ||M||_2, the octave's register), idx_x = clamp(floor((lg nu_x
//   + FadeLgLo) 4), 0, FadeEntries - 1) (a quarter octave per entry), likewise y;
//   alpha = min(floor(table[idx_x] table[idx_y] / 2^FadeFrac), 2^FadeFrac)  (FadeFrac fraction bits).
int64_t octaveFadeFx(int64_t lgx, int64_t lgy, int64_t lgm, const int64_t table[contract::kFadeEntries]);
// The octave term faded toward its mean fm (the octave's register, a mean(n) in the F format):
// sat_F(floor((fterm - fm) alpha / 2^FadeFrac) + fm) (rtl/octave/pst_octave_term.sv). alpha = 1.0
// gives fterm; fm = 0 gives fadeScaleFx(fterm, alpha).
int64_t fadeToMeanFx(const Profile& p, int64_t fterm, int64_t fm, int64_t alpha);
// The faded term: floor(v alpha / 2^FadeFrac) (|result| <= |v|: no saturation).
int64_t fadeScaleFx(int64_t v, int64_t alpha);

int64_t accumulateF(const Profile& p, int64_t q, const std::vector<int64_t>& terms);
int64_t accumulateGrad(const Profile& p, int64_t gradq, const std::vector<int64_t>& terms);

// Unit 5. grad: 3 x Grad; j: 6 x Jacobian (ds/dx, dt/dx, dr/dx, ds/dy, dt/dy, dr/dy).
//   gx = grad . dsdx, gy = grad . dsdy exact (GradFrac + JacobianFrac),
//   Wx = floor(gx N to WidthFrac) (N = 2^Log2Clut: a shift), Wy likewise,
//   ax = min(|Wx|, WMax), ay = min(|Wy|, WMax)   (WMax = 2^WW - 1, WW = contract::w_width(Log2Clut, WidthFrac):
//        every norm is >= max(ax, ay), so this clamp never changes the saturated result and
//        keeps the square root's input at 2 WW + 1 bits),
//   norm by p.filterNorm: Euclid isqrt(ax^2 + ay^2); MaxHalfMin max + floor(min / 2); L1 ax + ay,
//   W = min(norm, WMax): unsigned, contract::w_int_bits(Log2Clut) integer bits, WidthFrac fraction bits.
int64_t filterWidthFx(const Profile& p, const int64_t grad[3], const int64_t j[6]);

// The width cap (filter.width_cap profiles, rtl/width/pst_width_stage.sv): min(w, wcap), wcap the
// register's low contract::w_width bits (unsigned, W's format; all ones: no cap).
int64_t widthCapFx(const Profile& p, int64_t w, int64_t wcap);

// floor(sqrt(x)) by the digit-by-digit (restoring) method of rtl/common/pst_isqrt.sv, two input bits
// per step from the top. x < 2^126.
uint64_t isqrtFx(unsigned __int128 x);

// Shared step: floor(v / 2^sh) (sh < 0: exact v * 2^-sh), saturated to a signed `bits`-bit
// number: what the RTL does with a wide exact value and its format.
int64_t shiftSatSigned(fx::i128 v, int sh, int bits);

// Serial datapath step counts (cycles a fragment spends in the unit; the RTL's, checked by
// sim/unit/arith_unit_test): contract::quadric_serial_steps (rtl/octave/pst_quadric_serial.sv
// NSteps) and contract::width_serial_steps (rtl/width/pst_filter_width.sv NSteps) of the profile.
int quadricSerialSteps(const Profile& p);
int filterWidthSerialSteps(const Profile& p);

}  // namespace pst

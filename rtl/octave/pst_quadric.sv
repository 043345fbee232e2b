// Quadric (unit 3 of docs/HARDWARE.md): q(s) of eq. 3 and its gradient 2 (Q [s 1])_xyz
// (eq. 11 with the linear terms D, G, I kept). Combinational when Regs = 0; Regs = 1, 2 put
// pipeline registers (pst_delay, enabled by en_i) after v and the linear term, then after
// the three products s_k v_k, so q_o and gradq_o come Regs advances after s_i. Golden model: quadricFx in
// model/golden/arith_fx.cpp (same steps, bit for bit).
//
//   Q = [A B C D; B E F G; C F H I; D G I J]   (eq. 4, coef_i = A..J)
//   v = (Q [s 1])_xyz            exact, QuadricFrac + CoordFrac fraction bits
//   w = v + ((D, G, I) << CoordFrac)   exact: the linear terms folded into v, so that
//   q = s . w + (J << 2 CoordFrac)
//     = s . v + ((D s + G t + I r) << CoordFrac) + (J << 2 CoordFrac)
//                                exact, QuadricFrac + 2 CoordFrac fraction bits (= eq. 3):
//                                three products s_k w_k, no separate D s + G t + I r
//                                (the same integer; three QW x CW products fewer)
//   q_o     = sat_F(floor(q to FFrac))
//   gradq_o = sat_Grad(floor(2 v to GradFrac)), per component
// floor = arithmetic shift right (a left shift, exact, if the target has more fraction bits);
// sat = clamp to the signed output width.
//
// Parameters:
//   CoordInt, CoordFrac       s_i format (signed, Int bits include the sign): the multiplier
//                             widths and the exact-value fraction bits.
//   QuadricInt, QuadricFrac   coefficient format of coef_i.
//   FInt, FFrac               q_o format (the colour index f): where q is floored and clamped.
//   GradInt, GradFrac         gradq_o component format.
//   Regs                      pipeline registers (0..2, above; pst_octave_stage sets them).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_quadric #(
  `PST_QUADRIC_PARAMS,
  parameter int Regs        = 0,
  // Derived widths (not profile keys).
  localparam int CW = CoordInt + CoordFrac,       // one texture coordinate
  localparam int QW = QuadricInt + QuadricFrac,   // one coefficient
  localparam int FW = FInt + FFrac,               // q_o
  localparam int GW = GradInt + GradFrac          // one gradq_o component
) (
  input  logic             clk_i,    // pipeline registers (Regs > 0)
  input  logic             rst_ni,
  input  logic             en_i,
  input  logic [3*CW-1:0]  s_i,      // s, t, r; element k at [k*CW +: CW]
  input  logic [10*QW-1:0] coef_i,   // A..J; element k at [k*QW +: QW]
  output logic [FW-1:0]    q_o,
  output logic [3*GW-1:0]  gradq_o   // element k at [k*GW +: GW]
);

  // v: three products of at most 2^(QW+CW-2) each plus D << CoordFrac (at most 2^(QW+CW-2)
  // as CoordInt >= 1): |v| <= 2^(QW+CW) -> QW + CW + 1 bits signed.
  localparam int VW  = QW + CW + 1;
  // w = v + D << CoordFrac: |w| <= 1.25 2^(QW+CW) -> VW + 1 bits signed.
  localparam int WW  = VW + 1;
  // q: s . w < 3 * 2^(CW-1) * 1.25 2^(QW+CW) and J << 2 CoordFrac < 2^(QW+2CW-3):
  // |q| < 2^(QW+2CW+1).
  localparam int QXW = QW + 2 * CW + 3;

  // The coefficients A..J of eq. 3 and the coordinates s, t, r as signed values.
  logic signed [QW-1:0] ca, cb, cc, cd, ce, cf, cg, ch, ci, cj;
  logic signed [CW-1:0] s0, s1, s2;
  assign {cj, ci, ch, cg, cf, ce, cd, cc, cb, ca} = coef_i;
  assign {s2, s1, s0} = s_i;

  // Step 1: v = (Q [s 1])_xyz at QuadricFrac + CoordFrac; rows of Q: (A B C D), (B E F G),
  // (C F H I).
  logic signed [VW-1:0] v0_d, v1_d, v2_d, v0, v1, v2, v0_q, v1_q, v2_q;
  assign v0_d = VW'(ca) * VW'(s0) + VW'(cb) * VW'(s1) + VW'(cc) * VW'(s2) + (VW'(cd) <<< CoordFrac);
  assign v1_d = VW'(cb) * VW'(s0) + VW'(ce) * VW'(s1) + VW'(cf) * VW'(s2) + (VW'(cg) <<< CoordFrac);
  assign v2_d = VW'(cc) * VW'(s0) + VW'(cf) * VW'(s1) + VW'(ch) * VW'(s2) + (VW'(ci) <<< CoordFrac);

  logic signed [QXW-1:0] qx;

  // Register 1: v, s, J and the linear coefficients D, G, I.
  logic signed [CW-1:0] s0_r, s1_r, s2_r;
  logic signed [QW-1:0] cj_r, cj_q, cd_r, cg_r, ci_r;
  pst_delay #(.Width(3*VW + 3*CW + 4*QW), .Depth(Regs > 0 ? 1 : 0)) u_reg1 (
    .clk_i, .rst_ni, .en_i, .d_i ({v2_d, v1_d, v0_d, s2, s1, s0, cj, ci, cg, cd}),
    .q_o ({v2, v1, v0, s2_r, s1_r, s0_r, cj_r, ci_r, cg_r, cd_r})
  );

  // Step 2: w = v + (D, G, I) << CoordFrac; register 2: the three products s_k w_k (and what
  // the sum and the gradient still need).
  logic signed [WW-1:0] w0, w1, w2;
  assign w0 = WW'(v0) + (WW'(cd_r) <<< CoordFrac);
  assign w1 = WW'(v1) + (WW'(cg_r) <<< CoordFrac);
  assign w2 = WW'(v2) + (WW'(ci_r) <<< CoordFrac);
  logic signed [QXW-1:0] p0_d, p1_d, p2_d, p0, p1, p2;
  assign p0_d = QXW'(s0_r) * QXW'(w0);
  assign p1_d = QXW'(s1_r) * QXW'(w1);
  assign p2_d = QXW'(s2_r) * QXW'(w2);
  pst_delay #(.Width(3*QXW + QW + 3*VW), .Depth(Regs > 1 ? 1 : 0)) u_reg2 (
    .clk_i, .rst_ni, .en_i, .d_i ({p2_d, p1_d, p0_d, cj_r, v2, v1, v0}),
    .q_o ({p2, p1, p0, cj_q, v2_q, v1_q, v0_q})
  );
  // Step 3: q = s . w + J << 2 CoordFrac.
  assign qx = p0 + p1 + p2 + (QXW'(cj_q) <<< (2 * CoordFrac));

  // q_o and gradq_o: q and 2 v floored and saturated to their formats.
  pst_quadric_out #(`PST_QUADRIC_PASS) u_out (
    .q_i (qx), .v_i ({v2_q, v1_q, v0_q}), .q_o, .gradq_o
  );

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (CoordInt >= 1 && QuadricInt >= 1 && FInt >= 1 && GradInt >= 1)
      else $error("pst_quadric: every format needs its sign bit (Int >= 1)");
    assert (Regs >= 0 && Regs <= 2) else $error("pst_quadric: Regs must be 0..2");
  end
`endif

endmodule

`default_nettype wire

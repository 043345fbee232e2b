// Quadric folded over a fragment's two beats (unit 3 of docs/HARDWARE.md): q(s) of eq. 3 and
// its gradient 2 (Q [s 1])_xyz as pst_quadric, bit for bit, from two row units instead of
// three, for a parallel datapath that holds each fragment for two or more cycles (Passes x
// NoiseSteps >= 2: full's four noise units over two passes). Golden model: quadricFx in
// model/golden/arith_fx.cpp (the same integers; the fold changes no arithmetic).
//
// A row unit computes, for one row r of Q = [A B C D; B E F G; C F H I; D G I J] (eq. 4):
//   v_r = (Q [s 1])_r          exact, QuadricFrac + CoordFrac fraction bits (pst_quadric)
//   p_r = s_r (v_r + Q_r3 << CoordFrac)     exact, the linear term folded in (pst_quadric)
// Beat schedule (s_i and coef_i are held for the fragment's beats; first_i marks the beat
// before its last, the caller reads q with the last):
//   first_i beat   unit 0: row 0 (A B C D, s), unit 1: row 1 (B E F G, t)
//   next beat      unit 0: row 2 (C F H I, r)                 (unit 1's result unused)
// The first_i beat's p_0, p_1, v_0, v_1 are held (a register enabled when that beat leaves
// the units' Regs pipeline registers, as en_i advances them); when the next beat leaves them
//   q_o     = sat_F(floor((p_0 + p_1 + p_2 + J << 2 CoordFrac) to FFrac))
//   gradq_o = sat_Grad(floor(2 v_r to GradFrac)), per component
// are the fragment's (pst_quadric's values); other beats' outputs are not used.
// Area: 6 + 2 products instead of 9 + 3, for a 4 x QW + CW input multiplexer and the hold
// (2 QXW + 2 VW flip-flops).
//
// Parameters: as pst_quadric (formats; Regs 0..2 pipeline registers after v and after the
// products).
`include "pst_pkg.sv"
`default_nettype none

module pst_quadric_fold #(
  parameter int CoordInt    = pst_pkg::CoordIntDefault,
  parameter int CoordFrac   = pst_pkg::CoordFracDefault,
  parameter int QuadricInt  = pst_pkg::QuadricIntDefault,
  parameter int QuadricFrac = pst_pkg::QuadricFracDefault,
  parameter int FInt        = pst_pkg::FIntDefault,
  parameter int FFrac       = pst_pkg::FFracDefault,
  parameter int GradInt     = pst_pkg::GradIntDefault,
  parameter int GradFrac    = pst_pkg::GradFracDefault,
  parameter int Regs        = 0,
  // Derived widths (not profile keys).
  localparam int CW = CoordInt + CoordFrac,       // one texture coordinate
  localparam int QW = QuadricInt + QuadricFrac,   // one coefficient
  localparam int FW = FInt + FFrac,               // q_o
  localparam int GW = GradInt + GradFrac          // one gradq_o component
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             en_i,     // the pipeline advances (every register, the hold too)
  input  logic             first_i,  // this beat computes rows 0 and 1 (else row 2)
  input  logic [3*CW-1:0]  s_i,      // s, t, r; element k at [k*CW +: CW]
  input  logic [10*QW-1:0] coef_i,   // A..J; element k at [k*QW +: QW]
  output logic [FW-1:0]    q_o,
  output logic [3*GW-1:0]  gradq_o   // element k at [k*GW +: GW]
);

  // Widths as pst_quadric: v QW + CW + 1 bits, w = v + Q_r3 << CoordFrac one more, q QW + 2 CW + 3.
  localparam int VW  = QW + CW + 1;
  localparam int WW  = VW + 1;
  localparam int QXW = QW + 2 * CW + 3;

  logic signed [QW-1:0] ca, cb, cc, cd, ce, cf, cg, ch, ci, cj;
  logic signed [CW-1:0] s0, s1, s2;
  assign {cj, ci, ch, cg, cf, ce, cd, cc, cb, ca} = coef_i;
  assign {s2, s1, s0} = s_i;

  // The rows each unit takes this beat: unit 0 row 0 or row 2, unit 1 row 1.
  logic signed [QW-1:0] r0_a, r0_b, r0_c, r0_d;
  logic signed [CW-1:0] r0_s;
  assign {r0_a, r0_b, r0_c, r0_d} = first_i ? {ca, cb, cc, cd} : {cc, cf, ch, ci};
  assign r0_s = first_i ? s0 : s2;

  // Step 1: v_u = (row) . [s 1] at QuadricFrac + CoordFrac.
  logic signed [VW-1:0] v0_d, v1_d, v0, v1;
  assign v0_d = VW'(r0_a) * VW'(s0) + VW'(r0_b) * VW'(s1) + VW'(r0_c) * VW'(s2) + (VW'(r0_d) <<< CoordFrac);
  assign v1_d = VW'(cb) * VW'(s0) + VW'(ce) * VW'(s1) + VW'(cf) * VW'(s2) + (VW'(cg) <<< CoordFrac);

  // Register 1: v, the rows' own coordinates and linear coefficients, J, the beat's flag.
  logic signed [CW-1:0] r0_s_r, s1_r;
  logic signed [QW-1:0] r0_d_r, cg_r, cj_r, cj_q;
  logic                 first_r, first_q;
  pst_delay #(.Width(2*VW + 2*CW + 3*QW + 1), .Depth(Regs > 0 ? 1 : 0)) u_reg1 (
    .clk_i, .rst_ni, .en_i, .d_i ({v1_d, v0_d, s1, r0_s, cj, cg, r0_d, first_i}),
    .q_o ({v1, v0, s1_r, r0_s_r, cj_r, cg_r, r0_d_r, first_r})
  );

  // Step 2: p_u = s_r (v_u + Q_r3 << CoordFrac); register 2.
  logic signed [WW-1:0] w0, w1;
  assign w0 = WW'(v0) + (WW'(r0_d_r) <<< CoordFrac);
  assign w1 = WW'(v1) + (WW'(cg_r) <<< CoordFrac);
  logic signed [QXW-1:0] p0_d, p1_d, p0, p1;
  assign p0_d = QXW'(r0_s_r) * QXW'(w0);
  assign p1_d = QXW'(s1_r) * QXW'(w1);
  logic signed [VW-1:0] v0_q, v1_q;
  pst_delay #(.Width(2*QXW + QW + 2*VW + 1), .Depth(Regs > 1 ? 1 : 0)) u_reg2 (
    .clk_i, .rst_ni, .en_i, .d_i ({p1_d, p0_d, cj_r, v1, v0, first_r}),
    .q_o ({p1, p0, cj_q, v1_q, v0_q, first_q})
  );

  // The first beat's rows 0 and 1, held until the next beat leaves the registers.
  logic signed [QXW-1:0] hp0_q, hp1_q;
  logic signed [VW-1:0]  hv0_q, hv1_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      {hp0_q, hp1_q, hv0_q, hv1_q} <= '0;
    end else if (en_i && first_q) begin
      {hp0_q, hp1_q, hv0_q, hv1_q} <= {p0, p1, v0_q, v1_q};
    end
  end

  // Step 3: q = p_0 + p_1 + p_2 + J << 2 CoordFrac (this beat's unit 0 holds row 2).
  logic signed [QXW-1:0] qx;
  assign qx = hp0_q + hp1_q + p0 + (QXW'(cj_q) <<< (2 * CoordFrac));
  pst_floor_sat #(
    .InWidth (QXW), .InFrac (QuadricFrac + 2 * CoordFrac), .OutWidth (FW), .OutFrac (FFrac)
  ) u_q_sat (
    .x_i (qx), .y_o (q_o)
  );

  // grad q = 2 v (exact), floor to GradFrac, saturate to GW bits.
  logic [3*VW-1:0] v;
  assign v = {v0_q, hv1_q, hv0_q};
  for (genvar r = 0; r < 3; r++) begin : g_grad
    pst_floor_sat #(
      .InWidth (VW + 1), .InFrac (QuadricFrac + CoordFrac), .OutWidth (GW), .OutFrac (GradFrac)
    ) u_grad_sat (
      .x_i ({v[r*VW +: VW], 1'b0}), .y_o (gradq_o[r*GW +: GW])
    );
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (CoordInt >= 1 && QuadricInt >= 1 && FInt >= 1 && GradInt >= 1)
      else $error("pst_quadric_fold: every format needs its sign bit (Int >= 1)");
    assert (Regs >= 0 && Regs <= 2) else $error("pst_quadric_fold: Regs must be 0..2");
  end
`endif

endmodule

`default_nettype wire

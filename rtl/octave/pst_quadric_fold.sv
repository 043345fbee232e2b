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
// (2 QXW + 2 VW flip-flops). Register 1 holds w_u (v_u with the linear term added once more,
// in step 1's sum of products), so step 2's path is the product alone.
//
// Parameters: as pst_quadric (formats; Regs 0..2 pipeline registers after v and after the
// products); SelReg 1: unit 0's row registered a clock ahead from first_next_i (a fragment of
// three or more beats: the first of them is never used, so the register is always loaded
// from the coefficients that the used beats see).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_quadric_fold #(
  `PST_QUADRIC_PARAMS,
  parameter int Regs        = 0,
  parameter bit SelReg      = 1'b0,
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
  input  logic             first_next_i,   // SelReg: first_i of the next clock's beat
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
  logic [3*CW-1:0]      s_p;   // s for step 1's products (SelReg: a registered copy)
  if (SelReg) begin : g_sel_reg
    // Selected a cycle ahead from first_next_i and registered every clock: the products start
    // at a register, not at the multiplexer (the caller's promise: the coefficients do not
    // change in the cycle before a beat that is used; pst_octave_parallel with three or more
    // beats, register writes only while idle).
    // s is registered beside them (a copy of s_i, which holds one fragment over its beats):
    // the products' s then comes from a register of their own, not through s_i's fanout.
    logic [4*QW-1:0] row_q;
    logic [3*CW-1:0] s_q;
    always_ff @(posedge clk_i) begin
      row_q <= first_next_i ? {ca, cb, cc, cd} : {cc, cf, ch, ci};
      s_q   <= s_i;
    end
    assign {r0_a, r0_b, r0_c, r0_d} = row_q;
    assign s_p = s_q;
    logic unused_rst_sel;
    assign unused_rst_sel = rst_ni;
  end else begin : g_sel
    assign {r0_a, r0_b, r0_c, r0_d} = first_i ? {ca, cb, cc, cd} : {cc, cf, ch, ci};
    assign s_p = s_i;
    logic unused_first_next;
    assign unused_first_next = first_next_i;
  end
  assign r0_s = first_i ? s0 : s2;

  // Step 1: w_u = v_u + Q_r3 << CoordFrac = (row) . [s 1] + Q_r3 << CoordFrac, one sum of
  // products (the linear coefficient twice: w = a s + b t + c r + 2 d << CoordFrac), so that
  // step 2 starts at its product; v_u = w_u - Q_r3 << CoordFrac is taken back after it (off
  // the product's path).
  // Radix-4 Booth products (rtl/common/pst_mul_booth.sv, the coefficient recoded: 13 rows
  // instead of Yosys' 32-row AND array; step 1 is the fold's longest path), modulo 2^WW.
  logic signed [WW-1:0] w0_d, w1_d, w0, w1;
  logic [6*WW-1:0] pr;   // unit u, column c at [(3u + c)*WW +: WW]
  for (genvar c = 0; c < 3; c++) begin : g_col
    pst_mul_booth #(.AW(CW), .BW(QW), .BSigned(1'b1), .PW(WW)) u_m0 (
      .a_i (s_p[c*CW +: CW]), .b_i (c == 0 ? r0_a : c == 1 ? r0_b : r0_c), .p_o (pr[c*WW +: WW]));
    pst_mul_booth #(.AW(CW), .BW(QW), .BSigned(1'b1), .PW(WW)) u_m1 (
      .a_i (s_p[c*CW +: CW]), .b_i (c == 0 ? cb : c == 1 ? ce : cf), .p_o (pr[(3+c)*WW +: WW]));
  end
  assign w0_d = pr[0*WW +: WW] + pr[1*WW +: WW] + pr[2*WW +: WW] + (WW'(r0_d) <<< (CoordFrac + 1));
  assign w1_d = pr[3*WW +: WW] + pr[4*WW +: WW] + pr[5*WW +: WW] + (WW'(cg) <<< (CoordFrac + 1));

  // Register 1: w, the rows' own coordinates and linear coefficients, J, the beat's flag.
  logic signed [CW-1:0] r0_s_r, s1_r;
  logic signed [QW-1:0] r0_d_r, cg_r, cj_r, cj_q;
  logic                 first_r, first_q;
  pst_delay #(.Width(2*WW + 2*CW + 3*QW + 1), .Depth(Regs > 0 ? 1 : 0)) u_reg1 (
    .clk_i, .rst_ni, .en_i, .d_i ({w1_d, w0_d, s1, r0_s, cj, cg, r0_d, first_i}),
    .q_o ({w1, w0, s1_r, r0_s_r, cj_r, cg_r, r0_d_r, first_r})
  );

  // Step 2: p_u = s_r w_u; v_u = w_u - Q_r3 << CoordFrac (exact, VW bits); register 2.
  logic signed [VW-1:0] v0, v1;
  logic signed [WW-1:0] v0_w, v1_w;
  assign v0_w = w0 - (WW'(r0_d_r) <<< CoordFrac);
  assign v1_w = w1 - (WW'(cg_r) <<< CoordFrac);
  assign v0 = v0_w[VW-1:0];
  assign v1 = v1_w[VW-1:0];
  logic unused_v_top;   // |v| < 2^(VW-1): the top bit is a sign copy
  assign unused_v_top = ^{v0_w[WW-1], v1_w[WW-1]};
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
  // q_o and gradq_o: q and 2 v floored and saturated to their formats (as pst_quadric).
  pst_quadric_out #(`PST_QUADRIC_PASS) u_out (
    .q_i (qx), .v_i ({v0_q, hv1_q, hv0_q}), .q_o, .gradq_o
  );

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

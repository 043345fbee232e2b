// Quadric, one row of Q per cycle (stage 3 of docs/HARDWARE.md, datapath = "serial"): the
// same q(s) of eq. 3 and gradient 2 (Q [s 1])_xyz as pst_quadric, bit for bit, from three
// coefficient x coordinate multipliers and one coordinate x row multiplier instead of fifteen.
// Golden model: quadricFx in model/golden/arith_fx.cpp (the sum is exact, so the order of its
// terms does not change a bit).
//
//   Row r = row_i (0, 1, 2) of Q = [A B C D; B E F G; C F H I; D G I J] (eq. 4):
//   v_r = Q_r0 s + Q_r1 t + Q_r2 r + (Q_r3 << CoordFrac)   exact, QuadricFrac + CoordFrac bits
//   u_r = v_r + (Q_r3 << CoordFrac)                        (the linear term D s + G t + I r of
//                                                           eq. 3 folded into the row: s_r Q_r3)
//   q   = sum_r s_r u_r + (J << 2 CoordFrac)               = s . v + ((D s + G t + I r) << CoordFrac)
//                                                           + (J << 2 CoordFrac), exact
//   q_o     = sat_F(floor(q to FFrac))                     valid from row 2 on
//   gradq_o = sat_Grad(floor(2 v_r to GradFrac)), per row  valid from row 2 on
//
// Timing: the caller holds s_i and coef_i and steps row_i through 0, 1, 2 (then any value
// >= 3 to hold the result), raising adv_i on each cycle whose row it leaves: adv_i stores the
// row's partial sum s_r u_r and its gradient component. At row 2 the outputs are combinational
// (the stored rows plus row 2); from row 3 on they come from the registers alone.
//
// Parameters: as pst_quadric (CoordInt/Frac, QuadricInt/Frac: multiplier widths; FInt/Frac,
// GradInt/Frac: output formats).
`default_nettype none

module pst_quadric_serial #(
  parameter int CoordInt    = 12,
  parameter int CoordFrac   = 20,
  parameter int QuadricInt  = 8,
  parameter int QuadricFrac = 16,
  parameter int FInt        = 12,
  parameter int FFrac       = 20,
  parameter int GradInt     = 16,
  parameter int GradFrac    = 16,
  // Derived widths (not profile keys).
  localparam int CW = CoordInt + CoordFrac,       // one texture coordinate
  localparam int QW = QuadricInt + QuadricFrac,   // one coefficient
  localparam int FW = FInt + FFrac,               // q_o
  localparam int GW = GradInt + GradFrac          // one gradq_o component
) (
  input  wire logic              clk_i,
  input  wire logic              rst_ni,
  input  wire logic [1:0]        row_i,    // 0..2: the row this cycle; 3: hold
  input  wire logic              adv_i,    // store this row's partials (leaving the row)
  input  wire logic [3*CW-1:0]   s_i,      // s, t, r; element k at [k*CW +: CW]
  input  wire logic [10*QW-1:0]  coef_i,   // A..J; element k at [k*QW +: QW]
  output logic [FW-1:0]          q_o,
  output logic [3*GW-1:0]        gradq_o   // element k at [k*GW +: GW]
);

  // v_r: as pst_quadric, QW + CW + 1 bits; u_r = v_r + Q_r3 << CoordFrac: one bit more.
  localparam int VW  = QW + CW + 1;
  localparam int UW  = VW + 1;
  // q: |s_r u_r| < 2^(CW-1) 2^(QW+CW+1), three of them plus J << 2 CoordFrac: as pst_quadric,
  // QW + 2 CW + 3 bits.
  localparam int QXW = QW + 2 * CW + 3;
  localparam int QSh  = QuadricFrac + 2 * CoordFrac - FFrac;
  localparam int GSh  = QuadricFrac + CoordFrac - GradFrac;
  localparam int QShR = (QSh > 0) ? QSh : 0;
  localparam int QShL = (QSh < 0) ? -QSh : 0;
  localparam int GShR = (GSh > 0) ? GSh : 0;
  localparam int GShL = (GSh < 0) ? -GSh : 0;
  localparam int QSW = (QXW + QShL > FW) ? QXW + QShL : FW + 1;
  localparam int GSW = (VW + 1 + GShL > GW) ? VW + 1 + GShL : GW + 1;

  logic signed [QW-1:0] ca, cb, cc, cd, ce, cf, cg, ch, ci, cj;
  logic signed [CW-1:0] s0, s1, s2;
  assign {cj, ci, ch, cg, cf, ce, cd, cc, cb, ca} = coef_i;
  assign {s2, s1, s0} = s_i;

  // Step 1: the row's coefficients and coordinate (row 3 selects row 0's; unused then).
  logic signed [QW-1:0] k0, k1, k2, k3;
  logic signed [CW-1:0] sr;
  always_comb begin
    unique case (row_i)
      2'd1:    begin k0 = cb; k1 = ce; k2 = cf; k3 = cg; sr = s1; end
      2'd2:    begin k0 = cc; k1 = cf; k2 = ch; k3 = ci; sr = s2; end
      default: begin k0 = ca; k1 = cb; k2 = cc; k3 = cd; sr = s0; end
    endcase
  end

  // Step 2: v_r, u_r and the partial s_r u_r (exact).
  logic signed [VW-1:0]  v;
  logic signed [UW-1:0]  u;
  logic signed [QXW-1:0] su;
  assign v  = VW'(k0) * VW'(s0) + VW'(k1) * VW'(s1) + VW'(k2) * VW'(s2) + (VW'(k3) <<< CoordFrac);
  assign u  = UW'(v) + (UW'(k3) <<< CoordFrac);
  assign su = QXW'(sr) * QXW'(u);

  // Step 3: grad q_r = 2 v_r, floor to GradFrac, saturate to GW bits.
  logic signed [GSW-1:0] gs;
  logic [GW-1:0]         grow;
  assign gs = ((GSW'(v) <<< 1) <<< GShL) >>> GShR;
  always_comb begin
    if (gs[GSW-1:GW-1] == '0 || gs[GSW-1:GW-1] == '1) grow = gs[GW-1:0];
    else grow = {gs[GSW-1], {(GW-1){~gs[GSW-1]}}};
  end

  // Partial-sum and gradient registers.
  logic signed [QXW-1:0] acc_q, acc_d;
  logic [3*GW-1:0]       grad_q, grad_d;
  logic                  live;   // row_i is 0..2: its partial counts
  assign live = (row_i != 2'd3);

  logic signed [QXW-1:0] sum;    // sum of the rows so far, this row included
  assign sum = ((row_i == 2'd0) ? '0 : acc_q) + (live ? su : '0);

  always_comb begin
    acc_d  = acc_q;
    grad_d = grad_q;
    if (adv_i && live) begin
      acc_d = sum;
      grad_d[row_i*GW +: GW] = grow;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      acc_q  <= '0;
      grad_q <= '0;
    end else begin
      acc_q  <= acc_d;
      grad_q <= grad_d;
    end
  end

  // Step 4: q = sum + (J << 2 CoordFrac), floor to FFrac, saturate to FW bits.
  logic signed [QXW-1:0] qx;
  logic signed [QSW-1:0] qs;
  assign qx = sum + (QXW'(cj) <<< (2 * CoordFrac));
  assign qs = (QSW'(qx) <<< QShL) >>> QShR;
  always_comb begin
    if (qs[QSW-1:FW-1] == '0 || qs[QSW-1:FW-1] == '1) q_o = qs[FW-1:0];
    else q_o = {qs[QSW-1], {(FW-1){~qs[QSW-1]}}};
  end

  // The gradient: row 2's component live at row 2, the stored ones otherwise.
  always_comb begin
    gradq_o = grad_q;
    if (row_i == 2'd2) gradq_o[2*GW +: GW] = grow;
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (CoordInt >= 1 && QuadricInt >= 1 && FInt >= 1 && GradInt >= 1)
      else $error("pst_quadric_serial: every format needs its sign bit (Int >= 1)");
  end
  // Rows are taken in order: rows 0 and 1 are left only to the next one (after row 2 the
  // result is complete, and the next fragment may start at row 0).
  logic [1:0] row_prev_q;
  logic       adv_prev_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      row_prev_q <= 2'd3;
      adv_prev_q <= 1'b0;
    end else begin
      row_prev_q <= row_i;
      adv_prev_q <= adv_i;
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni && adv_prev_q && row_prev_q < 2'd2) begin
      assert (row_i == row_prev_q + 2'd1) else $error("pst_quadric_serial: row %0d left to row %0d", row_prev_q, row_i);
    end
  end
`endif

endmodule

`default_nettype wire

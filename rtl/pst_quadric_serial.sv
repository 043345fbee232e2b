// Quadric, one product per cycle (stage 3 of docs/HARDWARE.md, datapath = "serial"): the
// same q(s) of eq. 3 and gradient 2 (Q [s 1])_xyz as pst_quadric, bit for bit, from one
// coefficient x coordinate multiplier and one coordinate x row multiplier instead of fifteen
// multipliers. Golden model: quadricFx in model/golden/arith_fx.cpp (every sum is exact, so
// the order of its terms does not change a bit).
//
//   Step k = 3 r + c (k = step_i = 0..8), row r of Q = [A B C D; B E F G; C F H I; D G I J]
//   (eq. 4), column c:
//   v_r = Q_r0 s + Q_r1 t + Q_r2 r + (Q_r3 << CoordFrac)   one product Q_rc s_c per step, exact
//                                                           at QuadricFrac + CoordFrac bits
//   u_r = v_r + (Q_r3 << CoordFrac)                        (at c = 2; the linear term
//                                                           D s + G t + I r of eq. 3 folded into
//                                                           the row: s_r Q_r3)
//   q   = sum_r s_r u_r + (J << 2 CoordFrac)               = s . v + ((D s + G t + I r) << CoordFrac)
//                                                           + (J << 2 CoordFrac), exact
//   q_o     = sat_F(floor(q to FFrac))                     valid from step 8 on
//   gradq_o = sat_Grad(floor(2 v_r to GradFrac)), per row  valid from step 8 on
//
// Timing: the caller holds s_i and coef_i and steps step_i through 0..8 (then any value >= 9
// to hold the result), raising adv_i on each cycle whose step it leaves: adv_i stores the
// partial sums (and, at c = 2, the row's s_r u_r and gradient component). At step 8 the
// outputs are combinational; from step 9 on they come from the registers alone.
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
  input  wire logic [3:0]        step_i,   // 0..8: product 3 r + c this cycle; >= 9: hold
  input  wire logic              adv_i,    // store this step's partial sums (leaving the step)
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

  // Step 1: this step's row r, column c, coefficient Q_rc, coordinate s_c, and the row's
  // constant Q_r3 and coordinate s_r.
  logic                 live;    // step_i is 0..8
  logic [1:0]           r, c;
  logic signed [QW-1:0] krc, k3;
  logic signed [CW-1:0] sc, sr;
  assign live = (step_i < 4'd9);
  always_comb begin
    r = 2'd0;
    c = 2'd0;
    if (live) begin
      r = 2'(step_i / 4'd3);
      c = 2'(step_i % 4'd3);
    end
    unique case ({r, c})
      4'b0000: krc = ca;  4'b0001: krc = cb;  4'b0010: krc = cc;
      4'b0100: krc = cb;  4'b0101: krc = ce;  4'b0110: krc = cf;
      4'b1000: krc = cc;  4'b1001: krc = cf;  4'b1010: krc = ch;
      default: krc = ca;
    endcase
    unique case (r)
      2'd1:    begin k3 = cg; sr = s1; end
      2'd2:    begin k3 = ci; sr = s2; end
      default: begin k3 = cd; sr = s0; end
    endcase
    unique case (c)
      2'd1:    sc = s1;
      2'd2:    sc = s2;
      default: sc = s0;
    endcase
  end

  // Step 2: the partial v_r, and at c = 2 u_r and s_r u_r (exact).
  logic signed [VW-1:0]  vacc_q, vsum, v;
  logic signed [UW-1:0]  u;
  logic signed [QXW-1:0] su;
  assign vsum = ((c == 2'd0) ? '0 : vacc_q) + VW'(krc) * VW'(sc);
  assign v    = vsum + (VW'(k3) <<< CoordFrac);
  assign u    = UW'(v) + (UW'(k3) <<< CoordFrac);
  assign su   = QXW'(sr) * QXW'(u);

  // Step 3: grad q_r = 2 v_r, floor to GradFrac, saturate to GW bits.
  logic signed [GSW-1:0] gs;
  logic [GW-1:0]         grow;
  assign gs = ((GSW'(v) <<< 1) <<< GShL) >>> GShR;
  always_comb begin
    if (gs[GSW-1:GW-1] == '0 || gs[GSW-1:GW-1] == '1) grow = gs[GW-1:0];
    else grow = {gs[GSW-1], {(GW-1){~gs[GSW-1]}}};
  end

  // Partial-sum and gradient registers.
  logic                  row_end;   // c = 2: v_r is complete
  logic signed [QXW-1:0] acc_q, sum;
  logic [3*GW-1:0]       grad_q;
  assign row_end = live && (c == 2'd2);
  assign sum     = ((step_i == 4'd0) ? '0 : acc_q) + (row_end ? su : '0);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      vacc_q <= '0;
      acc_q  <= '0;
      grad_q <= '0;
    end else if (adv_i && live) begin
      vacc_q <= vsum;
      acc_q  <= sum;
      if (row_end) grad_q[r*GW +: GW] <= grow;
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

  // The gradient: row 2's component live at step 8, the stored ones otherwise.
  always_comb begin
    gradq_o = grad_q;
    if (step_i == 4'd8) gradq_o[2*GW +: GW] = grow;
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (CoordInt >= 1 && QuadricInt >= 1 && FInt >= 1 && GradInt >= 1)
      else $error("pst_quadric_serial: every format needs its sign bit (Int >= 1)");
  end
  // Steps are taken in order: steps 0..7 are left only to the next one (after step 8 the
  // result is complete, and the next fragment may start at step 0).
  logic [3:0] step_prev_q;
  logic       adv_prev_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      step_prev_q <= 4'd9;
      adv_prev_q  <= 1'b0;
    end else begin
      step_prev_q <= step_i;
      adv_prev_q  <= adv_i;
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni && adv_prev_q && step_prev_q < 4'd8) begin
      assert (step_i == step_prev_q + 4'd1)
        else $error("pst_quadric_serial: step %0d left to step %0d", step_prev_q, step_i);
    end
  end
`endif

endmodule

`default_nettype wire

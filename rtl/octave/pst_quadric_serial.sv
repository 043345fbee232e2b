// Quadric on one multiplier (unit 3 of docs/HARDWARE.md, datapath = "serial"): the same
// q(s) of eq. 3 and gradient 2 (Q [s 1])_xyz as pst_quadric, bit for bit, from one CW x QW
// multiplier used over NSteps cycles instead of fifteen multipliers. Golden model: quadricFx
// in model/golden/arith_fx.cpp (every sum is exact, so the order of its terms and the split of
// a product into partial products do not change a bit).
//
//   Row r of Q = [A B C D; B E F G; C F H I; D G I J] (eq. 4) takes RS = 3 + NChunks steps
//   (step_i = k = RS r + e):
//   e = 0, 1, 2:  v_r += Q_re s_e                        exact at QuadricFrac + CoordFrac bits;
//                 at e = 2: v_r = sum + (Q_r3 << CoordFrac), grad row r = sat_Grad(floor(2 v_r)),
//                 u_r = v_r + (Q_r3 << CoordFrac) held (the linear term D s + G t + I r of
//                 eq. 3 folded into the row: s_r Q_r3)
//   e = 3 + j:    q += (s_r chunk_j(u_r)) << (j L)       u_r = sum_j chunk_j 2^(j L): NChunks chunks of
//                 L = QW - 1 bits, the low ones unsigned, the top one signed, so that every
//                 chunk is a QW-bit signed multiplier operand like a coefficient
//   q_o = sat_F(floor(q + (J << 2 CoordFrac) to FFrac))  = s . v + ((D s + G t + I r) << CoordFrac)
//                                                          + (J << 2 CoordFrac) of eq. 3
//   NSteps = 3 RS; q_o and gradq_o are valid from the last step (done_o) on.
//
// Timing: the caller holds s_i and coef_i and steps step_i through 0, 1, ... (values from
// NSteps on hold the result), raising adv_i on each cycle whose step it leaves. At the last
// step q_o is combinational; after it, it comes from the registers alone. step_next_i is the
// step of the next cycle (what step_i will be after this clock edge): its row, position and
// first-step flag are decoded one cycle ahead and registered, so the step decode is not on
// the multiplier's path (step -> row / position -> operand mux -> multiplier).
//
// Regs = 1 (pst_octave_stage sets it with the term register): the product is registered and
// accumulated one step later, so the multiplier and the sums are separate paths. A row then
// takes RS = 4 + NChunks steps (step e = 3 waits for u_r, the chunks follow at e = 4 + j) and
// NSteps = 3 RS + 1 (the last product's sum).
//
// Parameters: as pst_quadric (CoordInt/Frac, QuadricInt/Frac: multiplier widths and the step
// count; FInt/Frac, GradInt/Frac: output formats).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_quadric_serial #(
  `PST_QUADRIC_PARAMS,
  parameter int Regs        = 0,
  // Derived widths (not profile keys).
  localparam int CW = CoordInt + CoordFrac,       // one texture coordinate
  localparam int QW = QuadricInt + QuadricFrac,   // one coefficient
  localparam int FW = FInt + FFrac,               // q_o
  localparam int GW = GradInt + GradFrac          // one gradq_o component
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic [4:0]        step_i,   // 0..NSteps-1: this cycle's product; >= NSteps: hold
  input  logic [4:0]        step_next_i,   // the next cycle's step_i
  input  logic              adv_i,    // store this step's partial sums (leaving the step)
  output logic                   done_o,   // q_o and gradq_o are valid (step_i >= NSteps - 1)
  input  logic [3*CW-1:0]   s_i,      // s, t, r; element k at [k*CW +: CW]
  input  logic [10*QW-1:0]  coef_i,   // A..J; element k at [k*QW +: QW]
  output logic [FW-1:0]          q_o,
  output logic [3*GW-1:0]        gradq_o   // element k at [k*GW +: GW]
);

  // v_r: as pst_quadric, QW + CW + 1 bits; u_r = v_r + Q_r3 << CoordFrac: one bit more.
  localparam int VW  = QW + CW + 1;
  localparam int UW  = VW + 1;
  // q: |s_r u_r| < 2^(CW-1) 2^(QW+CW+1), three of them plus J << 2 CoordFrac: as pst_quadric,
  // QW + 2 CW + 3 bits.
  localparam int QXW = QW + 2 * CW + 3;
  // u_r in NChunks chunks of L bits (the top one signed, TopW <= L bits), RS steps a row.
  localparam int L      = QW - 1;
  localparam int NChunks = pst_pkg::quadric_chunks(QW, CW);   // = (UW + L - 1) / L
  localparam int RS     = 3 + Regs + NChunks;   // steps a row (the chunks from e = 3 + Regs)
  localparam int NSteps = pst_pkg::quadric_serial_steps(QW, CW, Regs);   // = 3 RS + Regs
  localparam int TopW   = UW - (NChunks - 1) * L;
  localparam int PW     = CW + QW;   // the product, exact

  logic signed [QW-1:0] ca, cb, cc, cd, ce, cf, cg, ch, ci, cj;
  logic signed [CW-1:0] s0, s1, s2;
  assign {cj, ci, ch, cg, cf, ce, cd, cc, cb, ca} = coef_i;
  assign {s2, s1, s0} = s_i;

  // Step 1: this step's row r and position e, and the multiplier's operands.
  logic                 live;    // step_i < NSteps (a product step)
  logic [1:0]           r;
  logic [4:0]           e;
  logic signed [CW-1:0] sr;      // s_r
  logic signed [CW-1:0] ma;      // multiplier operand: s_e or s_r
  logic signed [QW-1:0] mb;      // multiplier operand: Q_re or chunk_j(u_r)
  logic signed [UW-1:0] u_q;     // u_r, held for the chunk steps
  logic                 first;   // step_i == 0
  // The decode of a step: {live, r, e, first}.
  function automatic logic [8:0] decode(input logic [4:0] k);
    logic [1:0] dr;
    logic [4:0] de;
    dr = 2'd0;
    de = 5'd0;
    if (32'(k) < 3 * RS) begin
      dr = 2'(32'(k) / RS);
      de = 5'(32'(k) % RS);
    end
    decode = {32'(k) < 3 * RS, dr, de, k == 5'd0};
  endfunction
  logic [8:0] dec_q;   // decode(step_i), registered from the previous cycle's step_next_i
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) dec_q <= decode(5'd0);
    else         dec_q <= decode(step_next_i);
  end
  assign {live, r, e, first} = dec_q;
  always_comb begin
    unique case (r)
      2'd1:    sr = s1;
      2'd2:    sr = s2;
      default: sr = s0;
    endcase
    ma = sr;
    mb = '0;
    if (e < 5'd3) begin
      unique case (e[1:0])
        2'd1:    ma = s1;
        2'd2:    ma = s2;
        default: ma = s0;
      endcase
      unique case ({r, e[1:0]})
        4'b0000: mb = ca;  4'b0001: mb = cb;  4'b0010: mb = cc;
        4'b0100: mb = cb;  4'b0101: mb = ce;  4'b0110: mb = cf;
        4'b1000: mb = cc;  4'b1001: mb = cf;  4'b1010: mb = ch;
        default: mb = ca;
      endcase
    end else begin
      for (int j = 0; j < NChunks; j++) begin
        if (32'(e) == 3 + Regs + j) begin
          if (j < NChunks - 1) mb = QW'({1'b0, u_q[j*L +: L]});          // unsigned low chunk
          else mb = QW'($signed(u_q[UW-1 -: TopW]));                // signed top chunk
        end
      end
    end
  end

  logic signed [PW-1:0] prod_d, prod;
  assign prod_d = PW'(ma) * PW'(mb);

  // Regs = 1: the product and its step's control wait a step (the sums below use the _a
  // values: the step whose product they add).
  logic [1:0]           r_a;
  logic [4:0]           e_a;
  logic                 live_a, first_a;
  pst_delay #(.Width(PW + 2 + 5 + 2), .Depth(Regs), .Reset(1'b1)) u_prod (
    .clk_i, .rst_ni, .en_i (adv_i), .d_i ({prod_d, r, e, live, first}),
    .q_o ({prod, r_a, e_a, live_a, first_a})
  );
  logic signed [QW-1:0] k3_a;   // Q_r3 of the adding step's row
  always_comb begin
    unique case (r_a)
      2'd1:    k3_a = cg;
      2'd2:    k3_a = ci;
      default: k3_a = cd;
    endcase
  end

  // Step 2: the partial v_r; at e = 2 v_r, u_r and grad row r.
  logic signed [VW-1:0]  vacc_q, vsum, v;
  logic signed [UW-1:0]  u;
  assign vsum = ((e_a == 5'd0) ? '0 : vacc_q) + VW'(prod);
  assign v    = vsum + (VW'(k3_a) <<< CoordFrac);
  assign u    = UW'(v) + (UW'(k3_a) <<< CoordFrac);

  // Step 3: grad q_r = 2 v_r (v_r << 1, exact), floor to GradFrac, saturate to GW bits.
  logic [GW-1:0] grow;
  pst_floor_sat #(
    .InWidth (VW + 1), .InFrac (QuadricFrac + CoordFrac), .OutWidth (GW), .OutFrac (GradFrac)
  ) u_grad_sat (
    .x_i ({v, 1'b0}), .y_o (grow)
  );

  // The chunk partial product s_r chunk_j << j L, added to the q sum.
  logic signed [QXW-1:0] part, acc_q, sum;
  always_comb begin
    part = '0;
    for (int j = 0; j < NChunks; j++) begin
      if (live_a && 32'(e_a) == 3 + Regs + j) part = QXW'(prod) <<< (j * L);
    end
  end
  assign sum = (first_a ? '0 : acc_q) + part;

  logic [3*GW-1:0] grad_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      vacc_q <= '0;
      u_q    <= '0;
      acc_q  <= '0;
      grad_q <= '0;
    end else if (adv_i && live_a) begin
      if (e_a < 5'd3) vacc_q <= vsum;
      acc_q  <= sum;
      if (e_a == 5'd2) begin
        u_q <= u;
        grad_q[r_a*GW +: GW] <= grow;
      end
    end
  end

  assign done_o = (32'(step_i) >= NSteps - 1);

  // Step 4: q = sum + (J << 2 CoordFrac), floor to FFrac, saturate to FW bits.
  logic signed [QXW-1:0] qx;
  assign qx = sum + (QXW'(cj) <<< (2 * CoordFrac));
  pst_floor_sat #(
    .InWidth (QXW), .InFrac (QuadricFrac + 2 * CoordFrac), .OutWidth (FW), .OutFrac (FFrac)
  ) u_q_sat (
    .x_i (qx), .y_o (q_o)
  );

  // Every row's gradient is stored by the last step (row 2's at step 2 RS + 2).
  assign gradq_o = grad_q;

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (CoordInt >= 1 && QuadricInt >= 1 && FInt >= 1 && GradInt >= 1)
      else $error("pst_quadric_serial: every format needs its sign bit (Int >= 1)");
  end
  // Steps are taken in order: a step before the last is left only to the next one (after
  // the last the result is complete, and the next fragment may start at step 0).
  logic [4:0] step_prev_q;
  logic       adv_prev_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      step_prev_q <= 5'(NSteps);
      adv_prev_q  <= 1'b0;
    end else begin
      step_prev_q <= step_i;
      adv_prev_q  <= adv_i;
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni && adv_prev_q && 32'(step_prev_q) < NSteps - 1) begin
      assert (step_i == step_prev_q + 5'd1)
        else $error("pst_quadric_serial: step %0d left to step %0d", step_prev_q, step_i);
    end
  end
  // The registered decode is this cycle's step's (the caller's step_next_i was right) on
  // every cycle whose step is used.
  always_ff @(posedge clk_i) begin
    if (rst_ni && adv_i) begin
      assert (dec_q == decode(step_i))
        else $error("pst_quadric_serial: step %0d decoded as another (step_next_i was wrong)", step_i);
    end
  end
  initial begin
    assert (NSteps <= 31) else $error("pst_quadric_serial: %0d steps do not fit step_i", NSteps);
    assert (QW >= 2) else $error("pst_quadric_serial: QuadricInt + QuadricFrac must be >= 2");
  end
`endif

endmodule

`default_nettype wire

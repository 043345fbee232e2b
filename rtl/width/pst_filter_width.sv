// Filter width (unit 5 of docs/HARDWARE.md): W = |grad_x f| N in colour-table entries
// (section 3.2: grad_x f = (grad_s f)^T ds/dx). Golden model: filterWidthFx in
// model/golden/arith_fx.cpp (same steps, bit for bit). Combinational when Serial = 0; with
// Serial = 1 the six products take one multiplier over six cycles (step_i = 3 d + k: direction
// d, component k), and w_o is valid at step 5 (the sums are exact, so the result is the same
// bit for bit). For the euclidean norm the serial unit goes on: step 6 ax^2, step 7 + ay^2 (one
// WW x WW squarer), then the square root two digits per cycle (steps 8 .. 7 + NSq, the same
// restoring digit recurrence as pst_isqrt from the top pair down: floor(sqrt) either way);
// done_o marks the last step.
//
//   gx = grad . dsdx, gy = grad . dsdy        exact, GradFrac + JacobianFrac fraction bits
//   Wx = floor(gx N to WidthFrac)             N = 2^Log2Clut: part of the shift; Wy likewise
//   ax = min(|Wx|, WMax), ay = min(|Wy|, WMax)    WMax = 2^WW - 1 (the W format's maximum).
//        Every norm below is >= max(ax, ay), so a clamped operand already means W = WMax:
//        the clamp never changes the result, and it keeps the square root's input at
//        2 WW + 1 bits however large gx is.
//   norm (FilterNorm): 0 euclid        floor(sqrt(ax^2 + ay^2))  (pst_isqrt of the exact sum)
//                      1 max_half_min  max(ax, ay) + floor(min(ax, ay) / 2)
//                      2 l1            ax + ay
//   w_o = min(norm, WMax): unsigned, Log2Clut + 2 integer bits, WidthFrac fraction bits.
//
// Parameters:
//   GradInt, GradFrac           grad_i component format (grad_s f).
//   JacobianInt, JacobianFrac   j_i entry format (ds/dx, ds/dy).
//   Log2Clut                    N = 2^Log2Clut entries: the scale to entries and W's range.
//   WidthFrac                   fraction bits of W.
//   FilterNorm                  which norm is built (pst_pkg::FilterNormEuclid, ...MaxHalfMin,
//                               ...L1).
//   Serial                      0: all six products at once; 1: one product per cycle
//                               (the profile's datapath = "serial").
//   Regs                        pipeline registers (Serial = 0 only; the profile's
//                               pipeline.width_regs): the first after the dot products gx, gy,
//                               the second after ax^2 + ay^2 (other norms: after the norm), the
//                               rest inside pst_isqrt (other norms: after the second); from 6
//                               on, the first between the six products and their sums and one
//                               more after the clamp (ax, ay), so 6 leaves 3 in the root; w_o
//                               comes Regs advances (en_i) after grad_i, j_i.
// Steps (Serial): pst_pkg::WidthProducts products, then for the euclidean norm
// pst_pkg::WidthEuclidSquares squares and NSq root cycles; NSteps in all (16 in reduced).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_filter_width #(
  `PST_FILTER_WIDTH_PARAMS,
  parameter bit Serial       = 1'b0,
  parameter int Regs         = 0,
  // Derived widths (not profile keys).
  localparam int GW = GradInt + GradFrac,           // one grad_i component
  localparam int JW = JacobianInt + JacobianFrac,   // one j_i entry
  localparam int WW = pst_pkg::w_width(Log2Clut, WidthFrac)     // W = w N in entries, < 4N
) (
  input  logic            clk_i,    // Serial only: partial-sum registers
  input  logic            rst_ni,
  input  logic [pst_pkg::StepBits-1:0] step_i,   // Serial only: product 3 d + k (0..5), then the norm's steps
  input  logic            adv_i,    // Serial only: store this step's partial sums
  input  logic            en_i,     // Regs > 0: the pipeline advances
  output logic            done_o,   // Serial only: w_o is valid (the last step; always 1 if not Serial)
  input  logic [3*GW-1:0] grad_i,   // element k at [k*GW +: GW]
  input  logic [6*JW-1:0] j_i,      // ds/dx, dt/dx, dr/dx, ds/dy, dt/dy, dr/dy
  output logic [WW-1:0]   w_o
);

  // gx: three GW x JW products, |sum| <= 3 * 2^(GW+JW-2) < 2^(GW+JW): GW + JW + 1 bits, plus
  // one so that negating the most negative value cannot overflow.
  localparam int XW   = GW + JW + 2;
  // Shift from GradFrac + JacobianFrac fraction bits to W's WidthFrac, times N (negative =
  // left shift).
  localparam int Sh   = GradFrac + JacobianFrac - Log2Clut - WidthFrac;
  localparam int ShR  = (Sh > 0) ? Sh : 0;
  localparam int ShL  = (Sh < 0) ? -Sh : 0;
  // Shifted width: room for the left shift and at least one bit above W for the clamp.
  localparam int SW   = (XW + ShL > WW) ? XW + ShL : WW + 1;
  localparam int SqW  = 2 * WW + 1;   // ax^2 + ay^2 <= 2 (2^WW - 1)^2 < 2^(2 WW + 1)
  // Serial euclid: root digits ceil(SqW / 2) = WW + 1, two per cycle over NSq cycles.
  localparam int NSq  = pst_pkg::width_root_steps(WW);   // = (WW + 2) / 2
  localparam bit Euclid = (FilterNorm == pst_pkg::FilterNormEuclid);
  // Serial steps: products 0 .. SqStep - 1, squares SqStep, SqStep + 1, root from RootStep.
  localparam int SqStep   = pst_pkg::WidthProducts;
  localparam int RootStep = SqStep + pst_pkg::WidthEuclidSquares;
  localparam int NSteps   = (!Serial) ? 1 : pst_pkg::width_serial_steps(FilterNorm, Log2Clut, WidthFrac);
  localparam int LastStep = NSteps - 1;
  localparam int SB = pst_pkg::StepBits;
  // Pipeline registers (parallel): after g, after the squares (or the norm), the rest.
  // Regs >= 6 (Split): the first register goes between the six products and their sums (RP)
  // and the second after |W|'s clamp (RA) instead of after g; then the squares, the rest in
  // the root: products | sums, |.|, clamp | squares | root. Fewer: g | squares | root.
  localparam bit Split = !Serial && Regs >= 6;
  localparam int RP = Split ? 1 : 0;
  localparam int R0 = (!Serial && !Split && Regs > 0) ? 1 : 0;
  localparam int RA = Split ? 1 : 0;
  localparam int R1 = (!Serial && Regs > 1) ? 1 : 0;
  localparam int RS = Split ? Regs - 3 : (!Serial && Regs > 2) ? Regs - 2 : 0;
  // (Not '1: Yosys 0.23 reads '1 in a parameter declaration as the 1-bit value 1.)
  localparam logic [WW-1:0] WMax = {WW{1'b1}};

  // Step 1 per direction d (0: x with dsdx = j[0..2], 1: y with dsdy = j[3..5]): gd.
  logic [2*XW-1:0] g;    // g_d at [d*XW +: XW]
  if (!Serial) begin : g_par
    // One signed product, exact: a radix-4 Booth product (rtl/common/pst_mul_booth.sv, the
    // Jacobian entry recoded; half the rows of Yosys' AND array: less area, a shorter path).
    localparam int PW = GW + JW;
    logic [2*XW-1:0] g_d;
    logic [6*PW-1:0] prod_d, prod;   // grad_k ds_k/d(x, y): product 3 d + k at [(3d+k)*PW +: PW]
    for (genvar d = 0; d < 2; d++) begin : g_dir
      for (genvar k = 0; k < 3; k++) begin : g_prod
        pst_mul_booth #(.AW(GW), .BW(JW), .BSigned(1'b1), .PW(PW)) u_mul (
          .a_i (grad_i[k*GW +: GW]), .b_i (j_i[(3*d+k)*JW +: JW]), .p_o (prod_d[(3*d+k)*PW +: PW]));
      end
    end
    pst_delay #(.Width(6*PW), .Depth(RP)) u_reg_p (.clk_i, .rst_ni, .en_i, .d_i (prod_d), .q_o (prod));
    for (genvar d = 0; d < 2; d++) begin : g_sum
      assign g_d[d*XW +: XW] = XW'($signed(prod[(3*d+0)*PW +: PW])) + XW'($signed(prod[(3*d+1)*PW +: PW])) +
                               XW'($signed(prod[(3*d+2)*PW +: PW]));
    end
    pst_delay #(.Width(2*XW), .Depth(R0)) u_reg_g (.clk_i, .rst_ni, .en_i, .d_i (g_d), .q_o (g));
    logic unused_serial;
    assign unused_serial = ^{step_i, adv_i};
    assign done_o = 1'b1;
  end else begin : g_ser
    // Product 3 d + k = step_i: grad_k ds_k/d(x or y) added to direction d's sum (k = 0
    // starts from zero). Direction x's sum is held for steps 3..5; y's is live at step 5.
    logic [1:0]           d, k;
    logic signed [GW-1:0] gk;
    logic signed [JW-1:0] jk;
    logic signed [XW-1:0] gx_q, gy_q, sum;
    logic                 prod_step;   // steps 0..5: the dot products
    assign prod_step = (32'(step_i) < SqStep);
    assign d = (step_i >= SB'(3)) ? 2'd1 : 2'd0;
    assign k = 2'((step_i >= SB'(3)) ? step_i - SB'(3) : step_i);
    always_comb begin
      gk = grad_i[0*GW +: GW];
      jk = j_i[0*JW +: JW];
      for (int c = 0; c < 3; c++) begin
        if (32'(k) == c) gk = grad_i[c*GW +: GW];
        for (int dd = 0; dd < 2; dd++) begin
          if (32'(k) == c && 32'(d) == dd) jk = j_i[(3*dd+c)*JW +: JW];
        end
      end
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        gx_q <= '0;
        gy_q <= '0;
      end else if (adv_i && prod_step) begin
        if (d == 2'd0) gx_q <= sum;
        else gy_q <= sum;
      end
    end
    assign sum = ((k == 2'd0) ? '0 : ((d == 2'd0) ? gx_q : gy_q)) + XW'(gk) * XW'(jk);
    // Direction y is live at step 5, held after it (the euclidean norm's steps, which take
    // both from the registers: the product does not run into the squares).
    if (Euclid) begin : g_held
      assign g = {gy_q, gx_q};
    end else begin : g_live
      assign g = prod_step ? {sum, gx_q} : {gy_q, gx_q};
    end
    logic unused_en;
    assign unused_en = en_i;
    assign done_o = (32'(step_i) == LastStep);
  end

  // Steps 2-3 per direction: to entries, |.|, clamp.
  logic [2*WW-1:0] aw_d, aw;   // a_d at [d*WW +: WW]; aw after RA
  for (genvar d = 0; d < 2; d++) begin : g_dir
    logic signed [XW-1:0] gd;
    logic signed [SW-1:0] wd, absd;
    assign gd   = g[d*XW +: XW];
    assign wd   = (SW'(gd) <<< ShL) >>> ShR;        // floor(g N to WidthFrac)
    assign absd = wd[SW-1] ? -wd : wd;              // |W_d|, no overflow (XW has a spare bit)
    assign aw_d[d*WW +: WW] = (absd[SW-1:WW] != '0) ? WMax : absd[WW-1:0];
  end
  pst_delay #(.Width(2*WW), .Depth(RA)) u_reg_a (.clk_i, .rst_ni, .en_i, .d_i (aw_d), .q_o (aw));

  logic [WW-1:0] ax, ay;
  assign ax = aw[0*WW +: WW];
  assign ay = aw[1*WW +: WW];

  // Step 4: the norm (at most WW + 1 bits), then saturate to WW bits.
  logic [WW:0] nrm;
  if (Euclid && !Serial) begin : g_euclid
    logic [SqW-1:0] sumsq_d, sumsq;
    logic [WW:0]    root;   // pst_isqrt: ceil(SqW / 2) = WW + 1 bits
    assign sumsq_d = SqW'(ax) * SqW'(ax) + SqW'(ay) * SqW'(ay);
    pst_delay #(.Width(SqW), .Depth(R1)) u_reg_sq (.clk_i, .rst_ni, .en_i, .d_i (sumsq_d), .q_o (sumsq));
    pst_isqrt #(.InWidth(SqW), .Regs(RS)) u_isqrt (.clk_i, .rst_ni, .en_i, .x_i (sumsq), .y_o (root));
    assign nrm = root;
  end else if (Euclid) begin : g_euclid_ser
    // xs_q: ax^2 (step 6), ax^2 + ay^2 (step 7), then shifted left two digits (4 bits) a cycle;
    // the digits are taken from its top. 4 NSq >= SqW bits (zero-extended).
    localparam int XPW = 4 * NSq;
    localparam int RW  = 2 * NSq + 2;   // remainder and root: root < 2^(2 NSq), rem <= 2 root
    logic [XPW-1:0] xs_q, sq, xs_d;
    logic [RW-1:0]  rem_q, root_q, rem_d, root_d;
    logic           sqrt_step, first;
    logic [WW-1:0]  a_sq;   // ax at step 6, ay at step 7
    assign a_sq      = (32'(step_i) == SqStep) ? ax : ay;
    assign sq        = XPW'(a_sq) * XPW'(a_sq);
    assign sqrt_step = (32'(step_i) >= RootStep);
    assign first     = (32'(step_i) == RootStep);
    always_comb begin
      logic [RW-1:0] r, q, trial;
      r = first ? '0 : rem_q;
      q = first ? '0 : root_q;
      for (int t = 0; t < 2; t++) begin
        r     = (r << 2) | RW'(xs_q[XPW-1-2*t -: 2]);
        trial = (q << 2) | RW'(1);
        if (r >= trial) begin
          r = r - trial;
          q = (q << 1) | RW'(1);
        end else begin
          q = q << 1;
        end
      end
      rem_d  = r;
      root_d = q;
      if (32'(step_i) == SqStep) xs_d = sq;
      else if (32'(step_i) == SqStep + 1) xs_d = xs_q + sq;
      else xs_d = xs_q << 4;
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        xs_q   <= '0;
        rem_q  <= '0;
        root_q <= '0;
      end else if (adv_i && 32'(step_i) >= SqStep) begin
        xs_q <= xs_d;
        if (sqrt_step) begin
          rem_q  <= rem_d;
          root_q <= root_d;
        end
      end
    end
    assign nrm = root_d[WW:0];   // the last step's root: floor(sqrt(ax^2 + ay^2)) < 2^(WW+1)
    logic unused_root;
    assign unused_root = ^root_d[RW-1:WW+1];
  end else if (FilterNorm == pst_pkg::FilterNormMaxHalfMin) begin : g_max_half_min
    logic [WW-1:0] amax, amin;
    logic [WW:0]   nrm_d;
    assign amax  = (ax >= ay) ? ax : ay;
    assign amin  = (ax >= ay) ? ay : ax;
    assign nrm_d = (WW + 1)'(amax) + ((WW + 1)'(amin) >> 1);
    pst_delay #(.Width(WW + 1), .Depth(R1 + RS)) u_reg_n (.clk_i, .rst_ni, .en_i, .d_i (nrm_d), .q_o (nrm));
  end else begin : g_l1
    logic [WW:0] nrm_d;
    assign nrm_d = (WW + 1)'(ax) + (WW + 1)'(ay);
    pst_delay #(.Width(WW + 1), .Depth(R1 + RS)) u_reg_n (.clk_i, .rst_ni, .en_i, .d_i (nrm_d), .q_o (nrm));
  end
  assign w_o = nrm[WW] ? WMax : nrm[WW-1:0];

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (Euclid || FilterNorm == pst_pkg::FilterNormMaxHalfMin || FilterNorm == pst_pkg::FilterNormL1)
      else $error("pst_filter_width: FilterNorm must be euclid, max_half_min or l1");
    assert (NSteps - 1 <= pst_pkg::StepMax) else $error("pst_filter_width: %0d steps do not fit step_i", NSteps);
    assert (!Serial || Regs == 0) else $error("pst_filter_width: the serial unit has no pipeline registers");
  end
  // W is at least the larger component and at most their sum (every norm), with the ax, ay
  // of the same fragment (R1 + RS registers earlier).
  logic [WW-1:0] ax_chk, ay_chk;
  pst_delay #(.Width(2*WW), .Depth(R1 + RS)) u_chk (.clk_i, .rst_ni, .en_i, .d_i ({ay, ax}), .q_o ({ay_chk, ax_chk}));
  always_comb begin
    if (done_o) assert (w_o >= ax_chk && w_o >= ay_chk && (WW + 1)'(w_o) <= (WW + 1)'(ax_chk) + (WW + 1)'(ay_chk))
      else $error("pst_filter_width: W outside [max(|Wx|, |Wy|), |Wx| + |Wy|]");
  end
`endif

endmodule

`default_nettype wire

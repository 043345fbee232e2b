// One lerp of the noise unit's interpolation tree (part of rtl/noise/pst_noise.sv, unit 2 of
// docs/HARDWARE.md), carrying the value and its three derivatives. Combinational.
// Golden: pst::noiseFx (model/golden/noise_fx.cpp).
//
// Nodes a (lower corner on axis Axis) and b (upper), each (v, g_x, g_y, g_z) at NodeFrac
// fraction bits; s, ds: the weight of b and its derivative on this axis, LF fraction bits.
//   L(x, y)   = x + floor((y - x) * s / 2^LF)                 one product per component
//   L_F(x, y) = x + 2^F floor(((y - x) / 2^F) s / 2^LF)        F = GradFloor (L_0 = L)
//   v'   = L(a.v, b.v)
//   g'_j = L_F(a.g_j, b.g_j)                                   for j != Axis
//   g'_k = 2^F floor(floor((b.v - a.v) / 2^F) ds / 2^LF) + L_F(a.g_k, b.g_k)   k = Axis
//   (product rule). The derivative lanes (inputs and outputs) are multiples of 2^F: the
//   profile's noise.grad_frac (rtl/noise/pst_noise.sv); the own-axis product takes the value
//   difference floored to 2^F, so it is (VW + 1 - F) bits wide.
//   NoiseInterp = 0 (scurve), 2 (quintic): the own-axis term needs a (VW+1) x (LF+2) product
//   (scurve: ds is even and < 2, so (VW+1) x LF and a shift; below).
//   NoiseInterp = 1 (linear): ds = 1, the own-axis term is b.v - a.v exactly (no multiplier).
// Ranges: L(x, y) lies between x and y (floor of a product of (y - x) and s in [0, 1)), so
// |v'| <= 3.5 stays Q3; |g'| <= 1.5 * 6 + 1 < 16 stays Q5 (proof in rtl/noise/pst_noise.sv).
//
// Narrow derivative lanes (exact; area only). The caller says what it knows of each input
// derivative lane k (pst_noise derives it from the corner kind and the lerps done before):
// every value on lane k is a multiple of 2^GradLo<k> and fits GradHi<k> bits signed (bits
// GradHi<k>-1 .. GW-1 are copies of one sign). The lane's lerp then multiplies only the
// GradHi - GradLo significant bits of y - x:
//   floor((y - x) s / 2^LF) = floor(D s / 2^(LF - Lo))   (D = (y - x) / 2^Lo, exact)
// (Lo >= LF: D s 2^(Lo - LF), no floor), and adds x: the same bits as the full-width lane.
// With a floor F <= Lo the lane computes 2^F floor(D s / 2^(LF - (Lo - F))) on the bits
// above F only and writes F constant zeros below (so the registers after it hold fewer bits).
// Full: the x lerps' derivative lanes are R (Q1.15 at NodeFrac 20: Hi 21, Lo 5), so their
// products are 17 x 16 instead of 26 x 16; the y and z lerps' not-yet-own lanes Q1 (Hi 21).
//
// Products: radix-4 Booth (rtl/common/pst_mul_booth.sv; Yosys 0.23 builds only AND arrays): signed
// differences times the unsigned weights.
//
// Parameters:
//   NoiseInterp, NoiseLatticeFrac, NodeFrac, Axis   as above
//   GradHi0..2, GradLo0..2   what is known of the input derivative lanes (default: nothing,
//                            Hi = GW, Lo = 0)
//   GradFloor                F: the derivative lanes' floor (default 0: exact L, every node
//                            bit); every GradLo must be >= F (the inputs are multiples of 2^F)
//
// Ports:
//   a_i, b_i, node_o [NodeW-1:0]  v at [0 +: VW], g_k at [VW + k*GW +: GW], signed
//   s_i  [LF-1:0]   unsigned weight of b_i
//   ds_i [LF+1:0]   unsigned ds/du (unused for linear)
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_noise_lerp #(
  `PST_WEIGHT_PARAMS,
  parameter int NodeFrac = 20,
  parameter int Axis = 0,
  parameter int GradHi0 = 5 + NodeFrac,
  parameter int GradHi1 = 5 + NodeFrac,
  parameter int GradHi2 = 5 + NodeFrac,
  parameter int GradLo0 = 0,
  parameter int GradLo1 = 0,
  parameter int GradLo2 = 0,
  parameter int GradFloor = 0,
  localparam int LF = NoiseLatticeFrac,     // fraction bits of s, ds
  localparam int VW = 3 + NodeFrac,         // node value Q3.NodeFrac
  localparam int GW = 5 + NodeFrac,         // node derivative Q5.NodeFrac
  localparam int NodeW = VW + 3 * GW
) (
  input  logic [NodeW-1:0] a_i,
  input  logic [NodeW-1:0] b_i,
  input  logic [LF-1:0]    s_i,
  input  logic [LF+1:0]    ds_i,
  output logic [NodeW-1:0]      node_o
);

  // Value difference b.v - a.v: Q4.NodeFrac (|b - a| <= 7).
  localparam int DW = VW + 1;
  // Own-axis sum: lerp (GW bits) + (b - a) ds (|.| < 10.6, sign-extended): GW + 1 bits.
  localparam int OwnW = GW + 1;

  // The derivative lanes' floor F, and the lanes' widths above it.
  localparam int F = GradFloor;
  // The value difference floored to 2^F: floor((b.v - a.v) / 2^F), DW - F bits.
  localparam int DFW = DW - F;

  logic signed [DW-1:0] dv;  // b.v - a.v, exact
  logic signed [DFW-1:0] dvf;
  assign dv = {b_i[VW-1], b_i[0 +: VW]} - {a_i[VW-1], a_i[0 +: VW]};
  assign dvf = dv[DW-1:F];
  if (F > 0) begin : g_unused_dv
    logic unused_dv;   // below the derivative lanes' floor
    assign unused_dv = ^dv[F-1:0];
  end

  // The own-axis product term floor(dvf ds / 2^LF) (in units of 2^F), sign-extended to
  // OwnW - F bits.
  logic signed [OwnW-F-1:0] own_term;
  if (NoiseInterp == pst_pkg::NoiseInterpScurve && LF >= 2) begin : g_scurve
    // scurve: ds = 6 (U - u2) is even and <= 1.5 2^LF (pst_noise_weight), so ds = 2 dh with
    // dh = ds[LF:1] < 2^LF: the product dvf dh is DFW x LF (not DFW x (LF+2)), then doubled.
    localparam int QW = DFW + LF;
    logic [LF-1:0] dh;
    logic [QW-1:0] q;
    assign dh = ds_i[LF:1];
    pst_mul_booth #(.AW(DFW), .BW(LF), .BSigned(1'b0), .PW(QW)) u_mul (
      .a_i (dvf), .b_i (dh), .p_o (q)
    );
    // floor(dvf ds / 2^LF) = floor(dvf dh / 2^(LF-1)); |(b - a) ds| <= 7 * 1.5 fits OwnW.
    assign own_term = (OwnW-F)'($signed(q[LF-1 +: QW-LF+1]));
    logic unused_q;
    assign unused_q = ^{q[LF-2:0], ds_i[LF+1], ds_i[0]};
  end else if (NoiseInterp != pst_pkg::NoiseInterpLinear) begin : g_general
    // dvf ds: DFW + LF + 2 bits, exact.
    localparam int QW = DFW + LF + 2;
    logic [QW-1:0] q;
    pst_mul_booth #(.AW(DFW), .BW(LF+2), .BSigned(1'b0), .PW(QW)) u_mul (
      .a_i (dvf), .b_i (ds_i), .p_o (q)
    );
    // floor: drop LF bits; |(b - a) ds| <= 7 * 1.875 fits OwnW (Q6) easily.
    assign own_term = q[LF +: OwnW-F];
    logic unused_q;
    assign unused_q = ^q[LF-1:0];   // QW = LF + OwnW - F: every higher bit is own_term
  end else begin : g_linear
    assign own_term = {{(OwnW-DW){dvf[DFW-1]}}, dvf};
    logic unused_ds;
    assign unused_ds = ^ds_i;
  end

  // Four component lerps: j = 0 value (VW bits), j = 1..3 derivative d/dp_(j-1) (GW bits).
  for (genvar j = 0; j < 4; j++) begin : g_comp
    localparam int W = (j == 0) ? VW : GW;               // component width
    localparam int Off = (j == 0) ? 0 : VW + (j-1) * GW; // component offset in the node
    // The lane's significant bits [Lo, Hi) (header).
    localparam int Hi = (j == 0) ? VW : (j == 1) ? GradHi0 : (j == 2) ? GradHi1 : GradHi2;
    localparam int Lo = (j == 0) ? 0 : (j == 1) ? GradLo0 : (j == 2) ? GradLo1 : GradLo2;
    localparam int Fj = (j == 0) ? 0 : F;                // the lane's floor
    localparam int Sh = Lo - Fj;                         // zero bits of D above the floor
    localparam int N = Hi - Lo + 1;                      // D = (y - x) / 2^Lo, signed
    localparam int PW = N + LF;                          // D s, exact
    localparam int RW = W - Fj;                          // the lane's bits above the floor
    logic signed [N-1:0]  diff;
    logic [PW-1:0]        p;
    logic signed [RW+1:0] term;    // floor((y - x) s / 2^(LF + Fj)), sign-extended
    logic signed [RW+1:0] lerp;    // (x + 2^Fj term) / 2^Fj, RW + 2 bits before the range check

    assign diff = {b_i[Off+Hi-1], b_i[Off+Lo +: Hi-Lo]} - {a_i[Off+Hi-1], a_i[Off+Lo +: Hi-Lo]};
    pst_mul_booth #(.AW(N), .BW(LF), .BSigned(1'b0), .PW(PW)) u_mul (
      .a_i (diff), .b_i (s_i), .p_o (p)
    );
    if (Sh >= LF) begin : g_exact
      assign term = (RW+2)'($signed(p)) <<< (Sh - LF);
    end else begin : g_floor
      logic signed [PW-LF+Sh-1:0] pf;
      assign pf = p[LF-Sh +: PW-LF+Sh];
      assign term = (RW+2)'(pf);
      logic unused_p_low;
      assign unused_p_low = ^p[LF-Sh-1:0];
    end
    assign lerp = {{(W+2-Hi){a_i[Off+Hi-1]}}, a_i[Off+Fj +: Hi-Fj]} + term;
    if (Hi < W) begin : g_unused_high
      logic unused_hi;   // sign copies (the caller's promise)
      assign unused_hi = ^{a_i[Off+Hi +: W-Hi], b_i[Off+Hi +: W-Hi]};
    end
    if (Lo > 0) begin : g_unused_low
      logic unused_lo;   // zeros (the caller's promise)
      assign unused_lo = ^b_i[Off +: Lo];
    end
    if (Fj > 0) begin : g_unused_low_a
      logic unused_lo_a;   // zeros (the caller's promise, Lo >= F)
      assign unused_lo_a = ^a_i[Off +: Fj];
    end

    // The lane's result above its floor (RW bits), then Fj zeros below.
    logic [RW-1:0] res;
    if (j == Axis + 1) begin : g_own
      // lerp + own_term (units of 2^F), two guard bits for the range check
      logic signed [OwnW-F+1:0] sum;
      assign sum = {{(OwnW+2-(W+2)){lerp[RW+1]}}, lerp} + {{2{own_term[OwnW-F-1]}}, own_term};
      assign res = sum[RW-1:0];
      logic unused_sum;
      assign unused_sum = ^sum[OwnW-F+1:RW];
    end else begin : g_other
      assign res = lerp[RW-1:0];
      logic unused_lerp;
      assign unused_lerp = ^lerp[RW+1:RW];
    end
    if (Fj > 0) begin : g_floor_zeros
      assign node_o[Off +: W] = {res, {Fj{1'b0}}};
    end else begin : g_no_floor
      assign node_o[Off +: W] = res;
    end
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (Axis < 0 || Axis > 2) $error("pst_noise_lerp: Axis must be 0..2");
    if (GradHi0 > GW || GradHi1 > GW || GradHi2 > GW || GradLo0 < 0 || GradLo1 < 0 || GradLo2 < 0 ||
        GradLo0 >= GradHi0 || GradLo1 >= GradHi1 || GradLo2 >= GradHi2)
      $error("pst_noise_lerp: GradHi/GradLo out of range");
    if (GradFloor < 0 || GradFloor >= NodeFrac || GradLo0 < GradFloor || GradLo1 < GradFloor ||
        GradLo2 < GradFloor)
      $error("pst_noise_lerp: GradFloor must be in [0, NodeFrac) and <= every GradLo");
  end
  if (NoiseInterp == pst_pkg::NoiseInterpScurve && LF >= 2) begin : g_assert_ds
    always_comb begin
      assert (ds_i[0] == 1'b0 && ds_i[LF+1] == 1'b0) else $error("pst_noise_lerp: scurve ds odd or >= 2");
    end
  end
  // Every component result fits its width (no wrap): the high bits are sign copies.
  for (genvar j = 0; j < 4; j++) begin : g_assert_comp
    localparam int W = (j == 0) ? VW : GW;
    localparam int Off = (j == 0) ? 0 : VW + (j-1) * GW;
    localparam int Hi = (j == 0) ? VW : (j == 1) ? GradHi0 : (j == 2) ? GradHi1 : GradHi2;
    localparam int Lo = (j == 0) ? 0 : (j == 1) ? GradLo0 : (j == 2) ? GradLo1 : GradLo2;
    // The caller's promise about the input lanes (GradHi, GradLo).
    always_comb begin
      assert (a_i[Off+W-1:Off+Hi-1] == '0 || a_i[Off+W-1:Off+Hi-1] == '1)
        else $error("pst_noise_lerp: lane %0d of a exceeds GradHi", j);
      assert (b_i[Off+W-1:Off+Hi-1] == '0 || b_i[Off+W-1:Off+Hi-1] == '1)
        else $error("pst_noise_lerp: lane %0d of b exceeds GradHi", j);
    end
    if (Lo > 0) begin : g_assert_lo
      always_comb begin
        assert (a_i[Off +: Lo] == '0 && b_i[Off +: Lo] == '0)
          else $error("pst_noise_lerp: lane %0d has bits below GradLo", j);
      end
    end
    if (j == Axis + 1) begin : g_own
      always_comb begin
        assert ((g_comp[j].g_own.sum[OwnW-F+1:W-F-1] == '0) ||
                (g_comp[j].g_own.sum[OwnW-F+1:W-F-1] == '1))
          else $error("pst_noise_lerp: own-axis derivative overflow");
      end
    end else begin : g_other
      localparam int RW = W - ((j == 0) ? 0 : F);
      always_comb begin
        assert ((g_comp[j].lerp[RW+1:RW-1] == '0) || (g_comp[j].lerp[RW+1:RW-1] == '1))
          else $error("pst_noise_lerp: component %0d overflow", j);
      end
    end
  end
`endif

endmodule

`default_nettype wire

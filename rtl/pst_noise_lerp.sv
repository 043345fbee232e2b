// One lerp of the noise unit's interpolation tree (part of rtl/pst_noise.sv, stage 2 of
// docs/HARDWARE.md), carrying the value and its three derivatives. Combinational.
// Golden: pst::noiseFx (model/golden/noise_fx.cpp).
//
// Nodes a (lower corner on axis Axis) and b (upper), each (v, g_x, g_y, g_z) at NodeFrac
// fraction bits; s, ds: the weight of b and its derivative on this axis, LF fraction bits.
//   L(x, y) = x + floor((y - x) * s / 2^LF)           one (W+1) x (LF+1) multiplier
//   v'   = L(a.v, b.v)
//   g'_j = L(a.g_j, b.g_j)                             for j != Axis
//   g'_k = floor((b.v - a.v) * ds / 2^LF) + L(a.g_k, b.g_k)   k = Axis: product rule
//   NoiseInterp = 0 (scurve), 2 (quintic): the own-axis term needs a (VW+1) x (LF+3) multiplier.
//   NoiseInterp = 1 (linear): ds = 1, the own-axis term is b.v - a.v exactly (no multiplier).
// Ranges: L(x, y) lies between x and y (floor of a product of (y - x) and s in [0, 1)), so
// |v'| <= 3.5 stays Q3; |g'| <= 1.5 * 6 + 1 < 16 stays Q5 (proof in rtl/pst_noise.sv).
//
// Ports:
//   a_i, b_i, node_o [NodeW-1:0]  v at [0 +: VW], g_k at [VW + k*GW +: GW], signed
//   s_i  [LF-1:0]   unsigned weight of b_i
//   ds_i [LF+1:0]   unsigned ds/du (unused for linear)
`include "pst_pkg.sv"
`default_nettype none

module pst_noise_lerp #(
  parameter int NoiseInterp = pst_pkg::NoiseInterpDefault,
  parameter int NoiseLatticeFrac = pst_pkg::NoiseLatticeFracDefault,
  parameter int NodeFrac = 20,
  parameter int Axis = 0,
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

  logic signed [DW-1:0] dv;  // b.v - a.v, exact
  assign dv = {b_i[VW-1], b_i[0 +: VW]} - {a_i[VW-1], a_i[0 +: VW]};

  // The own-axis product term floor((b.v - a.v) ds / 2^LF), sign-extended to OwnW.
  logic signed [OwnW-1:0] own_term;
  if (NoiseInterp != pst_pkg::NoiseInterpLinear) begin : g_scurve
    // (DW) x (LF+3) signed product: DW + LF + 3 bits, exact.
    localparam int QW = DW + LF + 3;
    logic signed [QW-1:0] dv_ext, ds_ext, q;
    assign dv_ext = {{(LF+3){dv[DW-1]}}, dv};
    assign ds_ext = {{(DW+1){1'b0}}, ds_i};
    assign q = dv_ext * ds_ext;
    // floor: drop LF bits; |(b - a) ds| <= 7 * 1.5 fits OwnW (Q6) easily.
    assign own_term = q[LF +: OwnW];
    logic unused_q;
    assign unused_q = ^{q[LF-1:0], q[QW-1:LF+OwnW]};
  end else begin : g_linear
    assign own_term = {{(OwnW-DW){dv[DW-1]}}, dv};
    logic unused_ds;
    assign unused_ds = ^ds_i;
  end

  // Four component lerps: j = 0 value (VW bits), j = 1..3 derivative d/dp_(j-1) (GW bits).
  for (genvar j = 0; j < 4; j++) begin : g_comp
    localparam int W = (j == 0) ? VW : GW;               // component width
    localparam int Off = (j == 0) ? 0 : VW + (j-1) * GW; // component offset in the node
    localparam int PW = W + 1 + LF + 1;                  // (y - x) x s, exact
    logic signed [W:0]    diff;    // y - x, one bit wider than the component
    logic signed [PW-1:0] diff_ext, s_ext, p;
    logic signed [W+1:0]  lerp;    // x + floor(p / 2^LF), W + 2 bits before the range check

    assign diff = {b_i[Off+W-1], b_i[Off +: W]} - {a_i[Off+W-1], a_i[Off +: W]};
    assign diff_ext = {{(LF+1){diff[W]}}, diff};
    assign s_ext = {{(W+2){1'b0}}, s_i};
    assign p = diff_ext * s_ext;
    assign lerp = {{2{a_i[Off+W-1]}}, a_i[Off +: W]} + p[LF +: W+2];

    logic unused_p_low;
    assign unused_p_low = ^p[LF-1:0];

    if (j == Axis + 1) begin : g_own
      logic signed [OwnW+1:0] sum;  // lerp + own_term, two guard bits for the range check
      assign sum = {{(OwnW+2-(W+2)){lerp[W+1]}}, lerp} + {{2{own_term[OwnW-1]}}, own_term};
      assign node_o[Off +: W] = sum[W-1:0];
      logic unused_sum;
      assign unused_sum = ^sum[OwnW+1:W];
    end else begin : g_other
      assign node_o[Off +: W] = lerp[W-1:0];
      logic unused_lerp;
      assign unused_lerp = ^lerp[W+1:W];
    end
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (Axis < 0 || Axis > 2) $error("pst_noise_lerp: Axis must be 0..2");
  end
  // Every component result fits its width (no wrap): the high bits are sign copies.
  for (genvar j = 0; j < 4; j++) begin : g_assert_comp
    localparam int W = (j == 0) ? VW : GW;
    if (j == Axis + 1) begin : g_own
      always_comb begin
        assert ((g_comp[j].g_own.sum[OwnW+1:W-1] == '0) || (g_comp[j].g_own.sum[OwnW+1:W-1] == '1))
          else $error("pst_noise_lerp: own-axis derivative overflow");
      end
    end else begin : g_other
      always_comb begin
        assert ((g_comp[j].lerp[W+1:W-1] == '0) || (g_comp[j].lerp[W+1:W-1] == '1))
          else $error("pst_noise_lerp: component %0d overflow", j);
      end
    end
  end
`endif

endmodule

`default_nettype wire

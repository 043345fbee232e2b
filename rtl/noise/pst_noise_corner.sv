// One lattice corner of the noise unit (part of rtl/noise/pst_noise.sv, unit 2 of
// docs/HARDWARE.md): the corner's value and gradient as a lerp-tree leaf node.
// Combinational. Golden: pst::noiseFx (model/golden/noise_fx.cpp).
//
// corner_i = bx + 2 by + 4 bz selects the corner of the cell (x fastest, Rayshade's order); a
// port, not a parameter, so that a serial noise unit (NoiseSteps > 1) can walk the corners.
// In: R[m], R[m+1], R[m+2], R[m+3] (Q1.VF, VF = NoiseValueFrac) and the fractions u (LF =
// NoiseLatticeFrac bits per axis). d_k = u_k - b_k in [-1, 1).
//   NoiseCorner = 0 (value_gradient, Rayshade):
//     v = R[m] 2^(LF-1) + R[m+1] d_x + R[m+2] d_y + R[m+3] d_z
//         exact at VF + LF fraction bits: |R d| <= 1 (VF + LF + 2 bits each), |v| <= 3.5
//         (ExW = 3 + VF + LF bits); three (VF+1) x (LF+1) Booth products (d_k's bit
//         pattern is {b_k, u_k}).
//     gradient (R[m+1], R[m+2], R[m+3]).
//   NoiseCorner = 1 (value): v = R[m] 2^(LF-1) (0.5 R[m]); gradient 0 (R[m+1..3] unused).
//   NoiseCorner = 2 (grad12, Perlin 2002's grad(hash, d)): no value table (r_i unused); the
//     low four hash bits h = hash_i pick axis a = (h < 8 ? x : y) and axis b = (h < 4 ? y :
//     h == 12 || h == 14 ? x : z) (never a); v = (h[0] ? -d_a : d_a) + (h[1] ? -d_b : d_b)
//     exact at LF fraction bits (|v| <= 2, LF + 3 bits); gradient +-1 on axes a and b, 0 on
//     the third. Adders and muxes only.
// Out: node = (floor(v to NodeFrac), floor(R[m+1..3] to NodeFrac)): v Q3.NodeFrac, gradient
// Q5.NodeFrac (the width every lerp-tree node uses for derivatives).
//
// Ports:
//   r_i    [4*RW-1:0]  R[m+k] at [k*RW +: RW], RW = NoiseValueFrac + 1, signed
//   hash_i [3:0]       low four bits of the corner's hash m (grad12 only)
//   u_i    [3*LF-1:0]  u per axis, unsigned
//   node_o [NodeW-1:0] v at [0 +: VW], d/dp_k at [VW + k*GW +: GW] (VW = 3 + NodeFrac,
//                      GW = 5 + NodeFrac, NodeW = VW + 3 GW), signed
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_noise_corner #(
  `PST_CORNER_PARAMS,
  parameter int NodeFrac = 20,
  localparam int RW = NoiseValueFrac + 1,   // Q1.VF value-table entry
  localparam int LF = NoiseLatticeFrac,     // fraction bits of u
  localparam int VW = 3 + NodeFrac,         // node value Q3.NodeFrac: |v| <= 3.5
  localparam int GW = 5 + NodeFrac,         // node derivative Q5.NodeFrac: |g| < 16
  localparam int NodeW = VW + 3 * GW
) (
  input  logic [2:0]      corner_i,
  input  logic [4*RW-1:0] r_i,
  input  logic [3:0]      hash_i,
  input  logic [3*LF-1:0] u_i,
  output logic [NodeW-1:0]     node_o
);

  localparam int VF = NoiseValueFrac;
  // Exact corner value: 3 integer bits (|v| <= 3.5), VF + LF fraction bits.
  localparam int ExW = 3 + VF + LF;
  // Floor of v from VF + LF to NodeFrac fraction bits (< 0: exact left shift).
  localparam int VShift = VF + LF - NodeFrac;
  // R from VF to NodeFrac fraction bits (< 0: exact left shift).
  localparam int GShift = VF - NodeFrac;

  // 0.5 R[m] = R[m] << (LF - 1) at VF + LF fraction bits, sign-extended to ExW.
  logic signed [ExW-1:0] half_r0;
  if (LF > 1) begin : g_half_shift
    assign half_r0 = {{3{r_i[RW-1]}}, r_i[0 +: RW], {(LF-1){1'b0}}};
  end else begin : g_half_noshift
    assign half_r0 = {{3{r_i[RW-1]}}, r_i[0 +: RW]};
  end

  logic signed [ExW-1:0] v_exact;

  if (NoiseCorner == pst_pkg::NoiseCornerGrad12) begin : g_grad12
    // d_k = u_k - b_k as LF+3-bit signed values; v = +-d_a +-d_b, |v| <= 2.
    localparam int DW = LF + 3;
    localparam int GShift12 = LF - NodeFrac;  // floor of v from LF to NodeFrac bits
    logic [3*DW-1:0]       d;
    logic [1:0]            ax_a, ax_b;        // axis indices 0..2
    logic signed [DW-1:0]  da, db, v12;
    for (genvar k = 0; k < 3; k++) begin : g_d
      assign d[k*DW +: DW] = {{(DW-LF-1){corner_i[k]}}, corner_i[k], u_i[k*LF +: LF]};
    end
    assign ax_a = hash_i[3] ? 2'd1 : 2'd0;
    assign ax_b = (hash_i[3:2] == 2'b00) ? 2'd1 :
                  (hash_i == 4'd12 || hash_i == 4'd14) ? 2'd0 : 2'd2;
    assign da = hash_i[3] ? d[1*DW +: DW] : d[0*DW +: DW];
    always_comb begin
      unique case (ax_b)
        2'd0:    db = d[0*DW +: DW];
        2'd1:    db = d[1*DW +: DW];
        default: db = d[2*DW +: DW];
      endcase
    end
    assign v12 = (hash_i[0] ? -da : da) + (hash_i[1] ? -db : db);
    if (GShift12 > 0) begin : g_v12_floor
      assign node_o[0 +: VW] = VW'(v12 >>> GShift12);
    end else begin : g_v12_shift
      assign node_o[0 +: VW] = VW'(v12) <<< (-GShift12);
    end
    for (genvar k = 0; k < 3; k++) begin : g_dir
      logic signed [GW-1:0] one;
      assign one = GW'(1) <<< NodeFrac;
      assign node_o[VW + k*GW +: GW] = (ax_a == 2'(k)) ? (hash_i[0] ? -one : one) :
                                       (ax_b == 2'(k)) ? (hash_i[1] ? -one : one) : '0;
    end
    assign v_exact = '0;  // (the ROM corners' exact value; unused here)
    logic unused_grad12;
    assign unused_grad12 = ^{r_i, half_r0};
  end else if (NoiseCorner == pst_pkg::NoiseCornerValueGradient) begin : g_value_gradient
    // R d_k, d_k = u_k - b_k: its bit pattern is {b_k, u_k} (LF + 1 bits signed); a Booth
    // product (rtl/common/pst_mul_booth.sv, R recoded: fewer rows than d, 6666 GE a corner in full
    // against 7181 with d recoded) sign-extended to ExW bits (ExW >= RW + LF + 1: exact).
    logic [3*ExW-1:0] prod;  // R[m+1+k] d_k at [k*ExW +: ExW]
    for (genvar k = 0; k < 3; k++) begin : g_axis
      pst_mul_booth #(.AW(LF + 1), .BW(RW), .BSigned(1'b1), .PW(ExW)) u_mul (
        .a_i ({corner_i[k], u_i[k*LF +: LF]}),
        .b_i (r_i[(k+1)*RW +: RW]),
        .p_o (prod[k*ExW +: ExW])
      );

      // Gradient component k: R[m+1+k] brought to Q5.NodeFrac.
      if (GShift > 0) begin : g_grad_floor
        assign node_o[VW + k*GW +: GW] = {{4{r_i[(k+2)*RW-1]}}, r_i[(k+1)*RW + GShift +: RW - GShift]};
        logic unused_low;
        assign unused_low = ^r_i[(k+1)*RW +: GShift];
      end else if (GShift < 0) begin : g_grad_shift
        assign node_o[VW + k*GW +: GW] = {{4{r_i[(k+2)*RW-1]}}, r_i[(k+1)*RW +: RW], {(-GShift){1'b0}}};
      end else begin : g_grad_same
        assign node_o[VW + k*GW +: GW] = {{4{r_i[(k+2)*RW-1]}}, r_i[(k+1)*RW +: RW]};
      end
    end
    assign v_exact = half_r0 + prod[0 +: ExW] + prod[ExW +: ExW] + prod[2*ExW +: ExW];
  end else begin : g_value
    assign v_exact = half_r0;
    assign node_o[NodeW-1:VW] = '0;
    logic unused_value_only;
    assign unused_value_only = ^{r_i[4*RW-1:RW], u_i, corner_i};
  end
  if (NoiseCorner != pst_pkg::NoiseCornerGrad12) begin : g_unused_hash
    logic unused_hash;
    assign unused_hash = ^hash_i;
  end

  // Corner value to Q3.NodeFrac (the value-table corners).
  if (NoiseCorner == pst_pkg::NoiseCornerGrad12) begin : g_v_grad12
  end else if (VShift > 0) begin : g_v_floor
    assign node_o[0 +: VW] = v_exact[VShift +: VW];
    logic unused_v_low;
    assign unused_v_low = ^v_exact[VShift-1:0];
  end else if (VShift < 0) begin : g_v_shift
    assign node_o[0 +: VW] = {v_exact, {(-VShift){1'b0}}};
  end else begin : g_v_same
    assign node_o[0 +: VW] = v_exact;
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (LF < 1) $error("pst_noise_corner: NoiseLatticeFrac must be >= 1");
  end
  if (NoiseCorner == pst_pkg::NoiseCornerGrad12) begin : g_assert_grad12
    // |v| <= 2 (two components of d, each in [-1, 1]); a and b are different axes.
    always_comb begin
      assert (g_grad12.v12 <= $signed({3'b010, {(LF){1'b0}}}) && g_grad12.v12 >= -$signed({3'b010, {(LF){1'b0}}}))
        else $error("pst_noise_corner: grad12 |v| > 2");
      assert (g_grad12.ax_a != g_grad12.ax_b) else $error("pst_noise_corner: grad12 axes a == b");
    end
  end
  // |v| <= 3.5: the exact value never reaches the Q3 range limits.
  always_comb begin
    assert (v_exact <= $signed({3'b011, 1'b1, {(ExW-4){1'b0}}}) &&
            v_exact >= -$signed({3'b011, 1'b1, {(ExW-4){1'b0}}}))
      else $error("pst_noise_corner: |v| > 3.5");
  end
`endif

endmodule

`default_nettype wire

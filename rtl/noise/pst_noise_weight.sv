// Interpolation weight of one axis of the noise unit (part of rtl/noise/pst_noise.sv, unit 2 of
// docs/HARDWARE.md). Combinational. Golden: pst::noiseFx (model/golden/noise_fx.cpp).
//
// In: u, the unsigned NoiseLatticeFrac-bit (LF) fraction of the lattice cell (U = u 2^LF).
// Out: s = weight of the upper corner and ds = ds/du, both unsigned at LF fraction bits.
//   NoiseInterp = 0 (scurve, Rayshade's SCURVE(u) = u^2 (3 - 2u)):
//     u2 = floor(U * U / 2^LF)                      LF x LF multiplier, LF bits kept
//     s  = floor(u2 * (3 * 2^LF - 2U) / 2^LF)        LF x (LF+2) multiplier; s < 2^LF
//     ds = 6 * (U - u2)                              = 6 u (1 - u) reusing u2: shift-and-add,
//                                                    no third multiplier. U >= u2 always;
//                                                    max(U - u2) = 2^(LF-2) so ds <= 1.5.
//     Errors: s in (s_true - 4 LSB, s_true], ds in [ds_true, ds_true + 6 LSB).
//   NoiseInterp = 1 (linear): s = u, ds = 1 (= 2^LF; the lerp then uses b - a directly).
//   NoiseInterp = 2 (quintic, Perlin 2002's fade 6u^5 - 15u^4 + 10u^3 = u^3 (6u^2 - 15u + 10)):
//     u2 = floor(U * U / 2^LF)                      LF x LF multiplier
//     t3 = floor(u2 * U / 2^LF)                     LF x LF multiplier (u^3)
//     w  = 6 u2 - 15 U + 10 * 2^LF                  shifts and adds; w in (0, 10 * 2^LF]
//     s  = floor(t3 * w / 2^LF)                     LF x (LF+4) multiplier; s < 2^LF
//     a  = U - u2                                   = u (1 - u) in [0, 2^(LF-2)]
//     ds = floor(30 * a * a / 2^LF)                 LF x LF multiplier (a a < 2^(2LF-4)),
//                                                   x30 = x32 - x2; ds <= 1.875 (LF >= 2)
//     Errors: s in (s_true - 11 LSB, s_true], ds in (ds_true - 1, ds_true + 15 + 30/2^LF) LSB.
//
// Reg = 1 (pst_noise's first pipeline register): u and u2 are registered (en_i) between the
// two products (quintic: after u2, before its three other products), so s and ds come one
// advance after u_i; Reg = 0: combinational.
//
// Ports:
//   clk_i, rst_ni, en_i   the pipeline register (Reg = 1)
//   u_i  [LF-1:0]   unsigned fraction
//   s_o  [LF-1:0]   weight, unsigned, LF fraction bits (< 1)
//   ds_o [LF+1:0]   derivative, unsigned, LF fraction bits; two integer bits: <= 1.5 for
//                   LF >= 2, 3 at LF = 1, and 1 (= 2^LF) for linear; quintic <= 1.875
//                   (the contract requires LF >= 2 for it)
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_noise_weight #(
  `PST_WEIGHT_PARAMS,
  parameter bit Reg = 1'b0,
  localparam int LF = NoiseLatticeFrac  // fraction bits of u, s, ds
) (
  input  logic          clk_i,
  input  logic          rst_ni,
  input  logic          en_i,
  input  logic [LF-1:0] u_i,
  output logic [LF-1:0]      s_o,
  output logic [LF+1:0]      ds_o
);

  if (NoiseInterp == pst_pkg::NoiseInterpScurve) begin : g_scurve
    logic [2*LF-1:0] uu;          // U * U, exact
    logic [LF-1:0]   u2_d, u2;    // floor(u^2), LF fraction bits
    logic [LF-1:0]   u_q;         // u beside it
    logic [LF+1:0]   three_m_2u;  // 3 - 2u in (1, 3], LF fraction bits
    logic [2*LF+1:0] su;          // u2 * (3 - 2u), exact, 2 LF fraction bits
    logic [LF+2:0]   ds6;         // 6 (U - u2): 3 bits above LF for the x6

    assign uu = {{LF{1'b0}}, u_i} * {{LF{1'b0}}, u_i};
    assign u2_d = uu[LF +: LF];
    pst_delay #(.Width(2*LF), .Depth(Reg ? 1 : 0)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i ({u_i, u2_d}), .q_o ({u_q, u2})
    );
    assign three_m_2u = {2'b11, {LF{1'b0}}} - {1'b0, u_q, 1'b0};
    assign su = {{(LF+2){1'b0}}, u2} * {{LF{1'b0}}, three_m_2u};
    assign s_o = su[LF +: LF];
    assign ds6 = {2'b00, u_q - u2, 1'b0} + {1'b0, u_q - u2, 2'b00};
    assign ds_o = ds6[LF+1:0];

    logic unused_bits;
    assign unused_bits = ^{uu[LF-1:0], su[LF-1:0], su[2*LF+1:2*LF], ds6[LF+2]};

  end else if (NoiseInterp == pst_pkg::NoiseInterpQuintic) begin : g_quintic
    logic [2*LF-1:0] uu;          // U * U, exact
    logic [LF-1:0]   u2_d, u2;    // floor(u^2)
    logic [LF-1:0]   u_q;         // u beside it (after the register when Reg = 1)
    logic [2*LF-1:0] uuu;         // u2 * U, exact
    logic [LF-1:0]   t3;          // floor(u^3)
    logic [LF+4:0]   w;           // 6 u2 - 15 U + 10: in (0, 10], LF fraction bits
    logic [2*LF+4:0] sw;          // t3 * w, exact (< 2^(2 LF))
    logic [LF-1:0]   a;           // U - u2 = u (1 - u) <= 1/4
    logic [2*LF-1:0] aa;          // a * a, exact
    logic [2*LF+4:0] aa30;        // 30 a a = 32 a a - 2 a a

    assign uu = {{LF{1'b0}}, u_i} * {{LF{1'b0}}, u_i};
    assign u2_d = uu[LF +: LF];
    pst_delay #(.Width(2*LF), .Depth(Reg ? 1 : 0)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i ({u_i, u2_d}), .q_o ({u_q, u2})
    );
    assign uuu = {{LF{1'b0}}, u2} * {{LF{1'b0}}, u_q};
    assign t3 = uuu[LF +: LF];
    // 10 2^LF + 6 u2 - 15 U, every term LF+5 bits wide (the sum is positive: no wrap)
    assign w = {1'b0, 4'b1010, {LF{1'b0}}} + {4'b0, u2, 1'b0} + {3'b0, u2, 2'b0}
             - {1'b0, u_q, 4'b0} + {5'b0, u_q};
    assign sw = {{(LF+5){1'b0}}, t3} * {{LF{1'b0}}, w};
    assign s_o = sw[LF +: LF];
    assign a = u_q - u2;
    assign aa = {{LF{1'b0}}, a} * {{LF{1'b0}}, a};
    assign aa30 = {aa, 5'b0} - {4'b0, aa, 1'b0};
    assign ds_o = aa30[LF +: LF+2];

    logic unused_bits;
    assign unused_bits = ^{uu[LF-1:0], uuu[LF-1:0], sw[LF-1:0], sw[2*LF+4:2*LF],
                           aa30[LF-1:0], aa30[2*LF+4:2*LF+2]};

  end else begin : g_linear
    pst_delay #(.Width(LF), .Depth(Reg ? 1 : 0)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i (u_i), .q_o (s_o)
    );
    assign ds_o = {2'b01, {LF{1'b0}}};
  end

  // Assertions
`ifndef SYNTHESIS
  if (NoiseInterp == pst_pkg::NoiseInterpQuintic) begin : g_assert_quintic
    always_comb begin
      assert (g_quintic.sw[2*LF+4:2*LF] == '0) else $error("pst_noise_weight: quintic s >= 1");
      assert (g_quintic.aa30[2*LF+4:2*LF+2] == '0) else $error("pst_noise_weight: quintic ds >= 4");
      assert (g_quintic.u_q >= g_quintic.u2) else $error("pst_noise_weight: u < u^2");
    end
  end
  if (NoiseInterp == pst_pkg::NoiseInterpScurve) begin : g_assert_scurve
    always_comb begin
      assert (g_scurve.su[2*LF+1:2*LF] == 2'b00) else $error("pst_noise_weight: s >= 1");
      assert (g_scurve.ds6[LF+2] == 1'b0) else $error("pst_noise_weight: ds overflow");
      assert (g_scurve.u_q >= g_scurve.u2) else $error("pst_noise_weight: u < u^2");
    end
  end
`endif

endmodule

`default_nettype wire

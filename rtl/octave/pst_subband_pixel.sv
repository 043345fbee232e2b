// pst_subband_pixel: the pixel's part of the subband unit's anisotropic filter (noise.subband_
// orientations K = 4 or 8; docs/HARDWARE.md unit 2s): for each edge of the pixel (the Jacobian's
// columns ds/dx, ds/dy) and each orientation i, lg of its length along the orientation on the
// plane, |c_i . (j_A0, j_A1)|, with LenRegs registers after the lengths and LgRegs after the lg,
// all enabled by en_i. Golden: subbandPixelLgFx (model/golden/subband_fx.cpp, bit for bit).
//
//   p = floor((C_i j_A0 + S_i j_A1) / 2^SubbandDirFrac), (C_i, S_i) = round(2^8 (cos, sin)(pi i / K))
//   lg_o[e K + i] = corr(pst_fade_lg(|p|))   (|p| < 2^JW: |C_i| + |S_i| <= 2^8 sqrt 2, |j| <= 2^(JW-1))
//   corr: Mitchell's mantissa m (the FadeLgFrac low bits) -> floor(16 lg(1 + (m + 1/2) / 16)), the
//         lg at the centre of the mantissa's step (subbandLgCorrectFx)
//
// Parameters:
//   JacobianInt, JacobianFrac   the Jacobian entry format.
//   NoiseSubband                the plane (pst_pkg::NoiseSubbandXy, Xz or Yz): its axes A0, A1.
//   K                           orientations, 4 or 8.
//   LenRegs, LgRegs             0 or 1 registers after the lengths and after the lg.
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_subband_pixel #(
  `PST_JACOBIAN_PARAMS,
  parameter int NoiseSubband = pst_pkg::NoiseSubbandXz,
  parameter int K            = 4,
  parameter int LenRegs      = 0,
  parameter int LgRegs       = 0,
  localparam int JW  = JacobianInt + JacobianFrac,
  localparam int LgW = pst_pkg::fade_lg_width(JW)   // pst_fade_lg's lg_o
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              en_i,
  input  logic [6*JW-1:0]   j_i,
  output logic [2*K*LgW-1:0] lg_o
);

  localparam int A0 = (NoiseSubband == pst_pkg::NoiseSubbandYz) ? 1 : 0;
  localparam int A1 = (NoiseSubband == pst_pkg::NoiseSubbandXy) ? 1 : 2;
  localparam int DF = pst_pkg::SubbandDirFrac;
  localparam int PW = JW + DF + 2;   // C e0 + S e1 (signed)

  // round(2^8 cos(pi i / K)), round(2^8 sin(pi i / K)) (subbandDirection).
  function automatic int dir_c(input int i);
    if (K == 4) dir_c = (i == 0) ? 256 : (i == 1) ? 181 : (i == 2) ? 0 : -181;
    else dir_c = (i == 0) ? 256 : (i == 1) ? 237 : (i == 2) ? 181 : (i == 3) ? 98 : (i == 4) ? 0 :
                 (i == 5) ? -98 : (i == 6) ? -181 : -237;
  endfunction
  function automatic int dir_s(input int i);
    if (K == 4) dir_s = (i == 0) ? 0 : (i == 2) ? 256 : 181;
    else dir_s = (i == 0) ? 0 : (i == 1) ? 98 : (i == 2) ? 181 : (i == 3) ? 237 : (i == 4) ? 256 :
                 (i == 5) ? 237 : (i == 6) ? 181 : 98;
  endfunction

  logic [2*K*JW-1:0] len_a, len_b;
  for (genvar e = 0; e < 2; e++) begin : g_edge
    logic signed [JW-1:0] e0, e1;
    assign e0 = j_i[(3*e + A0)*JW +: JW];
    assign e1 = j_i[(3*e + A1)*JW +: JW];
    for (genvar i = 0; i < K; i++) begin : g_dir
      logic signed [PW-1:0] prod, p;
      logic [PW-1:0]        mag;
      assign prod = PW'(e0) * PW'(dir_c(i)) + PW'(e1) * PW'(dir_s(i));
      assign p    = prod >>> DF;
      assign mag  = p[PW-1] ? -p : p;
      assign len_a[(e*K + i)*JW +: JW] = mag[JW-1:0];
      logic unused_mag;
      assign unused_mag = ^mag[PW-1:JW];
`ifndef SYNTHESIS
      // |p| < 2^JW (the header's bound): the length fits pst_fade_lg's input.
      always_comb assert (mag[PW-1:JW] == '0 || !rst_ni);
`endif
    end
  end
  pst_delay #(.Width(2*K*JW), .Depth(LenRegs)) u_len (.clk_i, .rst_ni, .en_i, .d_i (len_a), .q_o (len_b));

  // floor(16 lg(1 + (m + 1/2) / 16)) for Mitchell's mantissa m (FadeLgFrac = 4).
  function automatic logic [3:0] corr(input logic [3:0] m);
    case (m)
      4'd0: corr = 4'd0;
      4'd14: corr = 4'd14;
      4'd15: corr = 4'd15;
      default: corr = m + 4'd1;
    endcase
  endfunction

  logic [2*K*LgW-1:0] lg_a;
  for (genvar k = 0; k < 2*K; k++) begin : g_lg
    logic [LgW-1:0] lg_m;
    pst_fade_lg #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_lg (
      .len_i (len_b[k*JW +: JW]), .lg_o (lg_m));
    assign lg_a[k*LgW +: LgW] = {lg_m[LgW-1:4], corr(lg_m[3:0])};
  end
  pst_delay #(.Width(2*K*LgW), .Depth(LgRegs)) u_lgr (.clk_i, .rst_ni, .en_i, .d_i (lg_a), .q_o (lg_o));

  logic unused_j;   // the Jacobian's third axis
  assign unused_j = ^{j_i[(3*0 + 3 - A0 - A1)*JW +: JW], j_i[(3*1 + 3 - A0 - A1)*JW +: JW]};

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (K != 4 && K != 8) $error("pst_subband_pixel: K must be 4 or 8");
    if (pst_pkg::FadeLgFrac != 4) $error("pst_subband_pixel: the lg correction is for FadeLgFrac = 4");
    if (LenRegs < 0 || LenRegs > 1 || LgRegs < 0 || LgRegs > 1) $error("pst_subband_pixel: LenRegs and LgRegs must be 0 or 1");
  end
`endif

endmodule

`default_nettype wire

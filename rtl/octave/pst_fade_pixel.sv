// pst_fade_pixel: the pixel's part of the octave fade (bandlimited octaves, docs/HARDWARE.md
// unit 4): the lengths of the pixel's two edges in texture space (pst_fade_norm of the
// Jacobian's columns ds/dx and ds/dy) and their lg (pst_fade_lg), with LenRegs registers after
// the lengths and LgRegs after the lg, all enabled by en_i. The lanes' fades
// (pst_octave_lane) add each octave's lg ||M_i|| to these.
//
// Parameters:
//   JacobianInt, JacobianFrac  the Jacobian's format (j_i: dsdx then dsdy, 3 elements each).
//   LenRegs, LgRegs            registers after the lengths, after their lg (0 or 1 each).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_fade_pixel #(
  `PST_JACOBIAN_PARAMS,
  parameter int LenRegs      = 0,
  parameter int LgRegs       = 0,
  localparam int JW  = JacobianInt + JacobianFrac,
  localparam int LgW = pst_pkg::fade_lg_width(JW)   // pst_fade_lg's lg_o
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic            en_i,
  input  logic [6*JW-1:0] j_i,
  output logic [LgW-1:0]  lgx_o,
  output logic [LgW-1:0]  lgy_o
);

  logic [JW-1:0]   lenx, leny;
  logic [2*JW-1:0] len_q;
  logic [LgW-1:0]  lgx, lgy;
  pst_fade_norm #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_nx (
    .e_i (j_i[0 +: 3*JW]), .len_o (lenx));
  pst_fade_norm #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_ny (
    .e_i (j_i[3*JW +: 3*JW]), .len_o (leny));
  pst_delay #(.Width(2*JW), .Depth(LenRegs)) u_len (
    .clk_i, .rst_ni, .en_i, .d_i ({leny, lenx}), .q_o (len_q));
  pst_fade_lg #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_lgx (
    .len_i (len_q[0 +: JW]), .lg_o (lgx));
  pst_fade_lg #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_lgy (
    .len_i (len_q[JW +: JW]), .lg_o (lgy));
  pst_delay #(.Width(2*LgW), .Depth(LgRegs)) u_lg (
    .clk_i, .rst_ni, .en_i, .d_i ({lgy, lgx}), .q_o ({lgy_o, lgx_o}));

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (LenRegs < 0 || LenRegs > 1 || LgRegs < 0 || LgRegs > 1) $error("pst_fade_pixel: LenRegs and LgRegs must be 0 or 1");
  end
`endif

endmodule

`default_nettype wire

// pst_top_sva: checker of pst_top's interface: register writes only while idle (the driver's
// rule: registers change between objects, with the pipeline drained), both stream handshakes
// (pst_handshake_sva, with cover points for a refused fragment and a stalled output), idle
// means empty; cover points for back-pressure from the output to the input (the whole
// pipeline full) and a register write right after traffic.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_top_sva #(
  parameter int TB = 1,
  parameter int CW = 1,
  parameter int JW = 1,
  parameter int OutW = 1
) (
  input logic            clk_i,
  input logic            rst_ni,
  input logic            reg_we_i,
  input logic            idle_o,
  input logic            frag_valid_i,
  input logic            frag_ready_o,
  input logic [TB-1:0]   frag_tag_i,
  input logic [3*CW-1:0] frag_s_i,
  input logic [6*JW-1:0] frag_j_i,
  input logic            out_valid_o,
  input logic            out_ready_i,
  input logic [OutW-1:0] out_all   // tag, RGBA, f, grad, W
);
  `PST_ASSERT(RegWriteOnlyWhenIdle, reg_we_i |-> idle_o)
  // The driver keeps an offered fragment until it is taken (an assumption on the source).
  pst_handshake_sva #(.Width(TB + 3*CW + 6*JW)) u_frag (
    .clk_i, .rst_ni, .valid_i (frag_valid_i), .ready_i (frag_ready_o),
    .data_i ({frag_tag_i, frag_s_i, frag_j_i}));
  // A colour offered at the output stays until it is taken.
  pst_handshake_sva #(.Width(OutW)) u_out (
    .clk_i, .rst_ni, .valid_i (out_valid_o), .ready_i (out_ready_i), .data_i (out_all));
  // Idle means empty: with no fragment coming in, nothing comes out next cycle.
  `PST_ASSERT(IdleNothingOut, (idle_o && !frag_valid_i) |=> !out_valid_o)
  `PST_ASSERT(OutNotIdle, out_valid_o |-> !idle_o)
  `PST_ASSERT_KNOWN(IdleKnown, idle_o)

  `PST_COVER(BackPressureFull, out_valid_o && !out_ready_i && frag_valid_i && !frag_ready_o)
  `PST_COVER(InAndOut, frag_valid_i && frag_ready_o && out_valid_o && out_ready_i)
  `PST_COVER(RegWriteAfterTraffic, reg_we_i && $past(!idle_o))
endmodule

bind pst_top pst_top_sva #(.TB(TB), .CW(CW), .JW(JW), .OutW(TB + CB4 + FW + 3*GW + WW)) u_sva (
  .clk_i, .rst_ni, .reg_we_i, .idle_o, .frag_valid_i, .frag_ready_o, .frag_tag_i, .frag_s_i,
  .frag_j_i, .out_valid_o, .out_ready_i,
  .out_all ({out_tag_o, out_rgba_o, out_f_o, out_grad_o, out_w_o}));

`default_nettype wire

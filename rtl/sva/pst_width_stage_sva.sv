// pst_width_stage_sva: checker of pst_width_stage. Assertions: the handshake at the output
// (pst_handshake_sva: W and the side payload held while refused), W before the cap at the maximum
// when the norm overflows, and W out = min(W, wcap) with the width cap (else W). Cover points: W
// saturated at the format's maximum (the norm's overflow, and W at WMax), W = 0, W capped;
// serial: the first and the last step of a fragment.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_width_stage_sva #(
  parameter int WW     = 4,
  parameter int SideW  = 1,
  parameter int SB     = 1,
  parameter bit Serial = 1'b0,
  parameter bit Cap    = 1'b0   // the width cap is built (FilterWidthCap on)
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic             ready_o,
  input logic             valid_o,
  input logic             ready_i,
  input logic [WW-1:0]    w_o,
  input logic [WW-1:0]    w,          // W before the cap
  input logic [WW-1:0]    wcap_i,
  input logic [SideW-1:0] side_o,
  input logic             done,
  input logic [SB-1:0]    step_q,
  input logic             norm_sat   // the norm overflows W's format (aligned with w_o)
);
  localparam logic [WW-1:0] WMax = {WW{1'b1}};
  logic taken;
  assign taken = valid_o && ready_i;

  pst_handshake_sva #(.Width(WW + SideW)) u_out (
    .clk_i, .rst_ni, .valid_i (valid_o), .ready_i, .data_i ({w_o, side_o}));
  `PST_ASSERT(NormSatGivesMax, (valid_o && norm_sat) |-> (w == WMax))
  `PST_ASSERT(CapIsTheMinimum, valid_o |-> (w_o == ((Cap && w > wcap_i) ? wcap_i : w)))
  `PST_ASSERT_KNOWN(ReadyKnown, ready_o)
  `PST_COVER(NormSat, taken && norm_sat)
  `PST_COVER(WMaxOut, taken && w_o == WMax)
  `PST_COVER(WZero, taken && w_o == '0)
  if (Cap) begin : g_cap
    `PST_COVER(Capped, taken && w > wcap_i)
  end
  if (Serial) begin : g_serial
    `PST_COVER(FirstStep, valid_i && !done && step_q == '0)
    `PST_COVER(LastStep, valid_i && done && step_q != '0)
  end else begin : g_parallel
    logic unused;
    assign unused = ^{valid_i, done, step_q};
  end
endmodule

bind pst_width_stage pst_width_stage_sva #(
  .WW(WW), .SideW(SideW), .SB(pst_pkg::StepBits), .Serial(Serial),
  .Cap(FilterWidthCap == pst_pkg::FilterWidthCapOn)
) u_sva (
  .clk_i, .rst_ni, .valid_i, .ready_o, .valid_o, .ready_i, .w_o, .w, .wcap_i, .side_o, .done, .step_q,
  .norm_sat (u_width.nrm[WW]));

`default_nettype wire

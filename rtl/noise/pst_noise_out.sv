// pst_noise_out: the output token stage of a noise unit (pst_noise, pst_subband, pst_worley):
// the unit's last Regs pipeline registers on its result and on the token {valid, step} beside
// it, and the token decoded at the output: valid_o (a step of an evaluation is at the output)
// and last_o (that step is the evaluation's last, NoiseSteps - 1: the result is valid). The
// three units share their output timing through this module (pst_noise_out_sva checks it).
//
// Parameters:
//   Width       bits of the result ({grad, n}).
//   Regs        pipeline registers at the output (0: the result and the token pass through).
//   NoiseSteps  steps of an evaluation (1..8: the token's step has 3 bits): which step last_o
//               marks.
//
// Ports:
//   en_i            the pipeline advances (the registers store)
//   tok_i [3:0]     the token {valid, step} of the result entering the stage
//   data_i          the result entering the stage
//   valid_o, last_o the token at the output: valid, and its step is NoiseSteps - 1
//   data_o          the result at the output (read when last_o)
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_noise_out #(
  parameter int Width      = 1,
  parameter int Regs       = 0,
  `PST_NOISE_STEPS_PARAMS
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             en_i,
  input  logic [3:0]       tok_i,
  input  logic [Width-1:0] data_i,
  output logic             valid_o,
  output logic             last_o,
  output logic [Width-1:0] data_o
);

  logic [3:0] tok_q;   // the token at the output
  pst_delay #(.Width(Width), .Depth(Regs)) u_data (
    .clk_i, .rst_ni, .en_i, .d_i (data_i), .q_o (data_o));
  pst_delay #(.Width(4), .Depth(Regs), .Reset(1'b1)) u_tok (
    .clk_i, .rst_ni, .en_i, .d_i (tok_i), .q_o (tok_q));
  assign valid_o = tok_q[3];
  assign last_o  = tok_q[3] && (32'(tok_q[2:0]) == NoiseSteps - 1);

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (Regs < 0) $error("pst_noise_out: Regs must be >= 0");
    if (NoiseSteps < 1 || NoiseSteps > 8) $error("pst_noise_out: NoiseSteps must be 1..8");
  end
`endif

endmodule

`default_nettype wire

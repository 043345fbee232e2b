// pst_noise_sva: checker of pst_noise's token at its input: steps in range and in order
// (pst_noise_steps_sva), with a cover point per step entering; the token at the output is
// checked by pst_noise_out_sva (bound to the unit's output stage).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_noise_sva #(
  parameter int NoiseSteps = 1
) (
  input logic       clk_i,
  input logic       rst_ni,
  input logic       en_i,
  input logic       valid_i,
  input logic [2:0] step_i
);
  pst_noise_steps_sva #(.NoiseSteps(NoiseSteps)) u_steps (.*);
endmodule

bind pst_noise pst_noise_sva #(.NoiseSteps(NoiseSteps)) u_sva (.*);

`default_nettype wire

// pst_noise_out_sva: checker of pst_noise_out, the output token stage of the three noise units
// (pst_noise, pst_subband, pst_worley): a last token only with a valid one, last_o exactly at
// the evaluation's last step, the token never unknown; a cover point for a token held at the
// output (the unit stalled with an evaluation inside).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_noise_out_sva #(
  parameter int NoiseSteps = 1
) (
  input logic       clk_i,
  input logic       rst_ni,
  input logic       en_i,
  input logic [2:0] step_q,   // the token's step at the output
  input logic       valid_o,
  input logic       last_o
);
  `PST_ASSERT(LastIsValid, last_o |-> valid_o)
  `PST_ASSERT(LastAtLastStep, valid_o |-> (last_o == (32'(step_q) == NoiseSteps - 1)))
  `PST_ASSERT_KNOWN(ValidKnown, {valid_o, last_o})
  `PST_COVER(HeldToken, !en_i && valid_o)
endmodule

bind pst_noise_out pst_noise_out_sva #(.NoiseSteps(NoiseSteps)) u_sva (
  .clk_i, .rst_ni, .en_i, .step_q (tok_q[2:0]), .valid_o, .last_o);

`default_nettype wire

// pst_noise_sva: checker of pst_noise's token: steps in range, a last token only with a valid
// one; a cover point per step entering (every serial step of the noise schedule) and for a
// held token (the unit stalled with an evaluation inside).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_noise_sva #(
  parameter int NoiseSteps = 1
) (
  input logic       clk_i,
  input logic       rst_ni,
  input logic       en_i,
  input logic       valid_i,
  input logic [2:0] step_i,
  input logic       valid_o,
  input logic       last_o
);
  `PST_ASSERT(StepInRange, valid_i |-> (32'(step_i) < NoiseSteps))
  `PST_ASSERT(LastIsValid, last_o |-> valid_o)
  for (genvar j = 0; j < NoiseSteps; j++) begin : g_step
    `PST_COVER(Step, en_i && valid_i && 32'(step_i) == j)
  end
  `PST_COVER(HeldToken, !en_i && valid_o)
endmodule

bind pst_noise pst_noise_sva #(.NoiseSteps(NoiseSteps)) u_sva (.*);

`default_nettype wire

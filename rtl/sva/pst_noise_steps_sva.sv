// pst_noise_steps_sva: the step protocol at a noise unit's input, shared by the three units:
// pst_noise's checker (bound below; the token at its output: pst_noise_out_sva) and part of
// pst_subband_sva and pst_worley_sva: every step in range, and the steps of an evaluation in
// order (0, 1, .. NoiseSteps - 1 on consecutive valid advances: the held nodes, sums and lists
// of the serial units rely on it). A cover point per step entering (every serial step of the
// schedule).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_noise_steps_sva #(
  parameter int NoiseSteps = 1
) (
  input logic       clk_i,
  input logic       rst_ni,
  input logic       en_i,
  input logic       valid_i,
  input logic [2:0] step_i
);
  // The step the next valid advance must carry.
  logic [2:0] next_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) next_q <= '0;
    else if (en_i && valid_i) next_q <= (32'(step_i) == NoiseSteps - 1) ? 3'd0 : step_i + 3'd1;
  end

  `PST_ASSERT(StepInRange, valid_i |-> (32'(step_i) < NoiseSteps))
  `PST_ASSERT(StepsInOrder, (en_i && valid_i) |-> (step_i == next_q))
  for (genvar j = 0; j < NoiseSteps; j++) begin : g_step
    `PST_COVER(Step, en_i && valid_i && 32'(step_i) == j)
  end
endmodule

bind pst_noise pst_noise_steps_sva #(.NoiseSteps(NoiseSteps)) u_sva (.*);

`default_nettype wire

// pst_quadric_serial_sva: checker of pst_quadric_serial: steps are taken in order (a step
// before the last is left only to the next one), done_o exactly from the last step on; a
// cover point per step of the schedule.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_quadric_serial_sva #(
  parameter int NSteps = 1
) (
  input logic       clk_i,
  input logic       rst_ni,
  input logic [4:0] step_i,
  input logic       adv_i,
  input logic       done_o
);
  `PST_ASSERT(StepsInOrder, (adv_i && 32'(step_i) < NSteps - 1) |=> (step_i == $past(step_i) + 5'd1))
  `PST_ASSERT(DoneFromLastStep, done_o == (32'(step_i) >= NSteps - 1))
  for (genvar st = 0; st < NSteps; st++) begin : g_step
    `PST_COVER(Step, adv_i && 32'(step_i) == st)
  end
endmodule

bind pst_quadric_serial pst_quadric_serial_sva #(.NSteps(NSteps)) u_sva (.*);

`default_nettype wire

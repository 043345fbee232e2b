// pst_step_counter_sva: checker of pst_step_counter (the serial stages' step counts): the
// count is zero without a fragment, returns to zero when the fragment leaves, holds while
// the done fragment is refused, and never wraps; cover: a stall at the last step.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_step_counter_sva #(
  parameter int Width = 2
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic             done_i,
  input logic             ready_i,
  input logic [Width-1:0] step_o
);
  `PST_ASSERT(NoWrap, (valid_i && !done_i) |-> (step_o != {Width{1'b1}}))
  `PST_ASSERT(ZeroWhenEmpty, !valid_i |-> (step_o == '0))
  `PST_ASSERT(ZeroAfterLeaving, (valid_i && done_i && ready_i) |=> (step_o == '0))
  `PST_ASSERT(HoldWhileStalled, (valid_i && done_i && !ready_i) |=> (step_o == $past(step_o)))
  `PST_ASSERT(StepsByOne, (valid_i && !done_i) |=> (step_o == $past(step_o) + Width'(1)))
  `PST_ASSERT_KNOWN(StepKnown, step_o)
  `PST_COVER(StalledAtDone, valid_i && done_i && !ready_i)
endmodule

bind pst_step_counter pst_step_counter_sva #(.Width(Width)) u_sva (.*);

`default_nettype wire

// Step counter of a multi-cycle pipeline stage (the serial datapath's octave stage, filter
// width and colour-table filter in pst_top): counts the cycles a fragment has spent in the stage while
// the stage is not done, and returns to 0 when the fragment leaves (done, and the next stage
// ready). With done_i tied high the count stays 0 (a one-cycle stage).
//
// Parameters:
//   Width   bits of the count (the stage's step index).
`default_nettype none

module pst_step_counter #(
  parameter int Width = 2
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,   // a fragment is in the stage
  input  logic             done_i,    // its result is valid this cycle
  input  logic             ready_i,   // the next stage takes it
  output logic [Width-1:0] step_o,
  output logic [Width-1:0] step_next_o   // the count at the next edge
);

  always_comb begin
    step_next_o = step_o;
    if (valid_i && !done_i) step_next_o = step_o + Width'(1);
    else if (valid_i && ready_i) step_next_o = '0;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) step_o <= '0;
    else step_o <= step_next_o;
  end

  // Assertions
`ifndef SYNTHESIS
  // The count never wraps: a stage is done before its last step index.
  assert property (@(posedge clk_i) disable iff (!rst_ni)
                   (valid_i && !done_i) |-> (step_o != {Width{1'b1}}));
`endif

endmodule

`default_nettype wire

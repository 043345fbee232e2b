// Pipeline register: one stage of the valid/ready stream (after PULP common_cells'
// spill-free stream register and FPnew's pipeline pattern).
//
// Parameters:
//   Width  payload bits carried with `valid`.
//
// Handshake: a payload moves when valid and ready are both high. The register accepts a new
// payload whenever the next stage takes the current one or the register is empty:
//   ready_o = ready_i | ~valid_q        (ready[i] = ready[i+1] | ~valid[i+1])
`default_nettype none

module pst_pipe_reg #(
  parameter int Width = 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  output logic             ready_o,
  input  logic [Width-1:0] data_i,
  output logic             valid_o,
  input  logic             ready_i,
  output logic [Width-1:0] data_o
);

  logic             valid_q;
  logic [Width-1:0] data_q;

  assign ready_o = ready_i | ~valid_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else if (ready_o) begin
      valid_q <= valid_i;
    end
  end

  // The payload register has no reset: it is only read while valid_q is set.
  always_ff @(posedge clk_i) begin
    if (ready_o && valid_i) begin
      data_q <= data_i;
    end
  end

  assign valid_o = valid_q;
  assign data_o  = data_q;

  // Assertions
`ifndef SYNTHESIS
  // A payload offered downstream stays put until it is taken.
  property p_stable_until_taken;
    @(posedge clk_i) disable iff (!rst_ni) (valid_o && !ready_i) |=> (valid_o && $stable(data_o));
  endproperty
  assert property (p_stable_until_taken);
`endif

endmodule

`default_nettype wire

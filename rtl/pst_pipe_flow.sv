// Flow control of a pipelined stage (pst_width_stage and pst_colour_stage, pipelined): the
// fragment's valid bit and its side payload travel Depth registers beside the datapath's own
// pst_delay registers, all advanced by en_o; the whole pipeline stalls (en_o = 0) only while
// its last register holds a fragment the next stage refuses; busy_o while any register holds
// one (pst_top's idle).
//
// Parameters:
//   Depth  register stages of the datapath this flow control runs (>= 1).
//   SideW  bits carried beside the fragment (side_i -> side_o).
`default_nettype none

module pst_pipe_flow #(
  parameter int Depth = 1,
  parameter int SideW = 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  output logic             ready_o,
  input  logic [SideW-1:0] side_i,
  output logic             valid_o,
  input  logic             ready_i,
  output logic [SideW-1:0] side_o,
  output logic             en_o,     // the pipeline advances this cycle
  output logic             busy_o    // a fragment is in the registers
);

  logic en;
  logic valid_e;
  assign en      = ~(valid_e & ~ready_i);
  assign en_o    = en;
  assign ready_o = en;
  assign valid_o = valid_e;
  pst_delay #(.Width(1), .Depth(Depth), .Reset(1'b1)) u_valid (
    .clk_i, .rst_ni, .en_i (en), .d_i (valid_i), .q_o (valid_e));
  pst_delay #(.Width(SideW), .Depth(Depth)) u_side (
    .clk_i, .rst_ni, .en_i (en), .d_i (side_i), .q_o (side_o));

  // Fragments in the registers: + one entering, - one leaving, at each advance.
  localparam int IW = $clog2(Depth + 2);
  logic [IW-1:0] inflight_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) inflight_q <= '0;
    else if (en) inflight_q <= inflight_q + IW'(valid_i) - IW'(valid_e);
  end
  assign busy_o = (inflight_q != '0);

  // Assertions
`ifndef SYNTHESIS
  initial begin
    // a stage without registers uses its own hold branch, not this module
    assert (Depth >= 1) else $error("pst_pipe_flow: Depth %0d < 1", Depth);
  end
`endif

endmodule

`default_nettype wire

// pst_pipe_flow: the flow control of a stage of pst_top (the octave stage's serial datapath,
// pst_width_stage, pst_colour_stage), in one of two forms by Depth:
//   Depth = 0 (hold): the fragment stays in the stage while it steps (adv_o = valid_i & ~done_i)
//             and is offered at its last step (valid_o = valid_i & done_i), leaving when the next
//             stage takes it (ready_o); move_o: the fragment steps or leaves this cycle;
//             side_o = side_i, busy_o = 0.
//   Depth >= 1 (pipelined): the fragment's valid bit and its side payload travel Depth
//             registers beside the datapath's own pst_delay registers, all advanced by adv_o
//             (= move_o); the whole pipeline stalls only while its last register holds a
//             fragment the next stage refuses; busy_o while any register holds one (pst_top's
//             idle). done_i is unused (a pipelined stage takes a fragment every cycle).
//
// Parameters:
//   Depth  register stages of the datapath this flow control runs (0: hold).
//   SideW  bits carried beside the fragment (side_i -> side_o).
`default_nettype none

module pst_pipe_flow #(
  parameter int Depth = 1,
  parameter int SideW = 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  input  logic             done_i,   // hold: the fragment's result is valid this cycle
  output logic             ready_o,
  input  logic [SideW-1:0] side_i,
  output logic             valid_o,
  input  logic             ready_i,
  output logic [SideW-1:0] side_o,
  output logic             adv_o,    // the datapath steps (hold) / the pipeline advances
  output logic             move_o,   // hold: a step or the fragment leaves; pipelined: adv_o
  output logic             busy_o    // a fragment is in the registers
);

  if (Depth == 0) begin : g_hold
    assign adv_o   = valid_i & ~done_i;
    assign move_o  = valid_i & (~done_i | ready_i);
    assign ready_o = done_i & ready_i;
    assign valid_o = valid_i & done_i;
    assign side_o  = side_i;
    assign busy_o  = 1'b0;
    logic unused_clk;
    assign unused_clk = ^{clk_i, rst_ni};
  end else begin : g_pipe
    logic en;
    logic valid_e;
    assign en      = ~(valid_e & ~ready_i);
    assign adv_o   = en;
    assign move_o  = en;
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
    logic unused_done;
    assign unused_done = done_i;
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (Depth >= 0) else $error("pst_pipe_flow: Depth %0d < 0", Depth);
  end
`endif

endmodule

`default_nettype wire

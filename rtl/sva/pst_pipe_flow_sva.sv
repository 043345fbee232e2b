// pst_pipe_flow_sva: checker of pst_pipe_flow (the stages' flow control): the handshake on
// both sides (pst_handshake_sva; the source side has no payload here), busy_o while a pipelined stage offers a fragment, no advance while the end is
// refused; cover points for a stall with a fragment waiting upstream and for streaming.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_pipe_flow_sva #(
  parameter int Depth = 1,
  parameter int SideW = 1
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic             ready_o,
  input logic             valid_o,
  input logic             ready_i,
  input logic [SideW-1:0] side_o,
  input logic             adv_o,
  input logic             busy_o
);
  pst_handshake_sva #(.Width(SideW)) u_out (
    .clk_i, .rst_ni, .valid_i (valid_o), .ready_i, .data_i (side_o));
  // The source keeps an offer the pipeline refuses; a refused end stalls the pipeline.
  pst_handshake_sva #(.Width(1)) u_in (
    .clk_i, .rst_ni, .valid_i, .ready_i (ready_o), .data_i (1'b0));
  `PST_ASSERT(StallWhenRefused, (valid_o && !ready_i) |-> !adv_o)
  `PST_ASSERT(BusyWhileOffering, valid_o |-> (busy_o || Depth == 0))
  `PST_COVER(StalledWithInput, valid_o && !ready_i && valid_i)
  `PST_COVER(Streaming, valid_i && valid_o && ready_i)
endmodule

bind pst_pipe_flow pst_pipe_flow_sva #(.Depth(Depth), .SideW(SideW)) u_sva (.*);

`default_nettype wire

// pst_pipe_reg_sva: checker of pst_pipe_reg (bound to every instance): the valid/ready
// handshake on both sides (pst_handshake_sva), and cover points for back-pressure while full, full throughput and
// a bubble. Ports only (the register's own rule, ready_o = ready_i | ~valid_q, may change).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_pipe_reg_sva #(
  parameter int Width = 1
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic             ready_o,
  input logic [Width-1:0] data_i,
  input logic             valid_o,
  input logic             ready_i,
  input logic [Width-1:0] data_o
);
  // Downstream: an offered payload stays put until it is taken.
  pst_handshake_sva #(.Width(Width)) u_out (
    .clk_i, .rst_ni, .valid_i (valid_o), .ready_i, .data_i (data_o));
  // Upstream (the source's side of the protocol): an offer is kept until it is taken.
  pst_handshake_sva #(.Width(Width)) u_in (
    .clk_i, .rst_ni, .valid_i, .ready_i (ready_o), .data_i);
  // Back-pressure while full: a payload waits and the source offers the next one.
  `PST_COVER(BackPressureFull, valid_o && !ready_i && valid_i)
  // Full throughput: one payload in and one out in the same cycle.
  `PST_COVER(InAndOut, valid_i && ready_o && valid_o && ready_i)
  // A bubble: empty while the source offers nothing.
  `PST_COVER(Bubble, !valid_o && !valid_i)
endmodule

bind pst_pipe_reg pst_pipe_reg_sva #(.Width(Width)) u_sva (.*);

`default_nettype wire

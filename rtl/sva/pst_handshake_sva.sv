// pst_handshake_sva: the valid/ready handshake of one stream boundary, written once and
// instantiated by the checker of every module with a valid/ready port pair (pst_pipe_reg,
// pst_pipe_flow, the octave datapaths, pst_octave_stage, pst_width_stage, pst_colour_stage,
// pst_top: its output side, and the input side where the source is outside the module).
// Assertions (names prefixed by the instance): an offer is kept, with its payload, until it is
// taken; valid and ready are never unknown; nor is an offered payload. Cover points: a refused
// offer (back-pressure) and a taken one.
//
// Parameters:
//   Width  payload bits held with the offer (data_i; a boundary without a payload ties one
//          constant bit).
//
// Ports (all inputs: the boundary's wires as the producer and consumer see them):
//   valid_i  the producer offers a payload
//   ready_i  the consumer takes it (the transfer: valid_i && ready_i on a clock edge)
//   data_i   the payload, read at the transfer
`include "sva/pst_assert.svh"
`default_nettype none

module pst_handshake_sva #(
  parameter int Width = 1
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic             ready_i,
  input logic [Width-1:0] data_i
);
  // An offer stays, and its payload with it, until the consumer takes it.
  `PST_ASSERT(HeldUntilTaken, (valid_i && !ready_i) |=> (valid_i && $stable(data_i)))
  `PST_ASSERT_KNOWN(HandshakeKnown, {valid_i, ready_i})
  `PST_ASSERT(DataKnown, valid_i |-> !$isunknown(data_i))
  `PST_COVER(Refused, valid_i && !ready_i)
  `PST_COVER(Taken, valid_i && ready_i)
endmodule

`default_nettype wire

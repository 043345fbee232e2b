// pst_delay_sva: checker of every pst_delay (pipeline registers and token delay lines): the
// output holds while the pipeline does not advance; one register takes d_i on an advance; no
// register (Depth 0) is a wire. Resetting lines (tokens) have no X after reset.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_delay_sva #(
  parameter int Width = 1,
  parameter int Depth = 1,
  parameter bit Reset = 1'b0
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             en_i,
  input logic [Width-1:0] d_i,
  input logic [Width-1:0] q_o
);
  if (Depth == 0) begin : g_wire
    always_comb begin
      `PST_ASSERT_I(Wire, q_o == d_i)
    end
    logic unused_ctl;
    assign unused_ctl = ^{clk_i, rst_ni, en_i};
  end else begin : g_regs
    `PST_ASSERT(HoldWhenStalled, !en_i |=> $stable(q_o))
    if (Depth == 1) begin : g_one
      `PST_ASSERT(TakeOnAdvance, en_i |=> (q_o == $past(d_i)))
    end else begin : g_more
      logic unused_d;   // Depth > 1: the registers between d_i and q_o are inside pst_delay
      assign unused_d = ^d_i;
    end
    if (Reset) begin : g_reset
      `PST_ASSERT_KNOWN(TokenKnown, q_o)
    end
  end
endmodule

bind pst_delay pst_delay_sva #(.Width(Width), .Depth(Depth), .Reset(Reset)) u_sva (.*);

`default_nettype wire

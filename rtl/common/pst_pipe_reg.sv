// Pipeline register: one stage of the valid/ready stream (after PULP common_cells' stream
// register and spill_register).
//
// Parameters:
//   Width  payload bits carried with `valid`.
//   Skid   0: one register, ready_o = ready_i | ~valid_q (the downstream ready passes through
//          combinationally: ready[i] = ready[i+1] | ~valid[i+1]).
//          1: a skid buffer with a registered ready: two entries, A and B, so ready_o is a
//          function of this register's own flip-flops and the downstream ready_i stops here
//          (pst_top uses it on the parallel datapath, where each stage's stall enable fans out
//          to thousands of pipeline flip-flops: docs/HARDWARE.md).
//
// Handshake: a payload moves when valid and ready are both high. Skid = 1: a payload enters
// A; the output is B's when B is full, else A's; while the output is refused, A's payload
// moves to B (the skid), so one more payload can still be taken after the stall became
// visible: ready_o = ~a_full | ~b_full (no path from ready_i). Both: a payload every cycle,
// one cycle of latency.
`default_nettype none

module pst_pipe_reg #(
  parameter int Width = 1,
  parameter bit Skid  = 1'b0
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

  if (!Skid) begin : g_reg
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

  end else begin : g_skid
    logic             a_full_q, b_full_q;
    logic [Width-1:0] a_data_q, b_data_q;
    logic             a_fill, a_drain, b_fill, b_drain;

    // A takes the input whenever the register is ready; it drains (to the output or into B)
    // whenever B is empty.
    assign a_fill  = valid_i & ready_o;
    assign a_drain = a_full_q & ~b_full_q;
    // B takes A's payload when the output refuses it; it drains when the output takes it.
    assign b_fill  = a_drain & ~ready_i;
    assign b_drain = b_full_q & ready_i;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        a_full_q <= 1'b0;
        b_full_q <= 1'b0;
      end else begin
        if (a_fill || a_drain) a_full_q <= a_fill;
        if (b_fill || b_drain) b_full_q <= b_fill;
      end
    end

    // The payload registers have no reset: they are only read while their full bit is set.
    always_ff @(posedge clk_i) begin
      if (a_fill) a_data_q <= data_i;
      if (b_fill) b_data_q <= a_data_q;
    end

    assign ready_o = ~a_full_q | ~b_full_q;
    assign valid_o = a_full_q | b_full_q;
    assign data_o  = b_full_q ? b_data_q : a_data_q;
  end

  // Assertions: the handshake on both sides is checked by pst_pipe_reg_sva (rtl/sva/, bound to
  // every instance).

endmodule

`default_nettype wire

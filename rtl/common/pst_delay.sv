// Pipeline delay: Depth registers in a row, all enabled by en_i (the pipeline's advance), so
// d_i comes out at q_o Depth advances later; Depth = 0 is a wire. The stage registers of the
// pipelined blocks (pst_noise, pst_octave_stage, pst_quadric, pst_filter_width,
// pst_clut_filter) and the delay lines that carry a token beside them are this module.
//
// Parameters:
//   Width  bits carried.
//   Depth  registers (0: combinational pass-through).
//   Reset  1: the registers reset to zero (tokens: valid bits); 0: no reset (payload, only
//          read while its token is valid).
`default_nettype none

module pst_delay #(
  parameter int Width = 1,
  parameter int Depth = 1,
  parameter bit Reset = 1'b0
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             en_i,
  input  logic [Width-1:0] d_i,
  output logic [Width-1:0] q_o
);

  if (Depth == 0) begin : g_wire
    assign q_o = d_i;
    logic unused_ctl;
    assign unused_ctl = ^{clk_i, rst_ni, en_i};
  end else begin : g_regs
    // The last register (q_o) apart from the ones before it (q: register k at
    // [k*Width +: Width], k < Depth - 1): an assertion's $past/$stable of q_o then samples
    // Width bits, not the whole line (Verilator 5.006 emits the sampled copy of a vector over
    // about 40 words as a loop whose index it does not declare).
    localparam int LW = (Depth > 1) ? (Depth - 1) * Width : 1;   // Depth = 1: one constant bit
    logic [LW-1:0]    q, d;
    logic [Width-1:0] last_q, last_d;
    if (Depth > 2) begin : g_shift
      assign d = {q[0 +: (Depth-2)*Width], d_i};
      assign last_d = q[(Depth-2)*Width +: Width];
    end else if (Depth == 2) begin : g_two
      assign d = d_i;
      assign last_d = q;
    end else begin : g_one
      assign d = '0;
      assign last_d = d_i;
      logic unused_q;
      assign unused_q = q;
    end
    if (Reset) begin : g_reset
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) {q, last_q} <= '0;
        else if (en_i) {q, last_q} <= {d, last_d};
      end
    end else begin : g_noreset
      always_ff @(posedge clk_i) begin
        if (en_i) {q, last_q} <= {d, last_d};
      end
      logic unused_rst;
      assign unused_rst = rst_ni;
    end
    assign q_o = last_q;
  end

endmodule

`default_nettype wire

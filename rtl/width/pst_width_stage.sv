// pst_width_stage: the filter-width stage of pst_top (docs/HARDWARE.md unit 5) around
// pst_filter_width: W = |grad_x f| N from grad f and the Jacobian of the fragment in [B].
// Parallel: one cycle. Serial: the unit's steps (pst_pkg::WidthProducts products, then the
// euclidean norm's squares and root), counted here; the fragment leaves [B] at the last step
// (valid_o), when the next stage takes it (ready_o = done & ready_i).
// Pipelined (parallel, WidthRegs > 0: the profile's pipeline.width_regs): the fragment leaves
// [B] at once into pst_filter_width's registers with side_i (what [C] needs besides W) beside
// it; valid_o, side_o come WidthRegs cycles later, and the pipeline stalls while [C] refuses
// its end (busy_o: a fragment is in the registers).
//
// Width cap (FilterWidthCap = on, the profile's filter.width_cap): w_o = min(W, wcap_i), one
// comparator and multiplexer after pst_filter_width's last step (docs/HARDWARE.md unit 5);
// wcap_i is a register (pst_regs), steady while fragments flow. Off: w_o = W, wcap_i unused.
//
// Parameters: the profile's formats and choices (pst_top's header).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_width_stage #(
  `PST_WIDTH_STAGE_PARAMS,
  parameter int SideW        = 1,
  localparam int GW = GradInt + GradFrac,
  localparam int JW = JacobianInt + JacobianFrac,
  localparam int WW = pst_pkg::w_width(Log2Clut, WidthFrac)
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic            valid_i,
  output logic            ready_o,
  input  logic [3*GW-1:0] grad_i,
  input  logic [6*JW-1:0] j_i,
  input  logic [SideW-1:0] side_i,   // carried to side_o with the fragment
  output logic            valid_o,
  input  logic            ready_i,
  input  logic [WW-1:0]   wcap_i,   // the width cap (FilterWidthCap on; register wcap)
  output logic [WW-1:0]   w_o,
  output logic [SideW-1:0] side_o,
  output logic            busy_o
);

  localparam bit Serial = (Datapath == pst_pkg::DatapathSerial);
  localparam int Regs   = Serial ? 0 : WidthRegs;

  logic                         done;   // W is valid this cycle
  logic [pst_pkg::StepBits-1:0] step_q;
  logic [pst_pkg::StepBits-1:0] unused_step_next;
  pst_step_counter #(.Width(pst_pkg::StepBits)) u_step (
    .clk_i, .rst_ni, .valid_i, .done_i (done), .ready_i, .step_o (step_q), .step_next_o (unused_step_next)
  );

  logic [WW-1:0] w;   // W = |grad_x f| N, before the cap
  pst_filter_width #(`PST_FILTER_WIDTH_PASS, .Serial(Serial), .Regs(Regs)) u_width (
    .clk_i, .rst_ni, .step_i (step_q), .adv_i (valid_i & ~done), .en_i (en), .done_o (done),
    .grad_i, .j_i, .w_o (w)
  );

  if (FilterWidthCap == pst_pkg::FilterWidthCapOn) begin : g_cap
    assign w_o = (w > wcap_i) ? wcap_i : w;
  end else begin : g_no_cap
    assign w_o = w;
    logic unused_wcap;
    assign unused_wcap = ^wcap_i;
  end

  logic en;   // the pipeline advances (Regs > 0)
  logic unused_move;
  pst_pipe_flow #(.Depth(Regs), .SideW(SideW)) u_flow (
    .clk_i, .rst_ni, .valid_i, .done_i (done), .ready_o, .side_i, .valid_o, .ready_i, .side_o,
    .adv_o (en), .move_o (unused_move), .busy_o);

endmodule

`default_nettype wire

// pst_colour_stage: the colour-table stage of pst_top (docs/HARDWARE.md unit 6) around
// pst_clut_filter: RGBA from f and W of the fragment in [C]. Parallel: one cycle. Serial: one
// channel per cycle (pst_pkg::ColourSteps steps, counted here); the fragment leaves [C] at
// the last (valid_o), when the next stage takes it. The tables are written through the
// register port (we_i, addr_i, wdata_i).
// Pipeline registers (ColourRegs, the profile's pipeline.colour_regs; pst_clut_filter's Regs):
// parallel: the fragment leaves [C] at once into them with side_i beside it, valid_o and
// side_o come ColourRegs cycles later and the pipeline stalls while [D] refuses its end
// (busy_o: a fragment is in the registers); serial: ColourSteps + ColourRegs steps in [C].
//
// Parameters: the profile's formats and choices (pst_top's header).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_colour_stage #(
  `PST_COLOUR_STAGE_PARAMS,
  parameter int SideW           = 1,
  localparam int FW  = FInt + FFrac,
  localparam int WW  = pst_pkg::w_width(Log2Clut, WidthFrac),
  localparam int CB4 = 4 * ColourBits,
  localparam int KB  = pst_pkg::RegControlKindWidth
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  input  logic                            we_i,
  input  logic [pst_pkg::RegAddrBits-1:0] addr_i,
  input  logic [pst_pkg::RegDataBits-1:0] wdata_i,
  input  logic                            clamp_i,
  input  logic [KB-1:0]                   kind_i,
  input  logic                            valid_i,
  output logic                            ready_o,
  input  logic [FW-1:0]                   f_i,
  input  logic [WW-1:0]                   w_i,
  input  logic [SideW-1:0]                side_i,   // carried to side_o with the fragment
  output logic                            valid_o,
  input  logic                            ready_i,
  output logic [CB4-1:0]                  rgba_o,
  output logic [SideW-1:0]                side_o,
  output logic                            busy_o
);

  localparam bit Serial = (Datapath == pst_pkg::DatapathSerial);
  localparam int SB = $clog2(pst_pkg::ColourSteps + ColourRegs);
  logic          done;   // RGBA is valid this cycle
  logic [SB-1:0] step_q;
  logic          en;     // pst_clut_filter's registers advance
  assign done = !Serial || (step_q == SB'(pst_pkg::ColourSteps - 1 + ColourRegs));
  logic [SB-1:0] unused_step_next;
  pst_step_counter #(.Width(SB)) u_step (
    .clk_i, .rst_ni, .valid_i, .done_i (done), .ready_i, .step_o (step_q), .step_next_o (unused_step_next)
  );

  pst_clut_filter #(`PST_CLUT_FILTER_PASS, .Regs(ColourRegs)) u_clut (
    .clk_i, .we_i, .addr_i, .wdata_i, .f_i, .w_i, .clamp_i, .kind_i, .rst_ni,
    .step_i (step_q), .adv_i (valid_i & ~done), .en_i (en), .rgba_o
  );

  logic unused_move;
  pst_pipe_flow #(.Depth(Serial ? 0 : ColourRegs), .SideW(SideW)) u_flow (
    .clk_i, .rst_ni, .valid_i, .done_i (done), .ready_o, .side_i, .valid_o, .ready_i, .side_o,
    .adv_o (en), .move_o (unused_move), .busy_o);

endmodule

`default_nettype wire

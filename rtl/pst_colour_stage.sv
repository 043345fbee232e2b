// pst_colour_stage: the colour-table stage of pst_top (docs/HARDWARE.md stage 6) around
// pst_clut_filter: RGBA from f and W of the fragment in [C]. Parallel: one cycle. Serial: one
// channel per cycle (pst_pkg::ColourSteps steps, counted here); the fragment leaves [C] at
// the last (valid_o), when the next stage takes it. The tables are written through the
// register port (we_i, addr_i, wdata_i).
//
// Parameters: the profile's formats and choices (pst_top's header).
`include "pst_pkg.sv"
`default_nettype none

module pst_colour_stage #(
  parameter int Datapath        = pst_pkg::DatapathDefault,
  parameter int FInt            = pst_pkg::FIntDefault,
  parameter int FFrac           = pst_pkg::FFracDefault,
  parameter int Log2Clut        = pst_pkg::Log2ClutDefault,
  parameter int ColourBits      = pst_pkg::ColourBitsDefault,
  parameter int WidthFrac       = pst_pkg::WidthFracDefault,
  parameter int FilterRecipFrac = pst_pkg::FilterRecipFracDefault,
  localparam int FW  = FInt + FFrac,
  localparam int WW  = Log2Clut + pst_pkg::WidthExtraIntBits + WidthFrac,
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
  output logic                            valid_o,
  input  logic                            ready_i,
  output logic [CB4-1:0]                  rgba_o
);

  localparam int SB = pst_pkg::ColourStepBits;
  logic          done;   // RGBA is valid this cycle
  logic [SB-1:0] step_q;
  assign done = (Datapath == pst_pkg::DatapathParallel) || (step_q == SB'(pst_pkg::ColourSteps - 1));
  pst_step_counter #(.Width(SB)) u_step (
    .clk_i, .rst_ni, .valid_i, .done_i (done), .ready_i, .step_o (step_q)
  );

  pst_clut_filter #(
    .FInt(FInt), .FFrac(FFrac), .Log2Clut(Log2Clut), .ColourBits(ColourBits),
    .WidthFrac(WidthFrac), .FilterRecipFrac(FilterRecipFrac), .Datapath(Datapath)
  ) u_clut (
    .clk_i, .we_i, .addr_i, .wdata_i, .f_i, .w_i, .clamp_i, .kind_i, .rst_ni,
    .step_i (step_q), .adv_i (valid_i & ~done), .rgba_o
  );

  assign valid_o = valid_i & done;
  assign ready_o = done & ready_i;

endmodule

`default_nettype wire

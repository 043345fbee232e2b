// pst_octave_stage_sva: checker of pst_octave_stage's hand-over to [B]. Assertions: the
// handshake (pst_handshake_sva: the result held while refused, f, grad f and the side payload
// with it, never unknown). Cover points: f and each grad f component at the top and bottom of
// their formats, the quadric at its format's extremes, 0 / some / all octaves active. The datapaths' schedules are checked by pst_octave_datapath_sva, the saturation of
// the sums by pst_octave_accum_sva.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_octave_stage_sva #(
  parameter int  Octaves    = 1,
  parameter int  OctBits    = 1,
  parameter int  FW         = 1,
  parameter int  GW         = 1,
  parameter int  SideW      = 1
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                valid_i,
  input logic                ready_o,
  input logic                valid_o,
  input logic                ready_i,
  input logic [FW-1:0]       f_o,
  input logic [3*GW-1:0]     grad_o,
  input logic [SideW-1:0]    side_o,
  input logic [OctBits-1:0]  active_i,
  input logic [FW-1:0]       q_e
);
  localparam logic [FW-1:0] FMax = {1'b0, {(FW-1){1'b1}}};
  localparam logic [FW-1:0] FMin = {1'b1, {(FW-1){1'b0}}};
  localparam logic [GW-1:0] GMax = {1'b0, {(GW-1){1'b1}}};
  localparam logic [GW-1:0] GMin = {1'b1, {(GW-1){1'b0}}};
  logic taken;
  assign taken = valid_o && ready_i;

  pst_handshake_sva #(.Width(FW + 3*GW + SideW)) u_out (
    .clk_i, .rst_ni, .valid_i (valid_o), .ready_i, .data_i ({f_o, grad_o, side_o}));
  `PST_ASSERT_KNOWN(ReadyKnown, ready_o)

  `PST_COVER(FAtMax, taken && f_o == FMax)
  `PST_COVER(FAtMin, taken && f_o == FMin)
  for (genvar k = 0; k < 3; k++) begin : g_grad
    `PST_COVER(GradAtMax, taken && grad_o[k*GW +: GW] == GMax)
    `PST_COVER(GradAtMin, taken && grad_o[k*GW +: GW] == GMin)
  end
  // The quadric's own saturation (q at an extreme of the F format).
  `PST_COVER(QuadricSatHigh, taken && q_e == FMax)
  `PST_COVER(QuadricSatLow, taken && q_e == FMin)

  `PST_COVER(NoActiveOctaves, taken && active_i == '0)
  `PST_COVER(SomeActiveOctaves, taken && active_i != '0 && 32'(active_i) < Octaves)
  `PST_COVER(AllActiveOctaves, taken && 32'(active_i) == Octaves)

  logic unused;
  assign unused = valid_i;
endmodule

bind pst_octave_stage pst_octave_stage_sva #(
  .Octaves(Octaves), .OctBits(OctBits), .FW(FW), .GW(GW), .SideW(SideW)
) u_sva (.*);

`default_nettype wire

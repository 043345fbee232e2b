// pst_octave_accum_sva: checker of pst_octave_accum (the sums of the octave stage).
// Assertions: a sum above / below its format gives that format's extreme (f and each grad f
// component), every cycle. Cover points: each saturated high and low (pst_octave_stage_sva
// covers the saturated values at a fragment's result).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_octave_accum_sva #(
  parameter int FW    = 1,
  parameter int GW    = 1,
  parameter int FAccW = 2,
  parameter int GAccW = 2
) (
  input logic               clk_i,
  input logic               rst_ni,
  input logic [FW-1:0]      f_o,
  input logic [3*GW-1:0]    grad_o,
  input logic [FAccW-1:0]   fout,
  input logic [3*GAccW-1:0] gout
);
  localparam logic [FW-1:0] FMax = {1'b0, {(FW-1){1'b1}}};
  localparam logic [FW-1:0] FMin = {1'b1, {(FW-1){1'b0}}};
  localparam logic [GW-1:0] GMax = {1'b0, {(GW-1){1'b1}}};
  localparam logic [GW-1:0] GMin = {1'b1, {(GW-1){1'b0}}};

  logic f_hi, f_lo;
  assign f_hi = $signed(fout) > $signed(FAccW'($signed(f_o)));
  assign f_lo = $signed(fout) < $signed(FAccW'($signed(f_o)));
  `PST_ASSERT(FSatHighIsMax, f_hi |-> (f_o == FMax))
  `PST_ASSERT(FSatLowIsMin, f_lo |-> (f_o == FMin))
  `PST_COVER(FSatHigh, f_hi)
  `PST_COVER(FSatLow, f_lo)
  for (genvar k = 0; k < 3; k++) begin : g_grad
    logic g_hi, g_lo;
    assign g_hi = $signed(gout[k*GAccW +: GAccW]) > $signed(GAccW'($signed(grad_o[k*GW +: GW])));
    assign g_lo = $signed(gout[k*GAccW +: GAccW]) < $signed(GAccW'($signed(grad_o[k*GW +: GW])));
    `PST_ASSERT(GradSatHighIsMax, g_hi |-> (grad_o[k*GW +: GW] == GMax))
    `PST_ASSERT(GradSatLowIsMin, g_lo |-> (grad_o[k*GW +: GW] == GMin))
    `PST_COVER(GradSatHigh, g_hi)
    `PST_COVER(GradSatLow, g_lo)
  end
endmodule

bind pst_octave_accum pst_octave_accum_sva #(.FW(FW), .GW(GW), .FAccW(FAccW), .GAccW(GAccW)) u_sva (.*);

`default_nettype wire

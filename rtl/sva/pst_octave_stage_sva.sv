// pst_octave_stage_sva: checker of pst_octave_stage. Assertions: the cycle counter stays in
// range, is zero without a fragment and holds while the result is refused (f, grad f and the
// side payload with it); the noise schedule's step and pass in range; the serial rows in
// range. Cover points: f and each grad f component saturated high and low, the quadric at its
// format's extremes, each pass's last noise step, the result stalled, 0 / some / all octaves
// active, and (serial) every transform and term row and a fragment waiting for the quadric.
// Bound with the stage's schedule signals (cyc_q, noise_on, npass, nstep, the serial rows) and
// the unsaturated sums (fout, gout).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_octave_stage_sva #(
  parameter int  Octaves    = 1,
  parameter int  NoiseSteps = 1,
  parameter int  Passes     = 1,
  parameter int  PassBits   = 1,
  parameter int  Cycles     = 1,
  parameter int  CycMax     = 1,
  parameter int  CycBits    = 1,
  parameter int  OctBits    = 1,
  parameter int  SR         = 3,
  parameter bit  Serial     = 1'b0,
  parameter int  FW         = 1,
  parameter int  GW         = 1,
  parameter int  FAccW      = 2,
  parameter int  GAccW      = 2,
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
  input logic [CycBits-1:0]  cyc_q,
  input logic                last_cycle,
  input logic                quad_done,
  input logic                noise_on,
  input logic [PassBits-1:0] npass,
  input logic [2:0]          nstep,
  input logic                xf_on,
  input logic [1:0]          xrow,
  input logic                tm_on,
  input logic [1:0]          trow,
  input logic [FW-1:0]       q_e,
  input logic [FAccW-1:0]    fout,
  input logic [3*GAccW-1:0]  gout
);
  localparam logic [FW-1:0] FMax = {1'b0, {(FW-1){1'b1}}};
  localparam logic [FW-1:0] FMin = {1'b1, {(FW-1){1'b0}}};
  localparam logic [GW-1:0] GMax = {1'b0, {(GW-1){1'b1}}};
  localparam logic [GW-1:0] GMin = {1'b1, {(GW-1){1'b0}}};
  logic taken;
  assign taken = valid_o && ready_i;

  `PST_ASSERT(CycInRange, 32'(cyc_q) < CycMax)
  `PST_ASSERT(CycZeroWhenEmpty, !valid_i |-> (cyc_q == '0))
  `PST_ASSERT(ResultHeldWhileRefused, (valid_o && !ready_i) |=>
                                      (valid_o && $stable(cyc_q) && $stable({f_o, grad_o, side_o})))
  `PST_ASSERT(NoiseStepInRange, noise_on |-> (32'(nstep) < NoiseSteps && 32'(npass) < Passes))
  `PST_ASSERT(ReadyOnlyAtLast, (valid_i && ready_o) |-> (32'(cyc_q) + 1 >= Cycles))
  `PST_ASSERT_KNOWN(HandshakeKnown, {valid_o, ready_o})
  `PST_ASSERT(ResultKnown, valid_o |-> !$isunknown({f_o, grad_o}))

  // Saturation: the sum above / below the format (pst_floor_sat's own checker asserts the
  // extremes it gives then).
  logic f_hi, f_lo;
  assign f_hi = $signed(fout) > $signed(FAccW'($signed(f_o)));
  assign f_lo = $signed(fout) < $signed(FAccW'($signed(f_o)));
  `PST_ASSERT(FSatHighIsMax, (valid_o && f_hi) |-> (f_o == FMax))
  `PST_ASSERT(FSatLowIsMin, (valid_o && f_lo) |-> (f_o == FMin))
  `PST_COVER(FSatHigh, taken && f_hi)
  `PST_COVER(FSatLow, taken && f_lo)
  for (genvar k = 0; k < 3; k++) begin : g_grad
    logic g_hi, g_lo;
    assign g_hi = $signed(gout[k*GAccW +: GAccW]) > $signed(GAccW'($signed(grad_o[k*GW +: GW])));
    assign g_lo = $signed(gout[k*GAccW +: GAccW]) < $signed(GAccW'($signed(grad_o[k*GW +: GW])));
    `PST_ASSERT(GradSatHighIsMax, (valid_o && g_hi) |-> (grad_o[k*GW +: GW] == GMax))
    `PST_ASSERT(GradSatLowIsMin, (valid_o && g_lo) |-> (grad_o[k*GW +: GW] == GMin))
    `PST_COVER(GradSatHigh, taken && g_hi)
    `PST_COVER(GradSatLow, taken && g_lo)
  end
  // The quadric's own saturation (q at an extreme of the F format).
  `PST_COVER(QuadricSatHigh, taken && q_e == FMax)
  `PST_COVER(QuadricSatLow, taken && q_e == FMin)

  // Pass boundaries: each pass's last noise step issued; the result stalled.
  for (genvar p = 0; p < Passes; p++) begin : g_pass
    `PST_COVER(PassEnd, valid_i && noise_on && 32'(nstep) == NoiseSteps - 1 && 32'(npass) == p)
  end
  `PST_COVER(ResultStalled, valid_o && !ready_i)
  `PST_COVER(NoActiveOctaves, taken && active_i == '0)
  `PST_COVER(SomeActiveOctaves, taken && active_i != '0 && 32'(active_i) < Octaves)
  `PST_COVER(AllActiveOctaves, taken && 32'(active_i) == Octaves)

  if (Serial) begin : g_serial
    `PST_ASSERT(RowsInRange, (!xf_on || 32'(xrow) < SR) && (!tm_on || 32'(trow) < SR))
    // Every transform row and term row computed (the fragment moving on), and a fragment
    // that waits for the serial quadric past its octave cycles.
    for (genvar r = 0; r < SR; r++) begin : g_row
      `PST_COVER(TransformRow, valid_i && !last_cycle && xf_on && 32'(xrow) == r)
      `PST_COVER(TermRow, valid_i && !last_cycle && tm_on && 32'(trow) == r)
    end
    `PST_COVER(WaitForQuadric, valid_i && (32'(cyc_q) + 1 >= Cycles) && !quad_done)
  end else begin : g_parallel
    logic unused;
    assign unused = ^{last_cycle, quad_done, xf_on, xrow, tm_on, trow};
  end
endmodule

bind pst_octave_stage pst_octave_stage_sva #(
  .Octaves(Octaves), .NoiseSteps(NoiseSteps), .Passes(Passes), .PassBits(PassBits),
  .Cycles(Cycles), .CycMax(CycMax), .CycBits(CycBits), .OctBits(OctBits), .SR(SR),
  .Serial(Serial), .FW(FW), .GW(GW), .FAccW(FAccW), .GAccW(GAccW), .SideW(SideW)
) u_sva (.*);

`default_nettype wire

// pst_octave_datapath_sva: checker of the octave datapaths' schedules (pst_octave_parallel,
// pst_octave_serial). Assertions: the handshake at the output (pst_handshake_sva, bound below:
// the side payload held while [B] refuses it); the cycle counter stays in range, is zero
// without a fragment and holds while the result is refused; [A] is released only at the last
// cycle; the noise step and pass in range; the serial rows in range. Cover points: each pass's last noise step
// and (serial) every transform and term row and a fragment waiting for the quadric.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_octave_datapath_sva #(
  parameter int NoiseSteps = 1,
  parameter int Passes     = 1,
  parameter int PassBits   = 1,
  parameter int Cycles     = 1,
  parameter int CycMax     = 1,
  parameter int CycBits    = 1,
  parameter bit Serial     = 1'b0
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                valid_i,
  input logic                ready_o,
  input logic                valid_o,
  input logic                ready_i,
  input logic [CycBits-1:0]  cyc_q,
  input logic                noise_on,
  input logic [PassBits-1:0] npass,
  input logic [2:0]          nstep,
  // Serial only (tied off on the parallel datapath)
  input logic                last_cycle,
  input logic                quad_done,
  input logic                xf_on,
  input logic [1:0]          xrow,
  input logic                tm_on,
  input logic [1:0]          trow
);
  localparam int SR = 3;

  `PST_ASSERT(CycInRange, 32'(cyc_q) < CycMax)
  `PST_ASSERT(CycZeroWhenEmpty, !valid_i |-> (cyc_q == '0))
  `PST_ASSERT(CycHeldWhileRefused, (valid_o && !ready_i) |=> $stable(cyc_q))
  `PST_ASSERT(NoiseStepInRange, noise_on |-> (32'(nstep) < NoiseSteps && 32'(npass) < Passes))
  `PST_ASSERT(ReadyOnlyAtLast, (valid_i && ready_o) |-> (32'(cyc_q) + 1 >= Cycles))
  for (genvar p = 0; p < Passes; p++) begin : g_pass
    `PST_COVER(PassEnd, valid_i && noise_on && 32'(nstep) == NoiseSteps - 1 && 32'(npass) == p)
  end

  if (Serial) begin : g_serial
    `PST_ASSERT(RowsInRange, (!xf_on || 32'(xrow) < SR) && (!tm_on || 32'(trow) < SR))
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

bind pst_octave_parallel pst_octave_datapath_sva #(
  .NoiseSteps(NoiseSteps), .Passes(Passes), .PassBits(PassBits), .Cycles(Cycles), .CycMax(Cycles),
  .CycBits(CycBits), .Serial(1'b0)
) u_sva (
  .clk_i, .rst_ni, .valid_i, .ready_o, .valid_o, .ready_i, .cyc_q, .noise_on (1'b1), .npass, .nstep,
  .last_cycle (1'b0), .quad_done (1'b1), .xf_on (1'b0), .xrow (2'b0), .tm_on (1'b0), .trow (2'b0)
);

bind pst_octave_serial pst_octave_datapath_sva #(
  .NoiseSteps(NoiseSteps), .Passes(Passes), .PassBits(PassBits), .Cycles(Cycles), .CycMax(CycMax),
  .CycBits(CycBits), .Serial(1'b1)
) u_sva (
  .clk_i, .rst_ni, .valid_i, .ready_o, .valid_o, .ready_i, .cyc_q, .noise_on (sch.noise_on),
  .npass (sch.npass), .nstep (sch.nstep), .last_cycle, .quad_done, .xf_on (sch.xf_on),
  .xrow (sch.xrow), .tm_on (sch.tm_on), .trow (sch.trow)
);

// The hand-over to [B]: the handshake checker on each datapath's output.
bind pst_octave_parallel pst_handshake_sva #(.Width(SideW)) u_sva_out (
  .clk_i, .rst_ni, .valid_i (valid_o), .ready_i, .data_i (side_o));
bind pst_octave_serial pst_handshake_sva #(.Width(SideW)) u_sva_out (
  .clk_i, .rst_ni, .valid_i (valid_o), .ready_i, .data_i (side_o));

`default_nettype wire

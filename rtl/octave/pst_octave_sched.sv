// pst_octave_sched: the cycle schedule of the serial octave datapath (pst_octave_serial): for
// the fragment's cycle c in the octave stage, which noise step, transform row and term row run.
// One row of M_i s + o_i and of a_i M_i^T g per cycle (3 + 3 multipliers instead of 9 + 9),
// software-pipelined around the noise unit (SR = 3 rows, NR = its registers):
//   transform of pass p, row r   cycle p NoiseSteps + r            (r < SR)
//   noise of pass p, step j      cycle SR + p NoiseSteps + j
//   term of pass p, row r        cycle SR + NR + (p + 1) NoiseSteps + r
// (NoiseSteps >= 4 keeps the three apart: rows 0, 1 wait in a buffer while the previous pass's
// noise runs, row 2 completes the noise unit's input at its last step; a pass's result waits
// for its term rows.) The schedule is registered: sch_o is this cycle's (decoded a cycle
// ahead from cyc_next_i, so the decode stays off the term rows' multiplier paths; its xpass
// is zero), next_o the next cycle's, from which the lanes select and register their rows.
//
// Parameters:
//   Passes      octave passes per fragment (Octaves / NoiseUnits).
//   NoiseSteps  cycles per noise evaluation.
//   NoiseRegs   the noise unit's pipeline registers (NR above).
//   CycBits     width of the cycle count.
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_octave_sched #(
  parameter int Passes     = 1,
  `PST_NOISE_SCHED_PARAMS,
  parameter int CycBits    = 5,
  localparam int PassBits  = (Passes > 1) ? $clog2(Passes) : 1,
  localparam int SchW      = 3 * PassBits + 10   // $bits of the schedule below
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic [CycBits-1:0] cyc_next_i,   // the cycle count at the next edge
  output logic [SchW-1:0]   sch_o,         // this cycle's schedule (a sched_t)
  output logic [SchW-1:0]   next_o         // the next cycle's
);

  localparam int SR = pst_pkg::SerialRows;
  localparam int NR = NoiseRegs;

  // The schedule of cycle c: {noise_on, npass, nstep, xf_on, xpass, xrow, tm_on, tpass, trow}
  // (pst_octave_serial's sched_t).
  function automatic logic [SchW-1:0] sched(input int c);
    int                  cn, ct;
    logic                no, xo, to;
    logic [PassBits-1:0] np, xp, tp;
    logic [2:0]          ns;
    logic [1:0]          xr, tr;
    cn = c - SR;
    ct = c - SR - NR;
    no = (c >= SR) && (c < SR + Passes * NoiseSteps);
    np = no ? PassBits'(cn / NoiseSteps) : '0;
    ns = no ? 3'(cn % NoiseSteps) : '0;
    xo = (c < Passes * NoiseSteps) && (c % NoiseSteps < SR);
    xp = PassBits'(c / NoiseSteps);
    xr = 2'(c % NoiseSteps);
    to = (ct >= NoiseSteps) && (ct < (Passes + 1) * NoiseSteps) && (ct % NoiseSteps < SR);
    tp = to ? PassBits'(ct / NoiseSteps - 1) : '0;
    tr = to ? 2'(ct % NoiseSteps) : '0;
    sched = {no, np, ns, xo, xp, xr, to, tp, tr};
  endfunction

  // This cycle's schedule without its transform pass (the datapath reads its matrix rows
  // from next_o a cycle ahead): the flops of a constant field drop out.
  localparam logic [SchW-1:0] NoXpass = ~(SchW'((1 << PassBits) - 1) << (PassBits + 5));
  assign next_o = sched(32'(cyc_next_i));
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) sch_o <= sched(0) & NoXpass;
    else sch_o <= next_o & NoXpass;
  end

endmodule

`default_nettype wire

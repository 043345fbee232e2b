// pst_top: the procedural solid-texturing pipeline of Hart et al. 1999 (docs/HARDWARE.md),
// wiring only:
//
//   reg port -> pst_regs ------------------+--------------------------------+
//                                          v                                v
//   fragment -> [A] -> pst_octave_stage -> [B] -> pst_width_stage -> [C] -> pst_colour_stage -> [D] -> out
//     frag_t            (quadric, lanes,   acc_t   (filter width)   width_t  (colour table)   out_t
//                        accumulation)
//
// [A]..[D] are pst_pipe_reg stages (valid/ready) carrying the named payloads frag_t, acc_t,
// width_t, out_t: on the parallel datapath skid buffers with a registered ready_o (the
// downstream ready stops at each boundary instead of reaching the enables of every stage's
// pipeline registers), on the serial datapath single registers (ready[i] = ready[i+1] |
// ~valid[i+1]: a short chain of a few gates per stage). Each stage module holds a fragment for its
// cycles (pst_pkg: the serial datapath's step counts) and hands it on at the last. Pipeline
// registers inside the stages (NoiseRegs, OctaveRegs, WidthRegs, ColourRegs; docs/HARDWARE.md):
// a parallel stage takes a fragment every cycle into them and carries the payload fields it
// does not compute (side_i/side_o) beside it; busy_o joins idle_o.
//
// Parameters (all from the profile, rtl/configs/NAME.toml, through scripts/profile.py; the
// schema is rtl/contract.toml):
//   Octaves, NoiseUnits   K noise terms held; units evaluated per pass. Octaves / NoiseUnits
//                         passes per fragment: 1 = one fragment per clock.
//   NoiseSteps            cycles per pass (pst_noise): Passes x NoiseSteps cycles per fragment.
//   Datapath              pst_pkg::DatapathParallel or DatapathSerial: the quadric one row per
//                         cycle, the filter width one product per cycle (6 cycles in [B], 16 in
//                         reduced with the euclidean norm: squares and square root serial too),
//                         the colour-table filter one channel per cycle (4 cycles in [C]).
//   NoiseRegs, OctaveRegs, WidthRegs, ColourRegs   pipeline registers (latency; serial: cycles).
//   Log2Clut, ColourBits; Noise*; FilterNorm, FilterRecipFrac; <Format>Int/Frac: colour
//   table, noise unit, |grad| and SAT precision, number formats (docs/HARDWARE.md).
//   FilterBandlimit       isotropic: the fade unit for bandlimited octaves (pst_fade_lg per
//                         pixel, pst_octave_fade per lane, in pst_octave_stage); off: none.
//
// Register writes (reg_we_i) are legal only while idle_o is high: the driver drains the
// pipeline before it changes the texture, as a driver between two objects would.
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_top #(
  `PST_PROFILE_PARAMS,
  parameter bit DebugProbes = 1'b1,
  // Derived widths (not profile keys).
  localparam int CW  = CoordInt + CoordFrac,                                // one coordinate
  localparam int JW  = JacobianInt + JacobianFrac,                          // one Jacobian entry
  localparam int FW  = FInt + FFrac,                                        // f
  localparam int GW  = GradInt + GradFrac,                                  // one grad f component
  localparam int WW  = pst_pkg::w_width(Log2Clut, WidthFrac),   // W = w N, < 4N
  localparam int CB4 = 4 * ColourBits,                                      // packed RGBA
  localparam int TB  = pst_pkg::TagBits, localparam int LF = NoiseLatticeFrac,
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,                // noise value
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac             // noise gradient
) (
  input  logic                           clk_i,
  input  logic                           rst_ni,
  // Register write port (docs/HARDWARE.md register map)
  input  logic                           reg_we_i,
  input  logic [pst_pkg::RegAddrBits-1:0] reg_addr_i,
  input  logic [pst_pkg::RegDataBits-1:0] reg_wdata_i,
  output logic                           idle_o,
  // Fragments in
  input  logic                           frag_valid_i,
  output logic                           frag_ready_o,
  input  logic [TB-1:0]                  frag_tag_i,
  input  logic [3*CW-1:0]                frag_s_i,
  input  logic [6*JW-1:0]                frag_j_i,
  // Colours out
  output logic                           out_valid_o,
  input  logic                           out_ready_i,
  output logic [TB-1:0]                  out_tag_o,
  output logic [CB4-1:0]                 out_rgba_o,
  output logic [FW-1:0]                  out_f_o,
  output logic [3*GW-1:0]                out_grad_o,
  output logic [WW-1:0]                  out_w_o,
  // Debug probes of the octave stage (a pass's noise results with its tag and lattice input,
  // when they leave the noise units; q with its tag when the fragment leaves the stage): the
  // harness samples them every cycle so the scoreboard can name the first unit that differs.
  // Tied to zero when DebugProbes = 0 (synthesis).
  output logic                           probe_valid_o,
  output logic [TB-1:0]                  probe_tag_o,
  output logic [pst_pkg::ProbePassBits-1:0] probe_pass_o,
  output logic                           probe_q_valid_o,   // probe_q_o is final (the last cycle)
  output logic [TB-1:0]                  probe_q_tag_o,
  output logic [FW-1:0]                  probe_q_o,
  output logic [NoiseUnits*pst_pkg::LatticeWidth-1:0] probe_lat_o,
  output logic [NoiseUnits*3*LF-1:0]     probe_frac_o,
  output logic [NoiseUnits*NW-1:0]       probe_n_o,
  output logic [NoiseUnits*3*NGW-1:0]    probe_g_o
);

  // Payloads of [A]..[D] (the first field at the high bits).
  typedef struct packed { logic [6*JW-1:0] j; logic [3*CW-1:0] s; logic [TB-1:0] tag; } frag_t;
  typedef struct packed { logic [3*GW-1:0] grad; logic [FW-1:0] f; logic [6*JW-1:0] j; logic [TB-1:0] tag; } acc_t;
  typedef struct packed { logic [WW-1:0] w; logic [3*GW-1:0] grad; logic [FW-1:0] f; logic [TB-1:0] tag; } width_t;
  typedef struct packed {
    logic [WW-1:0] w; logic [3*GW-1:0] grad; logic [FW-1:0] f; logic [CB4-1:0] rgba; logic [TB-1:0] tag;
  } out_t;
  frag_t  a_d, a_q;
  acc_t   b_d, b_q;
  width_t c_d, c_q;
  out_t   d_d, d_q;
  logic a_valid, a_ready, b_in_valid, b_in_ready, b_valid, b_ready;
  logic c_in_valid, c_in_ready, c_valid, c_ready, d_in_valid, d_in_ready;
  logic octave_busy, width_busy, colour_busy;   // fragments inside the stages' pipeline registers
  // Skid buffers at the boundaries of the parallel datapath (registered ready).
  localparam bit Skid = (Datapath == pst_pkg::DatapathParallel);

  // Registers: control, quadric, octaves.
  localparam int RegOctW = pst_pkg::octave_count_bits(Octaves);
  logic                          clamp;
  logic [pst_pkg::RegControlKindWidth-1:0] kind;
  logic [RegOctW-1:0]            active;
  logic [10*(QuadricInt+QuadricFrac)-1:0]          quad;
  logic [Octaves*9*(MatrixInt+MatrixFrac)-1:0]     oct_m;
  logic [Octaves*3*(OffsetInt+OffsetFrac)-1:0]     oct_o;
  logic [Octaves*(AmplitudeInt+AmplitudeFrac)-1:0] oct_a;
  logic [Octaves*9*(GradMatrixInt+GradMatrixFrac)-1:0] oct_gm;
  logic [pst_pkg::RegWorleyCount*(pst_pkg::WorleyCoefInt+pst_pkg::WorleyCoefFrac)-1:0] worley_c;
  logic [Octaves*pst_pkg::FadeLgBits-1:0] oct_lgm;       // bandlimited octaves (FilterBandlimit)
  logic [Octaves*(FInt+FFrac)-1:0]        oct_fm;
  logic                          bl;
  logic [pst_pkg::FadeEntries*pst_pkg::FadeBits-1:0] fade;
  // FilterWidthCap on: the filter-width cap, W = min(W, wcap) (register wcap in pst_regs, the
  // minimum in pst_width_stage); off: none (wcap all ones, unused).
  logic [WW-1:0]                 wcap;
  pst_regs #(`PST_REGS_PASS, .Worley(NoiseWorleySearch != pst_pkg::NoiseWorleySearchNone)
  ) u_regs (.clk_i, .rst_ni, .we_i (reg_we_i), .addr_i (reg_addr_i), .wdata_i (reg_wdata_i),
    .clamp_o (clamp), .kind_o (kind), .active_o (active), .quad_o (quad), .oct_m_o (oct_m),
    .oct_o_o (oct_o), .oct_a_o (oct_a), .oct_gm_o (oct_gm), .worley_o (worley_c),
    .bl_o (bl), .fade_o (fade),
    .oct_lgm_o (oct_lgm), .oct_fm_o (oct_fm), .wcap_o (wcap));

  // [A] fragment -> octave stage -> [B]
  assign a_d.tag = frag_tag_i;
  assign a_d.s   = frag_s_i;
  assign a_d.j   = frag_j_i;
  pst_pipe_reg #(.Width($bits(a_d)), .Skid(Skid)) u_reg_a (.clk_i, .rst_ni, .valid_i (frag_valid_i),
    .ready_o (frag_ready_o), .data_i (a_d), .valid_o (a_valid), .ready_i (a_ready), .data_o (a_q));

  pst_octave_stage #(`PST_OCTAVE_STAGE_PASS, .SideW(6*JW + TB), .DebugProbes(DebugProbes)
  ) u_octave (.clk_i, .rst_ni, .valid_i (a_valid), .ready_o (a_ready), .s_i (a_q.s),
    .side_i ({a_q.j, a_q.tag}), .valid_o (b_in_valid), .ready_i (b_in_ready), .f_o (b_d.f),
    .grad_o (b_d.grad), .side_o ({b_d.j, b_d.tag}), .busy_o (octave_busy),
    .active_i (active), .quad_i (quad), .oct_m_i (oct_m), .oct_o_i (oct_o), .oct_a_i (oct_a),
    .oct_gm_i (oct_gm), .worley_c_i (worley_c), .oct_lgm_i (oct_lgm), .oct_fm_i (oct_fm), .bl_i (bl), .fade_i (fade), .probe_valid_o, .probe_tag_o, .probe_pass_o, .probe_q_valid_o,
    .probe_q_tag_o, .probe_q_o, .probe_lat_o, .probe_frac_o, .probe_n_o, .probe_g_o);
  pst_pipe_reg #(.Width($bits(b_d)), .Skid(Skid)) u_reg_b (.clk_i, .rst_ni, .valid_i (b_in_valid),
    .ready_o (b_in_ready), .data_i (b_d), .valid_o (b_valid), .ready_i (b_ready), .data_o (b_q));

  // [B] -> filter width -> [C]
  pst_width_stage #(`PST_WIDTH_STAGE_PASS, .SideW(3*GW + FW + TB)
  ) u_width (.clk_i, .rst_ni, .valid_i (b_valid), .ready_o (b_ready), .grad_i (b_q.grad),
    .j_i (b_q.j), .side_i ({b_q.grad, b_q.f, b_q.tag}), .valid_o (c_in_valid),
    .ready_i (c_in_ready), .wcap_i (wcap), .w_o (c_d.w), .side_o ({c_d.grad, c_d.f, c_d.tag}), .busy_o (width_busy));
  pst_pipe_reg #(.Width($bits(c_d)), .Skid(Skid)) u_reg_c (.clk_i, .rst_ni, .valid_i (c_in_valid),
    .ready_o (c_in_ready), .data_i (c_d), .valid_o (c_valid), .ready_i (c_ready), .data_o (c_q));

  // [C] -> colour-table filter -> [D] -> out
  pst_colour_stage #(`PST_COLOUR_STAGE_PASS, .SideW(WW + 3*GW + FW + TB)
  ) u_colour (.clk_i, .rst_ni, .we_i (reg_we_i), .addr_i (reg_addr_i), .wdata_i (reg_wdata_i),
    .clamp_i (clamp), .kind_i (kind), .valid_i (c_valid), .ready_o (c_ready), .f_i (c_q.f),
    .w_i (c_q.w), .side_i ({c_q.w, c_q.grad, c_q.f, c_q.tag}), .valid_o (d_in_valid),
    .ready_i (d_in_ready), .rgba_o (d_d.rgba), .side_o ({d_d.w, d_d.grad, d_d.f, d_d.tag}),
    .busy_o (colour_busy));
  pst_pipe_reg #(.Width($bits(d_d)), .Skid(Skid)) u_reg_d (.clk_i, .rst_ni, .valid_i (d_in_valid),
    .ready_o (d_in_ready), .data_i (d_d), .valid_o (out_valid_o), .ready_i (out_ready_i), .data_o (d_q));
  assign out_tag_o  = d_q.tag;
  assign out_rgba_o = d_q.rgba;
  assign out_f_o    = d_q.f;
  assign out_grad_o = d_q.grad;
  assign out_w_o    = d_q.w;

  assign idle_o = ~(a_valid | octave_busy | b_valid | width_busy | c_valid | colour_busy | out_valid_o);

  // Assertions (the register-write rule and both stream handshakes: pst_top_sva, rtl/sva/)
`ifndef SYNTHESIS
  // The profile's ranges and cross-constraints (generated from rtl/contract.toml).
`include "pst_profile_checks.svh"
`endif

endmodule

`default_nettype wire

// pst_octave_datapath_ports: the port list of the two octave datapaths (pst_octave_parallel,
// pst_octave_serial), declared once: `PST_OCTAVE_DATAPATH_PORTS is the whole ( ... ) list, and
// `PST_OCTAVE_DATAPATH_CONNECT the one connection list pst_octave_stage instantiates either
// with (its signals named as the ports, the datapath's outputs nz_*, fterm, gterm, acc_*, q_e,
// gradq_e, pr_* as below). `PST_OCTAVE_DATAPATH_WIDTHS, last in the datapath's #( ... ) after
// its parameters (`PST_OCTAVE_PARAMS, `PST_LANE_PARAMS, NoiseSubbandOrientations), declares the
// widths the ports use: CW, MW, OW, AW, GMW, QW, FW, GW, JW (the formats), LF, NW, NGW (the
// noise unit's), LTW, TB, PPB, FB, LMW, OctBits, SLW (the subband unit's weights of a lane:
// max(1, NoiseSubbandOrientations) * FadeBits).
// A macro, not packed structs: the port widths follow the profile's parameters (a module's,
// set per profile by -G or chparam), and a struct port type whose field widths follow module
// parameters needs `parameter type` (Yosys 0.23: syntax error) or an interface (Yosys 0.23
// reads `b.f` as an implicitly declared wire and drops the logic); a pst_pkg typedef has one
// width for every profile (checked 2026-12-07: a pst_pkg struct with localparam widths as a
// port type is read by Yosys 0.23 and Verilator 5.006 alike).
//
// Ports:
//   valid_i, ready_o, s_i, side_i    [A]: the fragment's texture coordinates and side payload
//   valid_o, ready_i, side_o         the hand-over to [B]; busy_o: a beat inside the pipeline
//   active_i .. fade_i               pst_octave_stage's registers (steady while a fragment is
//                                    in flight)
//   nz_*_o, nz_*_i                   the noise units (lane u at [u*W +: W]); nz_lam_o the
//                                    subband unit's weights (1.0 where the datapath forms
//                                    none), nz_last_i the lanes' outputs are an evaluation's
//                                    last step
//   fterm_o .. gradq_o               the accumulators: a beat's terms, added (acc_first_o:
//                                    from zero); the quadric with the last
//   pr_*_o                           probes: the pass whose noise results are at the noise
//                                    units' outputs (DebugProbes = 0: zero)
`ifndef PST_OCTAVE_DATAPATH_PORTS_SVH
`define PST_OCTAVE_DATAPATH_PORTS_SVH

`define PST_OCTAVE_DATAPATH_WIDTHS \
  localparam int CW  = CoordInt + CoordFrac, \
  localparam int MW  = MatrixInt + MatrixFrac, \
  localparam int OW  = OffsetInt + OffsetFrac, \
  localparam int AW  = AmplitudeInt + AmplitudeFrac, \
  localparam int GMW = GradMatrixInt + GradMatrixFrac, \
  localparam int QW  = QuadricInt + QuadricFrac, \
  localparam int FW  = FInt + FFrac, \
  localparam int GW  = GradInt + GradFrac, \
  localparam int JW  = JacobianInt + JacobianFrac, \
  localparam int LF  = NoiseLatticeFrac, \
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac, \
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac, \
  localparam int LTW = pst_pkg::LatticeWidth, \
  localparam int TB  = pst_pkg::TagBits, \
  localparam int PPB = pst_pkg::ProbePassBits, \
  localparam int FB  = pst_pkg::FadeBits, \
  localparam int LMW = pst_pkg::FadeLgBits, \
  localparam int OctBits = pst_pkg::octave_count_bits(Octaves), \
  localparam int SLW = ((NoiseSubbandOrientations == 0) ? 1 : NoiseSubbandOrientations) * FB

`define PST_OCTAVE_DATAPATH_PORTS \
  input  logic                       clk_i, \
  input  logic                       rst_ni, \
  input  logic                       valid_i, \
  output logic                       ready_o, \
  input  logic [3*CW-1:0]            s_i, \
  input  logic [SideW-1:0]           side_i, \
  output logic                       valid_o, \
  input  logic                       ready_i, \
  output logic [SideW-1:0]           side_o, \
  output logic                       busy_o, \
  input  logic [OctBits-1:0]         active_i, \
  input  logic [10*QW-1:0]           quad_i, \
  input  logic [Octaves*9*MW-1:0]    oct_m_i, \
  input  logic [Octaves*3*OW-1:0]    oct_o_i, \
  input  logic [Octaves*AW-1:0]      oct_a_i, \
  input  logic [Octaves*9*GMW-1:0]   oct_gm_i, \
  input  logic [Octaves*LMW-1:0]     oct_lgm_i, \
  input  logic [Octaves*FW-1:0]      oct_fm_i, \
  input  logic                       bl_i, \
  input  logic [pst_pkg::FadeEntries*FB-1:0] fade_i, \
  output logic                       nz_en_o, \
  output logic                       nz_valid_o, \
  output logic [2:0]                 nz_step_o, \
  output logic [NoiseUnits*LTW-1:0]  nz_lat_o, \
  output logic [NoiseUnits*3*LF-1:0] nz_frac_o, \
  output logic [NoiseUnits*SLW-1:0]  nz_lam_o, \
  input  logic [NoiseUnits*NW-1:0]   nz_n_i, \
  input  logic [NoiseUnits*3*NGW-1:0] nz_g_i, \
  input  logic [NoiseUnits-1:0]      nz_last_i, \
  output logic [NoiseUnits*FW-1:0]   fterm_o, \
  output logic [NoiseUnits*3*GW-1:0] gterm_o, \
  output logic                       acc_en_o, \
  output logic                       acc_first_o, \
  output logic [FW-1:0]              q_o, \
  output logic [3*GW-1:0]            gradq_o, \
  output logic                       pr_valid_o, \
  output logic [PPB-1:0]             pr_pass_o, \
  output logic [TB-1:0]              pr_tag_o, \
  output logic [TB-1:0]              pr_q_tag_o

`define PST_OCTAVE_DATAPATH_CONNECT \
  .clk_i, .rst_ni, .valid_i, .ready_o, .s_i, .side_i, .valid_o, .ready_i, .side_o, .busy_o, \
  .active_i, .quad_i, .oct_m_i, .oct_o_i, .oct_a_i, .oct_gm_i, .oct_lgm_i, .oct_fm_i, .bl_i, \
  .fade_i, .nz_en_o (nz_en), .nz_valid_o (nz_valid), .nz_step_o (nz_step), .nz_lat_o (nz_lat), \
  .nz_frac_o (nz_frac), .nz_lam_o (nz_lam), .nz_n_i (nz_n), .nz_g_i (nz_g), \
  .nz_last_i (nz_last), .fterm_o (fterm), .gterm_o (gterm), .acc_en_o (acc_en), \
  .acc_first_o (acc_first), .q_o (q_e), .gradq_o (gradq_e), .pr_valid_o (pr_valid), \
  .pr_pass_o (pr_pass), .pr_tag_o (pr_tag), .pr_q_tag_o (pr_q_tag)

`endif

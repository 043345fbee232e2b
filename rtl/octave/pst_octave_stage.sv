// pst_octave_stage: the octave stage of pst_top, [A] -> [B] (docs/HARDWARE.md units 1-4): the
// quadric and NoiseUnits octave lanes (octave transform, noise, octave term) over Passes =
// Octaves / NoiseUnits passes, their terms accumulated and saturated to f and grad f. Wiring of
//   pst_octave_parallel or pst_octave_serial  the datapath (Datapath): its cycle count and
//                                             schedule, the quadric, the lanes (pst_octave_lane)
//   pst_octave_noise                          the noise units the lanes share
//   pst_octave_accum                          the sums and their saturation
// A fragment (valid_i, s_i, side_i) stays in [A] for the datapath's cycles and is offered to
// [B] (valid_o, f_o, grad_o, side_o) at its last; busy_o: a fragment is inside the parallel
// datapath's pipeline registers (pst_top's idle_o).
//
// Parameters: the profile's (pst_top's header). Datapath selects the datapath; NoiseRegs and
// OctaveRegs set its registers (parallel: latency, serial: cycles per fragment).
// Registers (pst_regs, flat): quad_i A..J; oct_*_i octave i's M, o, a, GM, lg ||M|| at block i;
// bl_i, fade_i: control.bandlimit and the fade table; oct_fm_i the octave terms' means (the fade's
// target).
`include "pst_pkg.sv"
`include "pst_params.svh"
`include "octave/pst_octave_datapath_ports.svh"
`default_nettype none

module pst_octave_stage #(
  `PST_OCTAVE_STAGE_PARAMS,
  parameter int SideW = pst_pkg::TagBits,   // side_i: the tag at its low TagBits, the Jacobian above
  parameter bit DebugProbes = 1'b1,
  localparam int CW  = CoordInt + CoordFrac,
  localparam int MW  = MatrixInt + MatrixFrac,
  localparam int OW  = OffsetInt + OffsetFrac,
  localparam int AW  = AmplitudeInt + AmplitudeFrac,
  localparam int GMW = GradMatrixInt + GradMatrixFrac,
  localparam int QW  = QuadricInt + QuadricFrac,
  localparam int FW  = FInt + FFrac,
  localparam int GW  = GradInt + GradFrac,
  localparam int LF  = NoiseLatticeFrac,
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,      // noise value
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,  // one noise gradient component
  localparam int LTW = pst_pkg::LatticeWidth,                     // one lane's lattice index
  localparam int PPB = pst_pkg::ProbePassBits,
  localparam int OctBits = pst_pkg::octave_count_bits(Octaves),   // active octave count
  localparam int FB  = pst_pkg::FadeBits,                         // a fade table entry, alpha
  localparam int LMW = pst_pkg::FadeLgBits,                       // lg ||M||
  localparam int WCW = pst_pkg::RegWorleyCount * (pst_pkg::WorleyCoefInt + pst_pkg::WorleyCoefFrac)
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  // The fragment in [A] and its hand-over to [B]
  input  logic                      valid_i,
  output logic                      ready_o,
  input  logic [3*CW-1:0]           s_i,
  input  logic [SideW-1:0]          side_i,   // carried to side_o with the fragment
  output logic                      valid_o,
  input  logic                      ready_i,
  output logic [FW-1:0]             f_o,
  output logic [3*GW-1:0]           grad_o,
  output logic [SideW-1:0]          side_o,
  output logic                      busy_o,
  // Registers
  input  logic [OctBits-1:0]        active_i,
  input  logic [10*QW-1:0]          quad_i,
  input  logic [Octaves*9*MW-1:0]   oct_m_i,
  input  logic [Octaves*3*OW-1:0]   oct_o_i,
  input  logic [Octaves*AW-1:0]     oct_a_i,
  input  logic [Octaves*9*GMW-1:0]  oct_gm_i,
  input  logic [WCW-1:0]            worley_c_i,
  input  logic [Octaves*LMW-1:0]    oct_lgm_i,
  input  logic [Octaves*(FInt+FFrac)-1:0] oct_fm_i,
  input  logic                      bl_i,
  input  logic [pst_pkg::FadeEntries*FB-1:0] fade_i,
  // Debug probes (pst_top's; zero when DebugProbes = 0)
  output logic                      probe_valid_o,
  output logic [pst_pkg::TagBits-1:0] probe_tag_o,
  output logic [PPB-1:0]            probe_pass_o,
  output logic                      probe_q_valid_o,
  output logic [pst_pkg::TagBits-1:0] probe_q_tag_o,
  output logic [FW-1:0]             probe_q_o,
  output logic [NoiseUnits*LTW-1:0] probe_lat_o,
  output logic [NoiseUnits*3*LF-1:0]  probe_frac_o,
  output logic [NoiseUnits*NW-1:0]    probe_n_o,
  output logic [NoiseUnits*3*NGW-1:0] probe_g_o
);

  localparam bit Serial = (Datapath == pst_pkg::DatapathSerial);
  localparam int TB     = pst_pkg::TagBits;

  // Datapath <-> noise units, datapath -> accumulators, datapath -> probes.
  logic                        nz_en, nz_valid;
  logic [2:0]                  nz_step;
  logic [NoiseUnits*LTW-1:0]   nz_lat;
  logic [NoiseUnits*3*LF-1:0]  nz_frac;
  logic [NoiseUnits-1:0]       nz_last;
  logic [NoiseUnits*NW-1:0]    nz_n;
  logic [NoiseUnits*3*NGW-1:0] nz_g;
  logic [NoiseUnits*FW-1:0]    fterm;
  logic [NoiseUnits*3*GW-1:0]  gterm;
  logic                        acc_en, acc_first;
  logic [FW-1:0]               q_e;
  logic [3*GW-1:0]             gradq_e;
  logic                        pr_valid;
  logic [PPB-1:0]              pr_pass;
  logic [TB-1:0]               pr_tag, pr_q_tag;

  // The subband unit's weights (noise.subband_orientations; either datapath forms them).
  localparam int SLW = ((NoiseSubbandOrientations == 0) ? 1 : NoiseSubbandOrientations) * FB;
  logic [NoiseUnits*SLW-1:0] nz_lam;
  if (Serial) begin : g_serial
    pst_octave_serial #(`PST_OCTAVE_PASS, `PST_LANE_PASS, .SideW(SideW), .DebugProbes(DebugProbes),
      .NoiseSubband(NoiseSubband), .NoiseSubbandOrientations(NoiseSubbandOrientations)
    ) u_datapath (`PST_OCTAVE_DATAPATH_CONNECT);
  end else begin : g_parallel
    pst_octave_parallel #(`PST_OCTAVE_PASS, `PST_LANE_PASS, .SideW(SideW), .DebugProbes(DebugProbes),
      .NoiseSubband(NoiseSubband), .NoiseSubbandOrientations(NoiseSubbandOrientations)
    ) u_datapath (`PST_OCTAVE_DATAPATH_CONNECT);
  end

  logic [NoiseUnits*LTW-1:0]  pr_lat;
  logic [NoiseUnits*3*LF-1:0] pr_frac;
  pst_octave_noise #(`PST_OCTAVE_NOISE_PASS, .DebugProbes(DebugProbes)) u_noise (
    .clk_i, .rst_ni, .en_i (nz_en), .valid_i (nz_valid), .step_i (nz_step), .lat_i (nz_lat),
    .frac_i (nz_frac), .worley_c_i, .sb_lam_i (nz_lam), .last_o (nz_last), .n_o (nz_n), .g_o (nz_g),
    .probe_lat_o (pr_lat), .probe_frac_o (pr_frac)
  );

  pst_octave_accum #(`PST_ACCUM_PASS) u_accum (
    .clk_i, .rst_ni, .acc_en_i (acc_en), .acc_first_i (acc_first), .fterm_i (fterm), .gterm_i (gterm),
    .q_i (q_e), .gradq_i (gradq_e), .f_o, .grad_o
  );

  // Probes: the noise results of a pass at the noise units' output (its last step), with the
  // tag and lattice input of that pass; q with the fragment's result.
  assign probe_valid_o   = DebugProbes & pr_valid;
  assign probe_tag_o     = DebugProbes ? pr_tag : '0;
  assign probe_pass_o    = DebugProbes ? pr_pass : '0;
  assign probe_q_valid_o = DebugProbes & valid_o;
  assign probe_q_tag_o   = pr_q_tag;
  assign probe_q_o       = DebugProbes ? q_e : '0;
  assign probe_lat_o     = pr_lat;
  assign probe_frac_o    = pr_frac;
  assign probe_n_o       = DebugProbes ? nz_n : '0;
  assign probe_g_o       = DebugProbes ? nz_g : '0;

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (SideW < TB) $error("pst_octave_stage: SideW must hold the tag");
  end
`endif

endmodule

`default_nettype wire

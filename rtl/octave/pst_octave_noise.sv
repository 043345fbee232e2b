// pst_octave_noise: the NoiseUnits noise units of the octave stage (docs/HARDWARE.md unit 2),
// one per lane: the lattice-noise unit (pst_noise) or, with noise.worley_search, a worley unit
// (pst_worley), or with noise.subband a subband unit (pst_subband); all step together (en_i,
// valid_i, step_i). Beside each, the probes' copy of its
// lattice input, delayed by its NoiseRegs registers so that it meets the unit's result.
//
// Parameters: the profile's noise keys (pst_top's header); DebugProbes = 0 ties the probe
// outputs to zero.
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_octave_noise #(
  `PST_OCTAVE_NOISE_PARAMS,
  parameter bit DebugProbes = 1'b1,
  localparam int LF  = NoiseLatticeFrac,
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,
  localparam int LTW = pst_pkg::LatticeWidth,
  localparam int WCW = pst_pkg::RegWorleyCount * (pst_pkg::WorleyCoefInt + pst_pkg::WorleyCoefFrac),
  // The subband unit's weights per lane (max(1, noise.subband_orientations) of FadeBits).
  localparam int SLW = ((NoiseSubbandOrientations == 0) ? 1 : NoiseSubbandOrientations) * pst_pkg::FadeBits
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic                        en_i,
  input  logic                        valid_i,
  input  logic [2:0]                  step_i,
  input  logic [NoiseUnits*LTW-1:0]   lat_i,    // lane u at [u*LTW +: LTW], likewise below
  input  logic [NoiseUnits*3*LF-1:0]  frac_i,
  input  logic [WCW-1:0]              worley_c_i,
  input  logic [NoiseUnits*SLW-1:0]   sb_lam_i,  // the subband unit's weights (lane u at [u*SLW +: SLW])
  output logic [NoiseUnits-1:0]       last_o,   // the output is an evaluation's last step
  output logic [NoiseUnits*NW-1:0]    n_o,
  output logic [NoiseUnits*3*NGW-1:0] g_o,
  output logic [NoiseUnits*LTW-1:0]   probe_lat_o,
  output logic [NoiseUnits*3*LF-1:0]  probe_frac_o
);

  for (genvar u = 0; u < NoiseUnits; u++) begin : g_unit
    logic unit_valid;
    if (NoiseSubband != pst_pkg::NoiseSubbandNone) begin : g_subband
      pst_subband #(`PST_SUBBAND_PASS, .NoiseSubband(NoiseSubband),
        .NoiseSubbandOrientations(NoiseSubbandOrientations)
      ) u_noise (
        .clk_i, .rst_ni, .en_i, .valid_i, .step_i, .lat_i (lat_i[u*LTW +: LTW]),
        .frac_i (frac_i[u*3*LF +: 3*LF]), .lam_i (sb_lam_i[u*SLW +: SLW]), .valid_o (unit_valid), .last_o (last_o[u]),
        .n_o (n_o[u*NW +: NW]), .grad_o (g_o[u*3*NGW +: 3*NGW])
      );
      logic unused_wc;
      assign unused_wc = ^worley_c_i;
    end else if (NoiseWorleySearch == pst_pkg::NoiseWorleySearchNone) begin : g_lattice
      logic unused_lam;
      assign unused_lam = ^sb_lam_i[u*SLW +: SLW];
      pst_noise #(`PST_LATTICE_PASS) u_noise (
        .clk_i, .rst_ni, .en_i, .valid_i, .step_i, .lat_i (lat_i[u*LTW +: LTW]),
        .frac_i (frac_i[u*3*LF +: 3*LF]), .valid_o (unit_valid), .last_o (last_o[u]),
        .n_o (n_o[u*NW +: NW]), .grad_o (g_o[u*3*NGW +: 3*NGW])
      );
      logic unused_wc;
      assign unused_wc = ^worley_c_i;
    end else begin : g_worley
      logic unused_lam;
      assign unused_lam = ^sb_lam_i[u*SLW +: SLW];
      pst_worley #(`PST_WORLEY_PASS, .NoiseWorleySearch(NoiseWorleySearch)) u_noise (
        .clk_i, .rst_ni, .en_i, .valid_i, .step_i, .lat_i (lat_i[u*LTW +: LTW]),
        .frac_i (frac_i[u*3*LF +: 3*LF]), .coef_i (worley_c_i), .valid_o (unit_valid),
        .last_o (last_o[u]), .n_o (n_o[u*NW +: NW]), .grad_o (g_o[u*3*NGW +: 3*NGW])
      );
    end
    logic unused_valid;
    assign unused_valid = unit_valid;

    if (DebugProbes) begin : g_probe
      pst_delay #(.Width(LTW + 3*LF), .Depth(NoiseRegs)) u_pr (
        .clk_i, .rst_ni, .en_i, .d_i ({lat_i[u*LTW +: LTW], frac_i[u*3*LF +: 3*LF]}),
        .q_o ({probe_lat_o[u*LTW +: LTW], probe_frac_o[u*3*LF +: 3*LF]}));
    end else begin : g_no_probe
      assign probe_lat_o[u*LTW +: LTW]    = '0;
      assign probe_frac_o[u*3*LF +: 3*LF] = '0;
    end
  end

endmodule

`default_nettype wire

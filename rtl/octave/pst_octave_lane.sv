// pst_octave_lane: the body of one octave lane (docs/HARDWARE.md units 2 and 4), combinational
// but for the transform's TransformRegs register, in three parts the datapaths register between as their schedules need:
//   transform  the lattice index and fraction of M_i s + o_i (pst_octave_transform), Rows rows;
//   fade       the octave's weight alpha from the pixel's lg edge lengths and lg ||M_i||
//              (pst_octave_fade; 1.0 without FilterBandlimit);
//   term       a_i n and rows of a_i M_i^T grad n, faded by alpha (pst_octave_term; the value
//              toward the term's mean fm_i).
// The parallel octave datapath (pst_octave_parallel) uses Rows = 3 with a beat through its
// pipeline registers between the parts; the serial one (pst_octave_serial) Rows = 1, a row of
// the matrices per cycle.
//
// Parameters:
//   Rows             3: whole matrices; 1: one row per use (m_i, o_i, gm_i that row's).
//   TransformRegs    0, 1: the register inside the transform (pst_octave_transform Regs).
//   FilterBandlimit  isotropic: the fade (alpha_o from the table); off: alpha_o = 1.0.
//   TermFade         0: no fade even with FilterBandlimit (the subband unit's anisotropic filter
//                    takes the fade unit's table for its weights and leaves the term whole): alpha_o
//                    = 1.0 and the term unfaded, neither built.
//   LgW              width of lgx_i, lgy_i (pst_fade_lg's lg_o).
//   <Format>Int/Frac the profile's number formats (pst_top's header).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_octave_lane #(
  parameter int Rows = 3,
  parameter int TransformRegs = 0,
  parameter int LgW = 9,
  parameter bit TermFade = 1'b1,
  `PST_LANE_PARAMS,
  localparam int CW  = CoordInt + CoordFrac,
  localparam int MW  = MatrixInt + MatrixFrac,
  localparam int OW  = OffsetInt + OffsetFrac,
  localparam int AW  = AmplitudeInt + AmplitudeFrac,
  localparam int GMW = GradMatrixInt + GradMatrixFrac,
  localparam int FW  = FInt + FFrac,
  localparam int GW  = GradInt + GradFrac,
  localparam int LB  = pst_pkg::LatticeBits,
  localparam int LF  = NoiseLatticeFrac,
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,
  localparam int FB  = pst_pkg::FadeBits,
  localparam int LMW = pst_pkg::FadeLgBits
) (
  input  logic                    clk_i,    // TransformRegs: the transform's register (en_i)
  input  logic                    rst_ni,
  input  logic                    en_i,
  // Transform
  input  logic [3*CW-1:0]         s_i,
  input  logic [Rows*3*MW-1:0]    m_i,
  input  logic [Rows*OW-1:0]      o_i,
  output logic [Rows*LB-1:0]      lat_o,
  output logic [Rows*LF-1:0]      frac_o,
  // Fade
  input  logic                    bl_i,
  input  logic [LgW-1:0]          lgx_i,
  input  logic [LgW-1:0]          lgy_i,
  input  logic [LMW-1:0]          lgm_i,
  input  logic [pst_pkg::FadeEntries*FB-1:0] fade_i,
  output logic [FB-1:0]           alpha_o,
  // Term
  input  logic [NW-1:0]           n_i,
  input  logic [3*NGW-1:0]        g_i,
  input  logic [AW-1:0]           a_i,
  input  logic [Rows*3*GMW-1:0]   gm_i,
  input  logic [FB-1:0]           alpha_i,
  input  logic [FW-1:0]           fm_i,
  output logic [FW-1:0]           fterm_o,
  output logic [Rows*GW-1:0]      gterm_o
);

  localparam bit Bl = (FilterBandlimit == pst_pkg::FilterBandlimitIsotropic) && TermFade;

  pst_octave_transform #(`PST_TRANSFORM_PASS, .Rows(Rows), .Regs(TransformRegs)) u_transform (
    .clk_i, .rst_ni, .en_i, .s_i (s_i), .m_i (m_i), .o_i (o_i), .lat_o (lat_o), .frac_o (frac_o)
  );

  if (Bl) begin : g_fade
    pst_octave_fade #(.LgW(LgW)) u_fade (
      .en_i (bl_i), .lgx_i (lgx_i), .lgy_i (lgy_i), .lgm_i (lgm_i), .table_i (fade_i), .alpha_o (alpha_o));
  end else begin : g_whole
    assign alpha_o = FB'(1 << pst_pkg::FadeFrac);
    logic unused_fade;
    assign unused_fade = ^{bl_i, lgx_i, lgy_i, lgm_i, fade_i};
  end

  pst_octave_term #(`PST_TERM_PASS, .Rows(Rows), .Bandlimit(Bl)) u_term (
    .n_i (n_i), .g_i (g_i), .a_i (a_i), .gm_i (gm_i), .alpha_i (alpha_i), .fm_i (fm_i), .fterm_o (fterm_o),
    .gterm_o (gterm_o)
  );

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (Rows != 1 && Rows != 3) $error("pst_octave_lane: Rows must be 1 or 3");
  end
`endif

endmodule

`default_nettype wire

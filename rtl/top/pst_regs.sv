// pst_regs: the pipeline's control, quadric and octave registers (docs/HARDWARE.md register
// map, addresses from pst_pkg: RegControl, RegActive, RegQuadric + k, RegOctave +
// RegOctaveStride i + k). Written through the register port only while the pipeline is idle
// (pst_top asserts it); the colour tables at the other addresses live in pst_clut_filter.
// Signed values are the low bits of the 32-bit word.
//
// Parameters:
//   Octaves                          octave register blocks (i < Octaves).
//   QuadricInt/Frac, MatrixInt/Frac, OffsetInt/Frac, AmplitudeInt/Frac, GradMatrixInt/Frac
//                                    register formats (the bits kept of each word).
//   Worley                           the worley unit's coefficients C_k (RegWorley + k, signed
//                                    WorleyCoefInt.WorleyCoefFrac) are held (else worley_o is 0).
//   FilterBandlimit                  FilterBandlimitIsotropic: the fade table and the octaves' lg ||M||
//                                    registers and control.bandlimit are kept; otherwise none (zeros).
//   FilterWidthCap, Log2Clut, WidthFrac
//                                    FilterWidthCapOn: the width cap register wcap (W's format,
//                                    w_width(Log2Clut, WidthFrac) bits) is kept; otherwise none
//                                    (wcap_o all ones: no cap).
//
// Outputs (flat vectors; octave i's block at [i*W +: W], element k of a block at [k*E +: E]):
//   clamp_o, kind_o    control: wrap mode (1 clamp) and filter kind
//   active_o           active octave count 0..Octaves
//   quad_o             A..J
//   oct_m_o, oct_o_o, oct_a_o, oct_gm_o   M (row-major), o, a, GM = a M^T (row-major)
//   worley_o           C_0..C_3 of the worley unit
//   bl_o, fade_o, oct_lgm_o            control.bandlimit, the fade table, lg ||M||_2 (FilterBandlimit)
//   oct_fm_o                           the octave terms' means a_i mean(n), F format (FilterBandlimit)
//   wcap_o                             the filter-width cap, W's format (FilterWidthCap)
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_regs #(
  `PST_REGS_PARAMS,
  parameter bit Worley         = 1'b0,   // the worley unit's coefficient registers exist
  localparam int FW  = FInt + FFrac,
  localparam int QW  = QuadricInt + QuadricFrac,
  localparam int MW  = MatrixInt + MatrixFrac,
  localparam int OW  = OffsetInt + OffsetFrac,
  localparam int AW  = AmplitudeInt + AmplitudeFrac,
  localparam int GMW = GradMatrixInt + GradMatrixFrac,
  localparam int OctBits = pst_pkg::octave_count_bits(Octaves),  // active octave count 0..Octaves
  localparam int AB  = pst_pkg::RegAddrBits,
  localparam int DB  = pst_pkg::RegDataBits,
  localparam int KB  = pst_pkg::RegControlKindWidth,
  localparam int NQ  = pst_pkg::RegQuadricCount,        // A..J
  localparam int NM  = pst_pkg::RegOctaveMCount,        // M entries
  localparam int NO  = pst_pkg::RegOctaveOCount,        // o entries
  localparam int NGM = pst_pkg::RegOctaveGmCount,       // GM entries
  localparam int NWC = pst_pkg::RegWorleyCount,         // worley coefficients
  localparam int WCW = pst_pkg::WorleyCoefInt + pst_pkg::WorleyCoefFrac,
  localparam int FB  = pst_pkg::FadeBits,
  localparam int FE  = pst_pkg::FadeEntries,
  localparam int LMW = pst_pkg::FadeLgBits,
  localparam int WW  = pst_pkg::w_width(Log2Clut, WidthFrac)   // W's format (the width cap)
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic                       we_i,
  input  logic [AB-1:0]              addr_i,
  input  logic [DB-1:0]              wdata_i,
  output logic                       clamp_o,
  output logic [KB-1:0]              kind_o,
  output logic [OctBits-1:0]         active_o,
  output logic [NQ*QW-1:0]           quad_o,
  output logic [Octaves*NM*MW-1:0]   oct_m_o,
  output logic [Octaves*NO*OW-1:0]   oct_o_o,
  output logic [Octaves*AW-1:0]      oct_a_o,
  output logic [Octaves*NGM*GMW-1:0] oct_gm_o,
  output logic [NWC*WCW-1:0]         worley_o,  // the worley unit's C_k (k at [k*WCW +: WCW])
  output logic                       bl_o,
  output logic [FE*FB-1:0]           fade_o,
  output logic [Octaves*LMW-1:0]     oct_lgm_o,
  output logic [Octaves*FW-1:0]      oct_fm_o,
  output logic [WW-1:0]              wcap_o
);

  localparam int CB = pst_pkg::RegControlBits;
  logic [CB-1:0] ctrl_q;
  logic unused_wdata;   // word bits above a register's format
  assign unused_wdata = ^wdata_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ctrl_q   <= '0;
      active_o <= '0;
      quad_o   <= '0;
      worley_o <= '0;
    end else if (we_i) begin
      if (addr_i == pst_pkg::RegControl) ctrl_q <= wdata_i[CB-1:0];
      if (addr_i == pst_pkg::RegActive) active_o <= wdata_i[OctBits-1:0];
      for (int k = 0; k < NQ; k++) begin
        if (addr_i == pst_pkg::RegQuadric + AB'(k)) quad_o[k*QW +: QW] <= wdata_i[QW-1:0];
      end
      for (int k = 0; k < NWC; k++) begin
        if (Worley && addr_i == pst_pkg::RegWorley + AB'(k)) worley_o[k*WCW +: WCW] <= wdata_i[WCW-1:0];
      end
    end
  end
  assign clamp_o = ctrl_q[pst_pkg::RegControlClampLsb];
  assign kind_o  = ctrl_q[pst_pkg::RegControlKindLsb +: KB];

  // Octave blocks (no reset: the driver writes every octave it enables).
  always_ff @(posedge clk_i) begin
    if (we_i) begin
      for (int i = 0; i < Octaves; i++) begin
        for (int k = 0; k < NM; k++) begin
          if (addr_i == pst_pkg::RegOctave + AB'(pst_pkg::RegOctaveStride * i + pst_pkg::RegOctaveM + k))
            oct_m_o[(i*NM+k)*MW +: MW] <= wdata_i[MW-1:0];
        end
        for (int k = 0; k < NGM; k++) begin
          if (addr_i == pst_pkg::RegOctave + AB'(pst_pkg::RegOctaveStride * i + pst_pkg::RegOctaveGm + k))
            oct_gm_o[(i*NGM+k)*GMW +: GMW] <= wdata_i[GMW-1:0];
        end
        for (int k = 0; k < NO; k++) begin
          if (addr_i == pst_pkg::RegOctave + AB'(pst_pkg::RegOctaveStride * i + pst_pkg::RegOctaveO + k))
            oct_o_o[(i*NO+k)*OW +: OW] <= wdata_i[OW-1:0];
        end
        if (addr_i == pst_pkg::RegOctave + AB'(pst_pkg::RegOctaveStride * i + pst_pkg::RegOctaveA))
          oct_a_o[i*AW +: AW] <= wdata_i[AW-1:0];
      end
    end
  end

  // Bandlimited octaves: the fade table and lg ||M_i||_2 (no reset: the driver writes them).
  if (FilterBandlimit == pst_pkg::FilterBandlimitIsotropic) begin : g_fade
    assign bl_o = ctrl_q[pst_pkg::RegControlBandlimitLsb];
    always_ff @(posedge clk_i) begin
      if (we_i) begin
        for (int k = 0; k < FE; k++) begin
          if (addr_i == pst_pkg::RegFade + AB'(k)) fade_o[k*FB +: FB] <= wdata_i[FB-1:0];
        end
        for (int i = 0; i < Octaves; i++) begin
          if (addr_i == pst_pkg::RegOctave + AB'(pst_pkg::RegOctaveStride * i + pst_pkg::RegOctaveLgm))
            oct_lgm_o[i*LMW +: LMW] <= wdata_i[LMW-1:0];
          if (addr_i == pst_pkg::RegOctave + AB'(pst_pkg::RegOctaveStride * i + pst_pkg::RegOctaveFm))
            oct_fm_o[i*FW +: FW] <= wdata_i[FW-1:0];
        end
      end
    end
  end else begin : g_no_fade
    assign bl_o      = 1'b0;
    assign fade_o    = '0;
    assign oct_lgm_o = '0;
    assign oct_fm_o  = '0;
    logic unused_bl;
    assign unused_bl = ctrl_q[pst_pkg::RegControlBandlimitLsb];
  end

  // The filter-width cap (reset to all ones: no cap until the driver writes one).
  if (FilterWidthCap == pst_pkg::FilterWidthCapOn) begin : g_wcap
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) wcap_o <= {WW{1'b1}};
      else if (we_i && addr_i == pst_pkg::RegWcap) wcap_o <= wdata_i[WW-1:0];
    end
  end else begin : g_no_wcap
    assign wcap_o = {WW{1'b1}};
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (Octaves <= pst_pkg::OctavesMax) else $fatal(1, "pst_regs: too many octaves for the register map");
  end
`endif

endmodule

`default_nettype wire

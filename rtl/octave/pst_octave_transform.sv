// Unit 1 of the texture pipeline (docs/HARDWARE.md): the octave transform p = M s + o of
// one noise octave, reduced to what the noise unit needs (lattice index mod 4096 and fraction).
// Combinational (Regs = 0) or one register inside (Regs = 1). Golden model:
// pst::octaveTransformFx (model/golden/noise_fx.cpp).
//
// Arithmetic, per axis r (exact until the floor):
//   acc_r = sum_j M[r][j] * s[j] + (o[r] << (MatrixFrac + CoordFrac - OffsetFrac))
//           at AccFrac = MatrixFrac + CoordFrac fraction bits (three signed products + offset),
//   p_r   = floor(acc_r to NoiseLatticeFrac fraction bits)  (= acc_r >>> (AccFrac - LF)),
//   frac  = p_r mod 2^NoiseLatticeFrac (unsigned fraction u of the lattice cell),
//   lat   = (floor(p_r) + 576) mod 4096: Rayshade adds 1e6 before truncating and hashes
//           only the low 12 bits of the lattice index; 1e6 mod 4096 = 576. The wrap is exact
//           for the noise (period 4096), so the integer bits above bit AccFrac + 11 are
//           never needed: the sums are kept modulo 2^(AccFrac + 12).
//
// Parameters (names as scripts/profile.py derives them from rtl/configs/NAME.toml):
//   CoordInt, CoordFrac     s, t, r format Q(CoordInt).(CoordFrac)
//   MatrixInt, MatrixFrac   M entries Q(MatrixInt).(MatrixFrac)
//   OffsetInt, OffsetFrac   o entries Q(OffsetInt).(OffsetFrac)
//   NoiseLatticeFrac        fraction bits of u handed to the noise unit (LF)
//   Rows                    3: all three axes; 1: one axis (the caller hands in that row of
//                           M and o: the serial datapath, one row per cycle)
//   Regs                    0: combinational; 1: a pipeline register (pst_delay, en_i) between
//                           the products (with o) and their sum: lat_o, frac_o come one advance
//                           after s_i, m_i, o_i (the parallel datapath's octave_regs = 3)
// Requires MatrixFrac + CoordFrac >= NoiseLatticeFrac and >= OffsetFrac (asserted).
//
// Ports:
//   s_i    3 x CW signed, element k at [k*CW +: CW]
//   m_i    Rows x 3 x MW signed, row-major: element 3*r + c at [(3*r+c)*MW +: MW]
//   o_i    Rows x OW signed
//   lat_o  Rows x pst_pkg::LatticeBits (12) lattice index (after the +576 offset, mod 4096)
//   frac_o Rows x NoiseLatticeFrac-bit unsigned fraction
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_octave_transform #(
  `PST_TRANSFORM_PARAMS,
  parameter int Rows = 3,
  parameter int Regs = 0,
  // Derived widths (do not override).
  localparam int CW = CoordInt + CoordFrac,   // s element width
  localparam int MW = MatrixInt + MatrixFrac, // M element width
  localparam int OW = OffsetInt + OffsetFrac, // o element width
  localparam int LF = NoiseLatticeFrac,
  localparam int LB = pst_pkg::LatticeBits        // one lattice index
) (
  input  logic             clk_i,    // Regs = 1: the register between products and sum
  input  logic             rst_ni,
  input  logic             en_i,
  input  logic [3*CW-1:0] s_i,
  input  logic [Rows*3*MW-1:0] m_i,
  input  logic [Rows*OW-1:0]   o_i,
  output logic [Rows*LB-1:0]        lat_o,
  output logic [Rows*LF-1:0]        frac_o
);

  // Fraction bits of the exact sum (products M s).
  localparam int AccFrac = MatrixFrac + CoordFrac;
  // Left shift bringing o to AccFrac fraction bits.
  localparam int OffShift = AccFrac - OffsetFrac;
  // Only bits [AccFrac - LF, AccFrac + LB) of the sum reach the noise (the fraction and the
  // lattice index mod 4096): the sum is kept modulo 2^KW, KW = AccFrac + LB (exact for those
  // bits; the integer bits above the lattice index are never built).
  localparam int KW = AccFrac + LB;
  // Each product M s is a Booth product modulo 2^KW (rtl/common/pst_mul_booth.sv; Yosys 0.23 builds
  // only AND arrays).
  // Offset of Rayshade's 1e6 lattice shift modulo 4096.
  localparam logic [LB-1:0] LatticeOffset = LB'(pst_pkg::LatticeOffset);

  for (genvar r = 0; r < Rows; r++) begin : g_axis
    logic [3*KW-1:0]  prod_d, prod;  // three products mod 2^KW, j at [j*KW +: KW]
    logic [OW-1:0]    o_r;           // o beside them
    logic [KW-1:0]    off_ext;
    logic [KW-1:0]    acc;

    for (genvar j = 0; j < 3; j++) begin : g_term
      pst_mul_booth #(.AW(CW), .BW(MW), .BSigned(1'b1), .PW(KW)) u_mul (
        .a_i (s_i[j*CW +: CW]),
        .b_i (m_i[(3*r+j)*MW +: MW]),
        .p_o (prod_d[j*KW +: KW])
      );
    end
    pst_delay #(.Width(3*KW + OW), .Depth(Regs)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i ({o_i[r*OW +: OW], prod_d}), .q_o ({o_r, prod})
    );

    if (OffShift > 0) begin : g_off_shift
      assign off_ext = KW'({{KW{o_r[OW-1]}}, o_r, {OffShift{1'b0}}});
    end else begin : g_off_noshift
      assign off_ext = KW'({{KW{o_r[OW-1]}}, o_r});
    end

    assign acc = prod[0 +: KW] + prod[KW +: KW] + prod[2*KW +: KW] + off_ext;

    // floor to LF fraction bits, then split: the low LF bits are u, the next LB the lattice.
    assign frac_o[r*LF +: LF] = acc[AccFrac-LF +: LF];
    assign lat_o[r*LB +: LB]  = acc[AccFrac +: LB] + LatticeOffset;

    // Bits below the LF fraction do not reach the noise.
    if (AccFrac - LF > 0) begin : g_unused_low
      logic unused_acc;
      assign unused_acc = ^acc[AccFrac-LF-1:0];
    end
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (AccFrac < NoiseLatticeFrac) $error("MatrixFrac + CoordFrac must be >= NoiseLatticeFrac");
    if (OffShift < 0) $error("MatrixFrac + CoordFrac must be >= OffsetFrac");
    if (Regs != 0 && Regs != 1) $error("pst_octave_transform: Regs must be 0 or 1");
  end
`endif

endmodule

`default_nettype wire

// Unit-test top for units 1 and 2 (sim/unit/noise_unit_test.cpp): an octave transform and a
// noise unit side by side with independent ports, so each is driven with its own vectors
// (special lattice indices and fractions straight into the noise unit). Combinational.
`include "pst_pkg.sv"
`default_nettype none

module pst_noise_unit_top #(
  parameter int CoordInt = pst_pkg::CoordIntDefault,
  parameter int CoordFrac = pst_pkg::CoordFracDefault,
  parameter int MatrixInt = pst_pkg::MatrixIntDefault,
  parameter int MatrixFrac = pst_pkg::MatrixFracDefault,
  parameter int OffsetInt = pst_pkg::OffsetIntDefault,
  parameter int OffsetFrac = pst_pkg::OffsetFracDefault,
  parameter int NoiseLatticeFrac = pst_pkg::NoiseLatticeFracDefault,
  parameter int NoiseInterp = pst_pkg::NoiseInterpDefault,
  parameter int NoiseCorner = pst_pkg::NoiseCornerDefault,
  parameter int NoiseHash = pst_pkg::NoiseHashDefault,
  parameter int NoiseValueFrac = pst_pkg::NoiseValueFracDefault,
  parameter int NoiseOutFrac = pst_pkg::NoiseOutFracDefault,
  parameter int NoiseSteps = pst_pkg::NoiseStepsDefault,
  parameter int NoiseGuardBits = pst_pkg::NoiseGuardBitsDefault,
  parameter int NoiseGradFrac = pst_pkg::NoiseGradFracDefault,
  localparam int CW = CoordInt + CoordFrac,    // s element width
  localparam int MW = MatrixInt + MatrixFrac,  // M element width
  localparam int OW = OffsetInt + OffsetFrac,  // o element width
  localparam int LF = NoiseLatticeFrac,        // fraction bits of u
  localparam int OF = NoiseOutFrac             // fraction bits of n and grad
) (
  // octave transform
  input  logic [3*CW-1:0]    ot_s_i,
  input  logic [9*MW-1:0]    ot_m_i,
  input  logic [3*OW-1:0]    ot_o_i,
  output logic [pst_pkg::LatticeWidth-1:0] ot_lat_o,
  output logic [3*LF-1:0]         ot_frac_o,
  // noise unit
  input  logic               clk_i,      // pst_noise with NoiseSteps > 1
  input  logic               rst_ni,
  input  logic [2:0]         nz_step_i,
  input  logic               nz_adv_i,
  input  logic [pst_pkg::LatticeWidth-1:0] nz_lat_i,
  input  logic [3*LF-1:0]    nz_frac_i,
  output logic signed [pst_pkg::NoiseIntBits+OF-1:0]  nz_n_o,
  output logic [3*(pst_pkg::NoiseGradIntBits+OF)-1:0] nz_grad_o
);

  pst_octave_transform #(
    .CoordInt         (CoordInt),
    .CoordFrac        (CoordFrac),
    .MatrixInt        (MatrixInt),
    .MatrixFrac       (MatrixFrac),
    .OffsetInt        (OffsetInt),
    .OffsetFrac       (OffsetFrac),
    .NoiseLatticeFrac (NoiseLatticeFrac)
  ) u_octave_transform (
    .clk_i, .rst_ni, .en_i (1'b0),   // Regs = 0: combinational
    .s_i    (ot_s_i),
    .m_i    (ot_m_i),
    .o_i    (ot_o_i),
    .lat_o  (ot_lat_o),
    .frac_o (ot_frac_o)
  );

  pst_noise #(
    .NoiseInterp      (NoiseInterp),
    .NoiseCorner      (NoiseCorner),
    .NoiseHash        (NoiseHash),
    .NoiseValueFrac   (NoiseValueFrac),
    .NoiseLatticeFrac (NoiseLatticeFrac),
    .NoiseOutFrac     (NoiseOutFrac),
    .NoiseSteps       (NoiseSteps),
    .NoiseGuardBits   (NoiseGuardBits),
    .NoiseGradFrac    (NoiseGradFrac),
    .NoiseRegs        (0)   // combinational: the pipelined unit is checked through pst_top
  ) u_noise (
    .clk_i,
    .rst_ni,
    .en_i    (nz_adv_i),
    .valid_i (1'b1),
    .step_i  (nz_step_i),
    .lat_i   (nz_lat_i),
    .frac_i  (nz_frac_i),
    .valid_o (),
    .last_o  (),
    .n_o     (nz_n_o),
    .grad_o  (nz_grad_o)
  );

endmodule

`default_nettype wire

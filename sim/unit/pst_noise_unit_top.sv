// Unit-test top for stages 1 and 2 (sim/unit/noise_unit_test.cpp): an octave transform and a
// noise unit side by side with independent ports, so each is driven with its own vectors
// (special lattice indices and fractions straight into the noise unit). Combinational.
`default_nettype none

module pst_noise_unit_top #(
  parameter int CoordInt = 12,
  parameter int CoordFrac = 20,
  parameter int MatrixInt = 8,
  parameter int MatrixFrac = 16,
  parameter int OffsetInt = 13,
  parameter int OffsetFrac = 16,
  parameter int NoiseLatticeFrac = 16,
  parameter int NoiseInterp = 0,
  parameter int NoiseCorner = 0,
  parameter int NoiseHash = 0,
  parameter int NoiseValueFrac = 15,
  parameter int NoiseOutFrac = 16,
  parameter int NoiseSteps = 1,
  parameter int NoiseGuardBits = 4,
  localparam int CW = CoordInt + CoordFrac,    // s element width
  localparam int MW = MatrixInt + MatrixFrac,  // M element width
  localparam int OW = OffsetInt + OffsetFrac,  // o element width
  localparam int LF = NoiseLatticeFrac,        // fraction bits of u
  localparam int OF = NoiseOutFrac             // fraction bits of n and grad
) (
  // octave transform
  input  wire logic [3*CW-1:0]    ot_s_i,
  input  wire logic [9*MW-1:0]    ot_m_i,
  input  wire logic [3*OW-1:0]    ot_o_i,
  output logic [35:0]             ot_lat_o,
  output logic [3*LF-1:0]         ot_frac_o,
  // noise unit
  input  wire logic               clk_i,      // pst_noise with NoiseSteps > 1
  input  wire logic               rst_ni,
  input  wire logic [2:0]         nz_step_i,
  input  wire logic               nz_adv_i,
  input  wire logic [35:0]        nz_lat_i,
  input  wire logic [3*LF-1:0]    nz_frac_i,
  output logic signed [4+OF-1:0]  nz_n_o,
  output logic [3*(6+OF)-1:0]     nz_grad_o
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
    .NoiseGuardBits   (NoiseGuardBits)
  ) u_noise (
    .clk_i,
    .rst_ni,
    .step_i (nz_step_i),
    .adv_i  (nz_adv_i),
    .lat_i  (nz_lat_i),
    .frac_i (nz_frac_i),
    .n_o    (nz_n_o),
    .grad_o (nz_grad_o)
  );

endmodule

`default_nettype wire

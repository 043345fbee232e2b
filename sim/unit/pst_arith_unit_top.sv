// Unit-test top of the arithmetic units (sim/unit/arith_unit_test.cpp): pst_quadric (and
// pst_quadric_fold),
// pst_octave_term and pst_filter_width side by side, so that one verilated model per profile
// tests all three against the golden model (model/golden/arith_fx.cpp). Besides the profile's
// filter width (fw_w_o, norm FilterNorm) it builds the other two norms too (fw_w_norm_o: one
// WW-bit field per norm 0 euclid, 1 max_half_min, 2 l1) and a stand-alone pst_isqrt of the
// width the euclidean norm uses, so every variant is checked in every profile.
//
// It also holds pst_floor_sat in five fixed formats (fs_*), tested against shiftSatSigned.
//
// Parameters: the profile's, as scripts/profile.py derives them (see each module's header).
`include "pst_pkg.sv"
`default_nettype none

module pst_arith_unit_top #(
  parameter int CoordInt       = pst_pkg::CoordIntDefault,
  parameter int CoordFrac      = pst_pkg::CoordFracDefault,
  parameter int QuadricInt     = pst_pkg::QuadricIntDefault,
  parameter int QuadricFrac    = pst_pkg::QuadricFracDefault,
  parameter int NoiseOutFrac   = pst_pkg::NoiseOutFracDefault,
  parameter int AmplitudeInt   = pst_pkg::AmplitudeIntDefault,
  parameter int AmplitudeFrac  = pst_pkg::AmplitudeFracDefault,
  parameter int GradMatrixInt  = pst_pkg::GradMatrixIntDefault,
  parameter int GradMatrixFrac = pst_pkg::GradMatrixFracDefault,
  parameter int JacobianInt    = pst_pkg::JacobianIntDefault,
  parameter int JacobianFrac   = pst_pkg::JacobianFracDefault,
  parameter int Log2Clut       = pst_pkg::Log2ClutDefault,
  parameter int WidthFrac      = pst_pkg::WidthFracDefault,
  parameter int FilterNorm     = pst_pkg::FilterNormDefault,
  parameter int FInt           = pst_pkg::FIntDefault,
  parameter int FFrac          = pst_pkg::FFracDefault,
  parameter int GradInt        = pst_pkg::GradIntDefault,
  parameter int GradFrac       = pst_pkg::GradFracDefault,
  parameter int OctaveRegs     = pst_pkg::OctaveRegsDefault,   // the serial quadric's product register
  // Derived widths (not profile keys).
  localparam int CW  = CoordInt + CoordFrac,             // one texture coordinate
  localparam int QW  = QuadricInt + QuadricFrac,         // one quadric coefficient
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,                 // noise value
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,                 // one noise gradient component
  localparam int AW  = AmplitudeInt + AmplitudeFrac,     // a_i
  localparam int GMW = GradMatrixInt + GradMatrixFrac,   // one GM entry
  localparam int JW  = JacobianInt + JacobianFrac,       // one Jacobian entry
  localparam int FW  = FInt + FFrac,                     // f
  localparam int GW  = GradInt + GradFrac,               // one grad component
  localparam int WW  = Log2Clut + pst_pkg::WidthExtraIntBits + WidthFrac,         // W
  localparam int SqW = 2 * WW + 1                        // pst_filter_width's sqrt input
) (
  // pst_quadric
  input  logic [3*CW-1:0]   quad_s_i,
  input  logic [10*QW-1:0]  quad_coef_i,
  output logic [FW-1:0]     quad_q_o,
  output logic [3*GW-1:0]   quad_gradq_o,
  // pst_quadric_fold (Regs = 0) on quad_s_i / quad_coef_i, clocked by clk_i: rows 0 and 1 are
  // held at a clock edge with quad_fold_first_i and quad_fold_en_i, row 2 is live after it
  input  logic              quad_fold_en_i,
  input  logic              quad_fold_first_i,
  output logic [FW-1:0]     quad_fold_q_o,
  output logic [3*GW-1:0]   quad_fold_gradq_o,
  // pst_octave_term
  input  logic [NW-1:0]     term_n_i,
  input  logic [3*NGW-1:0]  term_g_i,
  input  logic [AW-1:0]     term_a_i,
  input  logic [9*GMW-1:0]  term_gm_i,
  output logic [FW-1:0]     term_fterm_o,
  output logic [3*GW-1:0]   term_gterm_o,
  // Serial variants (datapath = "serial"), on the same inputs: pst_quadric_serial (stepped
  // by quad_ser_step_i / quad_ser_adv_i, quad_ser_step_next_i: the step after the clock edge) and pst_filter_width #(.Serial(1)) (ser_step_i /
  // ser_adv_i).
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic [pst_pkg::StepBits-1:0] quad_ser_step_i,
  input  logic [pst_pkg::StepBits-1:0] quad_ser_step_next_i,   // the step after the next clock edge
  input  logic              quad_ser_adv_i,
  output logic              quad_ser_done_o,
  input  logic [pst_pkg::StepBits-1:0] ser_step_i,
  input  logic              ser_adv_i,
  output logic [FW-1:0]     quad_ser_q_o,
  output logic [3*GW-1:0]   quad_ser_gradq_o,
  output logic [WW-1:0]     fw_ser_w_o,
  output logic              fw_ser_done_o,
  output logic [WW-1:0]     fw_ser_euclid_w_o,   // the serial euclidean norm, whatever the profile's
  output logic              fw_ser_euclid_done_o,
  // pst_filter_width
  input  logic [3*GW-1:0]   fw_grad_i,
  input  logic [6*JW-1:0]   fw_j_i,
  output logic [WW-1:0]     fw_w_o,
  output logic [3*WW-1:0]   fw_w_norm_o,
  // pst_isqrt
  input  logic [SqW-1:0]    sqrt_x_i,
  output logic [WW:0]       sqrt_y_o,
  // pst_floor_sat in fixed formats (not the profile's): config c's x at [64c +: InWidth],
  // y at [64c +: OutWidth] (arith_unit_test.cpp FloorSat lists the same configs)
  input  logic [5*64-1:0]   fs_x_i,
  output logic [5*64-1:0]   fs_y_o
);

  pst_quadric #(
    .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
    .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
  ) u_quadric (
    .clk_i, .rst_ni, .en_i (1'b0),   // Regs = 0: combinational
    .s_i (quad_s_i), .coef_i (quad_coef_i), .q_o (quad_q_o), .gradq_o (quad_gradq_o)
  );

  pst_quadric_fold #(
    .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
    .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
  ) u_quadric_fold (
    .clk_i, .rst_ni, .en_i (quad_fold_en_i), .first_i (quad_fold_first_i), .first_next_i (1'b0),   // SelReg = 0
    .s_i (quad_s_i), .coef_i (quad_coef_i), .q_o (quad_fold_q_o), .gradq_o (quad_fold_gradq_o)
  );

  pst_quadric_serial #(
    .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
    .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
    , .Regs(OctaveRegs >= 1 ? 1 : 0)   // as pst_octave_stage builds it
  ) u_quadric_ser (
    .clk_i, .rst_ni, .step_i (quad_ser_step_i), .step_next_i (quad_ser_step_next_i), .adv_i (quad_ser_adv_i), .done_o (quad_ser_done_o),
    .s_i (quad_s_i), .coef_i (quad_coef_i), .q_o (quad_ser_q_o), .gradq_o (quad_ser_gradq_o)
  );

  pst_octave_term #(
    .NoiseOutFrac(NoiseOutFrac), .AmplitudeInt(AmplitudeInt), .AmplitudeFrac(AmplitudeFrac),
    .GradMatrixInt(GradMatrixInt), .GradMatrixFrac(GradMatrixFrac), .FInt(FInt),
    .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
  ) u_term (
    .n_i (term_n_i), .g_i (term_g_i), .a_i (term_a_i), .gm_i (term_gm_i), .alpha_i (pst_pkg::FadeBits'(0)), .fm_i ('0),
    .fterm_o (term_fterm_o), .gterm_o (term_gterm_o)
  );

  pst_filter_width #(
    .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
    .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
    .FilterNorm(FilterNorm)
  ) u_width (
    .clk_i, .rst_ni, .step_i ('0), .adv_i (1'b0), .en_i (1'b0), .done_o (),
    .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_w_o)
  );

  pst_filter_width #(
    .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
    .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
    .FilterNorm(FilterNorm), .Serial(1'b1)
  ) u_width_ser (
    .clk_i, .rst_ni, .step_i (ser_step_i), .adv_i (ser_adv_i), .en_i (1'b0), .done_o (fw_ser_done_o),
    .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_ser_w_o)
  );

  pst_filter_width #(
    .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
    .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
    .FilterNorm(pst_pkg::FilterNormEuclid), .Serial(1'b1)
  ) u_width_ser_euclid (
    .clk_i, .rst_ni, .step_i (ser_step_i), .adv_i (ser_adv_i), .en_i (1'b0), .done_o (fw_ser_euclid_done_o),
    .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_ser_euclid_w_o)
  );

  for (genvar n = 0; n < 3; n++) begin : g_norm
    pst_filter_width #(
      .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
      .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
      .FilterNorm(n)
    ) u_width_n (
      .clk_i, .rst_ni, .step_i ('0), .adv_i (1'b0), .en_i (1'b0), .done_o (),
      .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_w_norm_o[n*WW +: WW])
    );
  end

  pst_isqrt #(.InWidth(SqW)) u_isqrt (.clk_i, .rst_ni, .en_i (1'b0), .x_i (sqrt_x_i), .y_o (sqrt_y_o));

  // {InWidth, InFrac, OutWidth, OutFrac}: right shift with saturation, left shift into a wider
  // format, no shift, left shift with saturation, a wide right shift.
  localparam int FsIn[5]     = '{40, 12, 20, 10, 60};
  localparam int FsInFrac[5] = '{20,  4,  6,  2, 30};
  localparam int FsOut[5]    = '{16, 20, 10,  6, 48};
  localparam int FsOutFrac[5] = '{8, 10,  6,  6, 20};
  for (genvar c = 0; c < 5; c++) begin : g_floor_sat
    pst_floor_sat #(
      .InWidth (FsIn[c]), .InFrac (FsInFrac[c]), .OutWidth (FsOut[c]), .OutFrac (FsOutFrac[c])
    ) u_fs (
      .x_i (fs_x_i[64*c +: FsIn[c]]), .y_o (fs_y_o[64*c +: FsOut[c]])
    );
    assign fs_y_o[64*c + FsOut[c] +: 64 - FsOut[c]] = '0;
    logic unused_x;
    assign unused_x = ^fs_x_i[64*c + FsIn[c] +: 64 - FsIn[c]];
  end

endmodule

`default_nettype wire

// Unit-test top of the arithmetic stages (sim/unit/arith_unit_test.cpp): pst_quadric,
// pst_octave_term and pst_filter_width side by side, so that one verilated model per profile
// tests all three against the golden model (model/golden/arith_fx.cpp). Besides the profile's
// filter width (fw_w_o, norm FilterNorm) it builds the other two norms too (fw_w_norm_o: one
// WW-bit field per norm 0 euclid, 1 max_half_min, 2 l1) and a stand-alone pst_isqrt of the
// width the euclidean norm uses, so every variant is checked in every profile.
//
// Parameters: the profile's, as scripts/profile.py derives them (see each module's header).
`default_nettype none

module pst_arith_unit_top #(
  parameter int CoordInt       = 12,
  parameter int CoordFrac      = 20,
  parameter int QuadricInt     = 8,
  parameter int QuadricFrac    = 16,
  parameter int NoiseOutFrac   = 16,
  parameter int AmplitudeInt   = 2,
  parameter int AmplitudeFrac  = 16,
  parameter int GradMatrixInt  = 8,
  parameter int GradMatrixFrac = 16,
  parameter int JacobianInt    = 8,
  parameter int JacobianFrac   = 24,
  parameter int Log2Clut       = 8,
  parameter int WidthFrac      = 8,
  parameter int FilterNorm     = 0,
  parameter int FInt           = 12,
  parameter int FFrac          = 20,
  parameter int GradInt        = 16,
  parameter int GradFrac       = 16,
  // Derived widths (not profile keys).
  localparam int CW  = CoordInt + CoordFrac,             // one texture coordinate
  localparam int QW  = QuadricInt + QuadricFrac,         // one quadric coefficient
  localparam int NW  = 4 + NoiseOutFrac,                 // noise value
  localparam int NGW = 6 + NoiseOutFrac,                 // one noise gradient component
  localparam int AW  = AmplitudeInt + AmplitudeFrac,     // a_i
  localparam int GMW = GradMatrixInt + GradMatrixFrac,   // one GM entry
  localparam int JW  = JacobianInt + JacobianFrac,       // one Jacobian entry
  localparam int FW  = FInt + FFrac,                     // f
  localparam int GW  = GradInt + GradFrac,               // one grad component
  localparam int WW  = Log2Clut + 2 + WidthFrac,         // W
  localparam int SqW = 2 * WW + 1                        // pst_filter_width's sqrt input
) (
  // pst_quadric
  input  logic [3*CW-1:0]   quad_s_i,
  input  logic [10*QW-1:0]  quad_coef_i,
  output logic [FW-1:0]     quad_q_o,
  output logic [3*GW-1:0]   quad_gradq_o,
  // pst_octave_term
  input  logic [NW-1:0]     term_n_i,
  input  logic [3*NGW-1:0]  term_g_i,
  input  logic [AW-1:0]     term_a_i,
  input  logic [9*GMW-1:0]  term_gm_i,
  output logic [FW-1:0]     term_fterm_o,
  output logic [3*GW-1:0]   term_gterm_o,
  // Serial variants (datapath = "serial"), on the same inputs: pst_quadric_serial (stepped
  // by quad_ser_step_i / quad_ser_adv_i) and pst_filter_width #(.Serial(1)) (ser_step_i /
  // ser_adv_i).
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic [4:0]        quad_ser_step_i,
  input  logic              quad_ser_adv_i,
  output logic              quad_ser_done_o,
  input  logic [4:0]        ser_step_i,
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
  output logic [WW:0]       sqrt_y_o
);

  pst_quadric #(
    .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
    .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
  ) u_quadric (
    .s_i (quad_s_i), .coef_i (quad_coef_i), .q_o (quad_q_o), .gradq_o (quad_gradq_o)
  );

  pst_quadric_serial #(
    .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
    .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
  ) u_quadric_ser (
    .clk_i, .rst_ni, .step_i (quad_ser_step_i), .adv_i (quad_ser_adv_i), .done_o (quad_ser_done_o),
    .s_i (quad_s_i), .coef_i (quad_coef_i), .q_o (quad_ser_q_o), .gradq_o (quad_ser_gradq_o)
  );

  pst_octave_term #(
    .NoiseOutFrac(NoiseOutFrac), .AmplitudeInt(AmplitudeInt), .AmplitudeFrac(AmplitudeFrac),
    .GradMatrixInt(GradMatrixInt), .GradMatrixFrac(GradMatrixFrac), .FInt(FInt),
    .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
  ) u_term (
    .n_i (term_n_i), .g_i (term_g_i), .a_i (term_a_i), .gm_i (term_gm_i),
    .fterm_o (term_fterm_o), .gterm_o (term_gterm_o)
  );

  pst_filter_width #(
    .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
    .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
    .FilterNorm(FilterNorm)
  ) u_width (
    .clk_i, .rst_ni, .step_i (5'd0), .adv_i (1'b0), .done_o (),
    .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_w_o)
  );

  pst_filter_width #(
    .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
    .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
    .FilterNorm(FilterNorm), .Serial(1'b1)
  ) u_width_ser (
    .clk_i, .rst_ni, .step_i (ser_step_i), .adv_i (ser_adv_i), .done_o (fw_ser_done_o),
    .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_ser_w_o)
  );

  pst_filter_width #(
    .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
    .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
    .FilterNorm(0), .Serial(1'b1)
  ) u_width_ser_euclid (
    .clk_i, .rst_ni, .step_i (ser_step_i), .adv_i (ser_adv_i), .done_o (fw_ser_euclid_done_o),
    .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_ser_euclid_w_o)
  );

  for (genvar n = 0; n < 3; n++) begin : g_norm
    pst_filter_width #(
      .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
      .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
      .FilterNorm(n)
    ) u_width_n (
      .clk_i, .rst_ni, .step_i (5'd0), .adv_i (1'b0), .done_o (),
      .grad_i (fw_grad_i), .j_i (fw_j_i), .w_o (fw_w_norm_o[n*WW +: WW])
    );
  end

  pst_isqrt #(.InWidth(SqW)) u_isqrt (.x_i (sqrt_x_i), .y_o (sqrt_y_o));

endmodule

`default_nettype wire

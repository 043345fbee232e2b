// pst_quadric_out: the quadric's results brought to their formats (part of pst_quadric and
// pst_quadric_fold, unit 3 of docs/HARDWARE.md), combinational:
//   q_o     = sat_F(floor(q_i to FFrac))            q_i exact, QuadricFrac + 2 CoordFrac fraction bits
//   gradq_o = sat_Grad(floor(2 v_r to GradFrac))    per component, v_i exact, QuadricFrac + CoordFrac
// (floor and saturation: pst_floor_sat). Golden model: the end of quadricFx in
// model/golden/arith_fx.cpp.
//
// Parameters: the formats of s, Q, f and grad f (pst_quadric's); the widths of q_i and v_r
// follow from them as in pst_quadric (QXW = QW + 2 CW + 3, VW = QW + CW + 1).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_quadric_out #(
  `PST_QUADRIC_PARAMS,
  localparam int CW  = CoordInt + CoordFrac,
  localparam int QW  = QuadricInt + QuadricFrac,
  localparam int FW  = FInt + FFrac,
  localparam int GW  = GradInt + GradFrac,
  localparam int VW  = QW + CW + 1,        // v_r
  localparam int QXW = QW + 2 * CW + 3     // q
) (
  input  logic [QXW-1:0]  q_i,
  input  logic [3*VW-1:0] v_i,       // v_r at [r*VW +: VW]
  output logic [FW-1:0]   q_o,
  output logic [3*GW-1:0] gradq_o    // component r at [r*GW +: GW]
);

  pst_floor_sat #(
    .InWidth (QXW), .InFrac (QuadricFrac + 2 * CoordFrac), .OutWidth (FW), .OutFrac (FFrac)
  ) u_q_sat (
    .x_i (q_i), .y_o (q_o)
  );

  // grad q = 2 v (v << 1, exact), floor to GradFrac, saturate to GW bits.
  for (genvar r = 0; r < 3; r++) begin : g_grad
    pst_floor_sat #(
      .InWidth (VW + 1), .InFrac (QuadricFrac + CoordFrac), .OutWidth (GW), .OutFrac (GradFrac)
    ) u_grad_sat (
      .x_i ({v_i[r*VW +: VW], 1'b0}), .y_o (gradq_o[r*GW +: GW])
    );
  end

endmodule

`default_nettype wire

// pst_octave_accum: the accumulation at the end of the octave stage (eq. 1): f = q + sum of the
// active octaves' terms a_i n(T_i s), grad f = grad q + sum of a_i M_i^T grad n. Every cycle
// with acc_en_i adds the lanes' terms (acc_first_i: from zero); f_o and grad_o are the running
// sum plus the quadric, saturated to the F and Grad formats, the fragment's result when its
// datapath says so (valid_o). The sums are exact (AccGuard bits hold q and Octaves terms), so
// the order of the terms does not change a bit.
//
// Parameters:
//   Octaves, NoiseUnits   the terms summed (their count sets the guard bits), lanes per cycle.
//   FInt, FFrac           f format (q, fterm_i, f_o).
//   GradInt, GradFrac     grad f component format (gradq_i, gterm_i, grad_o).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_octave_accum #(
  `PST_ACCUM_PARAMS,
  localparam int FW        = FInt + FFrac,
  localparam int GW        = GradInt + GradFrac,
  localparam int AccGuard  = $clog2(Octaves + 1) + 1,
  localparam int FAccW     = FW + AccGuard,
  localparam int GAccW     = GW + AccGuard
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic                       acc_en_i,
  input  logic                       acc_first_i,
  input  logic [NoiseUnits*FW-1:0]   fterm_i,    // lane u at [u*FW +: FW]
  input  logic [NoiseUnits*3*GW-1:0] gterm_i,    // lane u, component k at [(3u + k)*GW +: GW]
  input  logic [FW-1:0]              q_i,
  input  logic [3*GW-1:0]            gradq_i,
  output logic [FW-1:0]              f_o,
  output logic [3*GW-1:0]            grad_o
);

  logic signed [FAccW-1:0] facc_q, facc_d, fsum, fout;
  logic [3*GAccW-1:0]      gacc_q, gacc_d, gsum, gout;

  always_comb begin
    logic signed [GAccW-1:0] gc;
    fsum = acc_first_i ? '0 : facc_q;
    for (int u = 0; u < NoiseUnits; u++) fsum = fsum + FAccW'($signed(fterm_i[u*FW +: FW]));
    fout = fsum + FAccW'($signed(q_i));
    for (int k = 0; k < 3; k++) begin
      gc = acc_first_i ? '0 : $signed(gacc_q[k*GAccW +: GAccW]);
      for (int u = 0; u < NoiseUnits; u++) gc = gc + GAccW'($signed(gterm_i[(3*u + k)*GW +: GW]));
      gsum[k*GAccW +: GAccW] = gc;
      gout[k*GAccW +: GAccW] = gc + GAccW'($signed(gradq_i[k*GW +: GW]));
    end
    facc_d = acc_en_i ? fsum : facc_q;
    gacc_d = acc_en_i ? gsum : gacc_q;
  end

  // Saturate to the F and Grad formats (the sums are already at their fraction bits).
  pst_floor_sat #(.InWidth (FAccW), .InFrac (FFrac), .OutWidth (FW), .OutFrac (FFrac)) u_f_sat (
    .x_i (fout), .y_o (f_o)
  );
  for (genvar k = 0; k < 3; k++) begin : g_grad_sat
    pst_floor_sat #(.InWidth (GAccW), .InFrac (GradFrac), .OutWidth (GW), .OutFrac (GradFrac)) u_sat (
      .x_i (gout[k*GAccW +: GAccW]), .y_o (grad_o[k*GW +: GW])
    );
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      facc_q <= '0;
      gacc_q <= '0;
    end else begin
      facc_q <= facc_d;
      gacc_q <= gacc_d;
    end
  end

endmodule

`default_nettype wire

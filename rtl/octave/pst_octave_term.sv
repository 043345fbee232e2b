// Octave term (unit 4 of docs/HARDWARE.md, one octave): the contribution a_i n(T_i s) of one
// octave to f and a_i M_i^T grad n to grad_s f (eq. 1, 10, 12). Combinational. The sum of q
// and the active octaves' terms, and its saturation, is done by the integrator (pst_top) at
// a width that holds every term exactly. Golden model: octaveTermFx in
// model/golden/arith_fx.cpp (same steps, bit for bit).
//
//   fterm_o    = sat_F(floor(a n to FFrac))                      a n exact at AmplitudeFrac + NoiseOutFrac
//   gterm_o[r] = sat_Grad(floor(sum_c GM[r][c] g[c] to GradFrac)) exact at GradMatrixFrac + NoiseOutFrac
// Every product is a radix-4 Booth product (pst_mul_booth; g_i, n_i and alpha_i recoded).
// floor = arithmetic shift right (a left shift, exact, if the target has more fraction bits);
// sat = clamp to the signed output width. With Bandlimit (filter.bandlimit = isotropic) both are
// then faded by the octave's alpha_i (pst_octave_fade; octaveTermFx, fadeToMeanFx, fadeScaleFx),
// the value toward the term's mean fm_i (the octave's register: a mean(n)), the gradient to 0:
//   fterm_o = sat_F(floor((fterm - fm) alpha / 2^FadeFrac) + fm)     (alpha = 1.0: fterm)
//   gterm_o[r] = floor(gterm[r] alpha / 2^FadeFrac)                   (|alpha| <= 1: no saturation)
//
// Parameters:
//   NoiseOutFrac                    fraction bits of n_i (Q4.NoiseOutFrac) and g_i (Q6.NoiseOutFrac).
//   AmplitudeInt, AmplitudeFrac     a_i format.
//   GradMatrixInt, GradMatrixFrac   GM = a_i M_i^T entry format (a driver-rounded register).
//   FInt, FFrac                     fterm_o format (the colour index f).
//   GradInt, GradFrac               gterm_o component format (grad_s f).
//   Rows                            3: all of GM g; 1: one row (the caller hands in that row of
//                                   GM: the serial datapath, one row per cycle).
//   Bandlimit                       1: fade by alpha_i (1 + Rows multipliers); 0: alpha_i unused.
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_octave_term #(
  `PST_TERM_PARAMS,
  parameter int Rows           = 3,
  parameter bit Bandlimit      = 1'b0,
  // Derived widths (not profile keys).
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,                  // noise value Q4.NoiseOutFrac
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,                  // noise gradient Q6.NoiseOutFrac
  localparam int AW  = AmplitudeInt + AmplitudeFrac,      // a_i
  localparam int GMW = GradMatrixInt + GradMatrixFrac,    // one GM entry
  localparam int FW  = FInt + FFrac,                      // fterm_o
  localparam int GW  = GradInt + GradFrac,                // one gterm_o component
  localparam int FB  = pst_pkg::FadeBits                  // alpha_i
) (
  input  logic [NW-1:0]    n_i,       // noise value
  input  logic [3*NGW-1:0] g_i,       // noise gradient dn/dp; element k at [k*NGW +: NGW]
  input  logic [AW-1:0]    a_i,       // amplitude
  input  logic [Rows*3*GMW-1:0] gm_i,  // GM = a M^T row-major: GM[r][c] at [(3r+c)*GMW +: GMW]
  input  logic [FB-1:0]         alpha_i, // the octave's fade, FadeFrac fraction bits (Bandlimit)
  input  logic [FW-1:0]         fm_i,    // the term's mean the fade goes to, F format (Bandlimit)
  output logic [FW-1:0]         fterm_o,
  output logic [Rows*GW-1:0]    gterm_o    // element r at [r*GW +: GW]
);

  // a n: a signed AW x NW product fits AW + NW bits.
  localparam int PW  = AW + NW;
  // GM . g: three GMW x NGW products, |sum| <= 3 * 2^(GMW+NGW-2) -> GMW + NGW + 2 bits.
  localparam int DW  = GMW + NGW + 2;

  // The saturated terms before the fade.
  logic [FW-1:0]      f_sat;
  logic [Rows*GW-1:0] g_sat;

  // fterm = sat_F(floor(a n to FFrac)).
  logic signed [PW-1:0] an;
  pst_mul_booth #(.AW(NW), .BW(AW), .BSigned(1'b1), .PW(PW)) u_an (.a_i(n_i), .b_i(a_i), .p_o(an));
  pst_floor_sat #(
    .InWidth (PW), .InFrac (AmplitudeFrac + NoiseOutFrac), .OutWidth (FW), .OutFrac (FFrac)
  ) u_f_sat (
    .x_i (an), .y_o (f_sat)
  );

  // gterm_r = sat_Grad(floor(sum_c GM[r][c] g[c] to GradFrac)).
  for (genvar r = 0; r < Rows; r++) begin : g_row
    logic signed [DW-1:0] dot;
    logic [3*DW-1:0] pr;
    for (genvar c = 0; c < 3; c++) begin : g_c
      pst_mul_booth #(.AW(GMW), .BW(NGW), .BSigned(1'b1), .PW(DW)) u_m (
        .a_i(gm_i[(3*r+c)*GMW +: GMW]), .b_i(g_i[c*NGW +: NGW]), .p_o(pr[c*DW +: DW]));
    end
    assign dot = pr[0 +: DW] + pr[DW +: DW] + pr[2*DW +: DW];
    pst_floor_sat #(
      .InWidth (DW), .InFrac (GradMatrixFrac + NoiseOutFrac), .OutWidth (GW), .OutFrac (GradFrac)
    ) u_g_sat (
      .x_i (dot), .y_o (g_sat[r*GW +: GW])
    );
  end

  // The fade: floor(v alpha / 2^FadeFrac), alpha unsigned (Booth products, alpha recoded).
  if (Bandlimit) begin : g_fade
    localparam int FPW = FW + 1 + FB + 1;
    localparam int GPW = GW + FB + 1;
    logic signed [FW:0]    fd;     // fterm - fm (FW + 1 bits)
    logic signed [FPW-1:0] fp;
    logic signed [FW+1:0]  fs;     // floor(fd alpha / 2^FadeFrac) + fm
    assign fd = (FW+1)'($signed(f_sat)) - (FW+1)'($signed(fm_i));
    pst_mul_booth #(.AW(FW + 1), .BW(FB), .BSigned(1'b0), .PW(FPW)) u_fp (
      .a_i(fd), .b_i(alpha_i), .p_o(fp));
    assign fs = (FW+2)'($signed(fp[pst_pkg::FadeFrac +: FW + 1])) + (FW+2)'($signed(fm_i));
    pst_floor_sat #(.InWidth (FW + 2), .InFrac (0), .OutWidth (FW), .OutFrac (0)) u_fs_sat (
      .x_i (fs), .y_o (fterm_o));
    for (genvar r = 0; r < Rows; r++) begin : g_row
      logic signed [GPW-1:0] gp;
      pst_mul_booth #(.AW(GW), .BW(FB), .BSigned(1'b0), .PW(GPW)) u_gp (
        .a_i(g_sat[r*GW +: GW]), .b_i(alpha_i), .p_o(gp));
      assign gterm_o[r*GW +: GW] = gp[pst_pkg::FadeFrac +: GW];
      logic unused_gp;
      assign unused_gp = ^{gp[GPW-1:pst_pkg::FadeFrac+GW], gp[pst_pkg::FadeFrac-1:0]};
    end
    logic unused_fp;
    assign unused_fp = ^{fp[FPW-1:pst_pkg::FadeFrac+FW+1], fp[pst_pkg::FadeFrac-1:0]};
  end else begin : g_whole
    assign fterm_o = f_sat;
    assign gterm_o = g_sat;
    logic unused_alpha;
    assign unused_alpha = ^{alpha_i, fm_i};
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (AmplitudeInt >= 1 && GradMatrixInt >= 1 && FInt >= 1 && GradInt >= 1)
      else $error("pst_octave_term: every format needs its sign bit (Int >= 1)");
  end
`endif

endmodule

`default_nettype wire

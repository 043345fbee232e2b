// Octave term (stage 4 of docs/HARDWARE.md, one octave): the contribution a_i n(T_i s) of one
// octave to f and a_i M_i^T grad n to grad_s f (eq. 1, 10, 12). Combinational. The sum of q
// and the active octaves' terms, and its saturation, is done by the integrator (pst_top) at
// a width that holds every term exactly. Golden model: octaveTermFx in
// model/golden/arith_fx.cpp (same steps, bit for bit).
//
//   fterm_o    = sat_F(floor(a n to FFrac))                      a n exact at AmplitudeFrac + NoiseOutFrac
//   gterm_o[r] = sat_Grad(floor(sum_c GM[r][c] g[c] to GradFrac)) exact at GradMatrixFrac + NoiseOutFrac
// floor = arithmetic shift right (a left shift, exact, if the target has more fraction bits);
// sat = clamp to the signed output width.
//
// Parameters:
//   NoiseOutFrac                    fraction bits of n_i (Q4.NoiseOutFrac) and g_i (Q6.NoiseOutFrac).
//   AmplitudeInt, AmplitudeFrac     a_i format.
//   GradMatrixInt, GradMatrixFrac   GM = a_i M_i^T entry format (a driver-rounded register).
//   FInt, FFrac                     fterm_o format (the colour index f).
//   GradInt, GradFrac               gterm_o component format (grad_s f).
//   Rows                            3: all of GM g; 1: one row (the caller hands in that row of
//                                   GM: the serial datapath, one row per cycle).
`default_nettype none

module pst_octave_term #(
  parameter int NoiseOutFrac   = 16,
  parameter int AmplitudeInt   = 2,
  parameter int AmplitudeFrac  = 16,
  parameter int GradMatrixInt  = 8,
  parameter int GradMatrixFrac = 16,
  parameter int FInt           = 12,
  parameter int FFrac          = 20,
  parameter int GradInt        = 16,
  parameter int GradFrac       = 16,
  parameter int Rows           = 3,
  // Derived widths (not profile keys).
  localparam int NW  = 4 + NoiseOutFrac,                  // noise value Q4.NoiseOutFrac
  localparam int NGW = 6 + NoiseOutFrac,                  // noise gradient Q6.NoiseOutFrac
  localparam int AW  = AmplitudeInt + AmplitudeFrac,      // a_i
  localparam int GMW = GradMatrixInt + GradMatrixFrac,    // one GM entry
  localparam int FW  = FInt + FFrac,                      // fterm_o
  localparam int GW  = GradInt + GradFrac                 // one gterm_o component
) (
  input  logic [NW-1:0]    n_i,       // noise value
  input  logic [3*NGW-1:0] g_i,       // noise gradient dn/dp; element k at [k*NGW +: NGW]
  input  logic [AW-1:0]    a_i,       // amplitude
  input  logic [Rows*3*GMW-1:0] gm_i,  // GM = a M^T row-major: GM[r][c] at [(3r+c)*GMW +: GMW]
  output logic [FW-1:0]         fterm_o,
  output logic [Rows*GW-1:0]    gterm_o    // element r at [r*GW +: GW]
);

  // a n: a signed AW x NW product fits AW + NW bits.
  localparam int PW  = AW + NW;
  // GM . g: three GMW x NGW products, |sum| <= 3 * 2^(GMW+NGW-2) -> GMW + NGW + 2 bits.
  localparam int DW  = GMW + NGW + 2;
  // Shifts from the exact fraction bits to the output formats (negative = left shift).
  localparam int FSh  = AmplitudeFrac + NoiseOutFrac - FFrac;
  localparam int GSh  = GradMatrixFrac + NoiseOutFrac - GradFrac;
  localparam int FShR = (FSh > 0) ? FSh : 0;
  localparam int FShL = (FSh < 0) ? -FSh : 0;
  localparam int GShR = (GSh > 0) ? GSh : 0;
  localparam int GShL = (GSh < 0) ? -GSh : 0;
  // Shifted widths: room for the left shift and for the output's sign check.
  localparam int FSW = (PW + FShL > FW) ? PW + FShL : FW + 1;
  localparam int GSW = (DW + GShL > GW) ? DW + GShL : GW + 1;

  // fterm = sat_F(floor(a n to FFrac)).
  logic signed [PW-1:0]  an;
  logic signed [FSW-1:0] fs;
  assign an = PW'($signed(a_i)) * PW'($signed(n_i));
  assign fs = (FSW'(an) <<< FShL) >>> FShR;
  always_comb begin
    if (fs[FSW-1:FW-1] == '0 || fs[FSW-1:FW-1] == '1) fterm_o = fs[FW-1:0];
    else fterm_o = {fs[FSW-1], {(FW-1){~fs[FSW-1]}}};
  end

  // gterm_r = sat_Grad(floor(sum_c GM[r][c] g[c] to GradFrac)).
  for (genvar r = 0; r < Rows; r++) begin : g_row
    logic signed [DW-1:0]  dot;
    logic signed [GSW-1:0] gs;
    assign dot = DW'($signed(gm_i[(3*r+0)*GMW +: GMW])) * DW'($signed(g_i[0*NGW +: NGW])) +
                 DW'($signed(gm_i[(3*r+1)*GMW +: GMW])) * DW'($signed(g_i[1*NGW +: NGW])) +
                 DW'($signed(gm_i[(3*r+2)*GMW +: GMW])) * DW'($signed(g_i[2*NGW +: NGW]));
    assign gs = (GSW'(dot) <<< GShL) >>> GShR;
    always_comb begin
      if (gs[GSW-1:GW-1] == '0 || gs[GSW-1:GW-1] == '1) gterm_o[r*GW +: GW] = gs[GW-1:0];
      else gterm_o[r*GW +: GW] = {gs[GSW-1], {(GW-1){~gs[GSW-1]}}};
    end
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

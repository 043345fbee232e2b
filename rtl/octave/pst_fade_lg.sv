// Footprint lg (bandlimited octaves, filter.bandlimit = isotropic; docs/HARDWARE.md unit 4):
// lg of a Jacobian column's length L (pst_fade_norm), once per pixel, for the fade units
// (pst_octave_fade); the second half of fadeLgFx in model/golden/arith_fx.cpp (bit for bit).
// Combinational.
//
//   lg_o = 2^FadeLgFrac (P - JacobianFrac) + the FadeLgFrac bits below L's leading one (bit P)
//        (Mitchell's lg(1 + m) ~ m, under 0.09 octave low)
//
// Parameters:
//   JacobianInt, JacobianFrac   the Jacobian entry format (L has JacobianFrac fraction bits).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_fade_lg #(
  `PST_JACOBIAN_PARAMS,
  localparam int JW  = JacobianInt + JacobianFrac,
  localparam int LF  = pst_pkg::FadeLgFrac,
  // lg_o in [-2^LF JacobianFrac, 2^LF (JW - JacobianFrac)): signed LgW bits.
  localparam int LgW = pst_pkg::fade_lg_width(JW)
) (
  input  logic [JW-1:0]  len_i,   // L >= 1
  output logic [LgW-1:0] lg_o
);

  logic [$clog2(JW)-1:0] lead;
  logic [JW+LF-1:0]      ext, sh;
  logic [LF-1:0]         mant;

  always_comb begin
    lead = '0;
    for (int b = 0; b < JW; b++) begin
      if (len_i[b]) lead = ($clog2(JW))'(b);
    end
    // The LF bits below the leading one: bit k of mant is L[lead - LF + k] (0 below bit 0).
    ext  = {len_i, LF'(0)};
    sh   = ext >> lead;
    mant = sh[LF-1:0];
  end

  logic signed [LgW-1:0] lead_s;
  assign lead_s = LgW'(lead);
  assign lg_o   = ((lead_s - LgW'(JacobianFrac)) <<< LF) + LgW'(mant);

  logic unused_sh;
  assign unused_sh = ^sh[JW+LF-1:LF];

endmodule

`default_nettype wire

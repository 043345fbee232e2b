// Footprint lg (bandlimited octaves, filter.bandlimit = isotropic; docs/HARDWARE.md stage 4):
// the lg length of one Jacobian column e, once per pixel, for the fade units (pst_octave_fade).
// Combinational. Golden model: fadeLgFx in model/golden/arith_fx.cpp (bit for bit).
//
//   v_k = |e_k|, mx = max v_k, r = v_0 + v_1 + v_2 - mx
//   L   = mx + floor(r / 4) + floor(r / 8)       max + 3/8 (mid + min): within -3 % .. +13.2 % of |e|
//   lg_o = 2^FadeLgFrac (P - JacobianFrac) + the FadeLgFrac bits below L's leading one (bit P)
//        (Mitchell's lg(1 + m) ~ m, under 0.09 octave low); L = 0 counts as L = 1.
//
// Parameters:
//   JacobianInt, JacobianFrac   the Jacobian entry format.
`include "pst_pkg.sv"
`default_nettype none

module pst_fade_lg #(
  parameter int JacobianInt  = pst_pkg::JacobianIntDefault,
  parameter int JacobianFrac = pst_pkg::JacobianFracDefault,
  localparam int JW  = JacobianInt + JacobianFrac,
  localparam int LF  = pst_pkg::FadeLgFrac,
  // lg_o in [-2^LF JacobianFrac, 2^LF (JW - JacobianFrac)): signed LgW bits.
  localparam int LgW = $clog2((JW + 1) << LF) + 1
) (
  input  logic [3*JW-1:0] e_i,   // one column: element k at [k*JW +: JW]
  output logic [LgW-1:0]  lg_o
);

  // |e_k| <= 2^(JW-1) fits JW bits unsigned; L < 1.75 * 2^(JW-1) < 2^JW.
  logic [JW-1:0]   v [3];
  logic [JW-1:0]   mx;
  logic [JW+1:0]   sum, r;
  logic [JW-1:0]   len;
  logic [$clog2(JW)-1:0] lead;
  logic [JW+LF-1:0] ext, sh;
  logic [LF-1:0]   mant;

  always_comb begin
    for (int k = 0; k < 3; k++) begin
      v[k] = e_i[k*JW + JW - 1] ? JW'(-e_i[k*JW +: JW]) : e_i[k*JW +: JW];
    end
    mx = v[0];
    if (v[1] > mx) mx = v[1];
    if (v[2] > mx) mx = v[2];
    sum = (JW+2)'(v[0]) + (JW+2)'(v[1]) + (JW+2)'(v[2]);
    r   = sum - (JW+2)'(mx);
    len = JW'((JW+2)'(mx) + (r >> 2) + (r >> 3));
    if (len == '0) len = JW'(1);
    lead = '0;
    for (int b = 0; b < JW; b++) begin
      if (len[b]) lead = ($clog2(JW))'(b);
    end
    // The LF bits below the leading one: bit k of mant is L[lead - LF + k] (0 below bit 0).
    ext  = {len, LF'(0)};
    sh   = ext >> lead;
    mant = sh[LF-1:0];
  end

  logic signed [LgW-1:0] lead_s;
  assign lead_s = LgW'(lead);
  assign lg_o   = ((lead_s - LgW'(JacobianFrac)) <<< LF) + LgW'(mant);

  logic unused_sh;
  assign unused_sh = ^sh[JW+LF-1:LF];

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (JW >= 2) else $error("pst_fade_lg: the Jacobian needs at least 2 bits");
  end
`endif

endmodule

`default_nettype wire

// Footprint length (bandlimited octaves, filter.bandlimit = isotropic; docs/HARDWARE.md unit
// 4): the cheap length of one Jacobian column e, once per pixel, the first half of fadeLgFx in
// model/golden/arith_fx.cpp (bit for bit); pst_fade_lg takes its lg. Combinational.
//
//   v_k = |e_k|, mx = max v_k, r = v_0 + v_1 + v_2 - mx
//   len_o = max(1, mx + floor(r / 4) + floor(r / 8))   max + 3/8 (mid + min): within -3 % .. +13.2 %
//                                                      of |e|; 0 counts as 1 (one LSB)
//
// Parameters:
//   JacobianInt, JacobianFrac   the Jacobian entry format.
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_fade_norm #(
  `PST_JACOBIAN_PARAMS,
  localparam int JW = JacobianInt + JacobianFrac
) (
  input  logic [3*JW-1:0] e_i,     // one column: element k at [k*JW +: JW]
  output logic [JW-1:0]   len_o    // unsigned, JacobianFrac fraction bits (< 1.75 * 2^(JW-1))
);

  // |e_k| <= 2^(JW-1) fits JW bits unsigned.
  logic [JW-1:0] v [3];
  logic [JW-1:0] mx;
  logic [JW+1:0] sum, r;
  logic [JW-1:0] len;

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
  end
  assign len_o = len;

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (JW >= 2) else $error("pst_fade_norm: the Jacobian needs at least 2 bits");
  end
`endif

endmodule

`default_nettype wire

// pst_fade_norm_sva: checker of pst_fade_norm (the footprint length of one Jacobian column):
// the length is never 0, never below the largest |e_k| and at most 7/4 of it (max + 3/8 of
// the two others, each <= max); recomputed here from e_i with wider, signed arithmetic.
// Cover points (combinational: reached by the module's inputs, valid fragment or not): the
// zero column (length clamped to 1), the most negative entry (|e| = 2^(JW-1)), the maximum in
// each element.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_fade_norm_sva #(
  parameter int JW = 2
) (
  input logic [3*JW-1:0] e_i,
  input logic [JW-1:0]   len_o
);
  logic [JW+3:0] a [3];
  logic [JW+3:0] mx, len;
  always_comb begin
    for (int k = 0; k < 3; k++) begin
      logic signed [JW+3:0] s;
      s = (JW+4)'($signed(e_i[k*JW +: JW]));
      a[k] = s < 0 ? -s : s;
    end
    mx = a[0];
    for (int k = 1; k < 3; k++) if (a[k] > mx) mx = a[k];
    len = (JW+4)'(len_o);
    `PST_ASSERT_I(NotZero, len_o != '0)
    `PST_ASSERT_I(AtLeastMax, len >= mx)
    `PST_ASSERT_I(AtMostSevenQuartersMax, mx == '0 ? (len == 1) : (4 * len <= 7 * mx))
    `PST_COVER_I(ZeroColumn, mx == '0)
    `PST_COVER_I(MostNegative, e_i[JW-1:0] == {1'b1, {(JW-1){1'b0}}})
    `PST_COVER_I(MaxInX, mx != '0 && a[0] == mx)
    `PST_COVER_I(MaxInY, mx != '0 && a[1] == mx && a[0] < mx)
    `PST_COVER_I(MaxInZ, mx != '0 && a[2] == mx && a[0] < mx && a[1] < mx)
  end
endmodule

bind pst_fade_norm pst_fade_norm_sva #(.JW(JW)) u_sva (.*);

`default_nettype wire

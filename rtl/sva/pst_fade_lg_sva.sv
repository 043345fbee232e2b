// pst_fade_lg_sva: checker of pst_fade_lg (Mitchell's lg of a footprint length L): for L >= 1
// the integer part of lg_o (floor(lg_o / 2^LF)) + JacobianFrac is the position P of L's
// leading one (2^P <= L < 2^(P+1)) and the fraction bits are the LF bits of L below bit P.
// L = 0 only before the first fragment (registers after reset; the length unit never gives
// 0): not checked. Cover points: L = 1 (lowest, lg = -JacobianFrac), L's top bit set, a
// fraction of lg from below bit 0 (P < LF, zero-filled).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_fade_lg_sva #(
  parameter int JW  = 2,
  parameter int JF  = 1,
  parameter int LF  = 1,
  parameter int LgW = 2
) (
  input logic [JW-1:0]  len_i,
  input logic [LgW-1:0] lg_o
);
  int                 p;
  logic [JW+LF-1:0]   lw, frac;
  always_comb begin
    p    = (int'($signed(lg_o)) >>> LF) + JF;   // floor(lg_o / 2^LF) + JacobianFrac
    lw   = {len_i, LF'(0)};
    frac = (p >= 0 && p < JW) ? ((lw >> p) & ((JW+LF)'(1) << LF) - 1) : '0;
    if (len_i != '0) begin
      `PST_ASSERT_I(LeadingOne, p >= 0 && p < JW && (len_i >> p) == JW'(1))
      `PST_ASSERT_I(FractionBits, (JW+LF)'(lg_o[LF-1:0]) == frac)
    end
    `PST_COVER_I(LenOne, len_i == JW'(1))
    `PST_COVER_I(LenTopBit, len_i[JW-1])
    `PST_COVER_I(LenBelowFraction, len_i != '0 && p < LF)
  end
endmodule

bind pst_fade_lg pst_fade_lg_sva #(.JW(JW), .JF(JacobianFrac), .LF(LF), .LgW(LgW)) u_sva (.*);

`default_nettype wire

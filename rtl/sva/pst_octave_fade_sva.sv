// pst_octave_fade_sva: checker of pst_octave_fade (one octave's fade alpha): alpha never
// exceeds 1.0; off (en_i = 0) it is exactly 1.0; the table indices are the quarter-octave
// index of lg nu = lg |J| + lg ||M|| clamped to the table (recomputed here in 32-bit signed
// arithmetic, so a too-narrow sum in the module shows); with both factors <= 1.0 alpha is at
// most the smaller one. Cover points (combinational, per evaluation): off, index clamped below
// / above / inside (x), alpha 0 and alpha 1.0 while on.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_octave_fade_sva #(
  parameter int LgW = 2,
  parameter int LMW = 2,
  parameter int FB  = 2,
  parameter int FE  = 2,
  parameter int IB  = 1
) (
  input logic           en_i,
  input logic [LgW-1:0] lgx_i,
  input logic [LgW-1:0] lgy_i,
  input logic [LMW-1:0] lgm_i,
  input logic [IB-1:0]  ix,
  input logic [IB-1:0]  iy,
  input logic [FB-1:0]  hx,
  input logic [FB-1:0]  hy,
  input logic [FB-1:0]  alpha_o
);
  localparam int One = 1 << pst_pkg::FadeFrac;

  function automatic int qidx(input logic [LgW-1:0] lg, input logic [LMW-1:0] lgm);
    int t;
    t = int'($signed(lg)) + int'($signed(lgm)) + (pst_pkg::FadeLgLo << pst_pkg::FadeLgFrac);
    return t >>> (pst_pkg::FadeLgFrac - 2);
  endfunction

  int qx, qy, ex, ey;
  always_comb begin
    qx = qidx(lgx_i, lgm_i);
    qy = qidx(lgy_i, lgm_i);
    ex = qx < 0 ? 0 : qx > FE - 1 ? FE - 1 : qx;
    ey = qy < 0 ? 0 : qy > FE - 1 ? FE - 1 : qy;
    `PST_ASSERT_I(AtMostOne, 32'(alpha_o) <= One)
    `PST_ASSERT_I(OffIsOne, en_i || 32'(alpha_o) == One)
    `PST_ASSERT_I(IndexX, 32'(ix) == ex)
    `PST_ASSERT_I(IndexY, 32'(iy) == ey)
    `PST_ASSERT_I(AtMostFactors, !(en_i && 32'(hx) <= One && 32'(hy) <= One) ||
                                 (alpha_o <= hx && alpha_o <= hy))
    `PST_COVER_I(Off, !en_i)
    `PST_COVER_I(ClampLow, en_i && qx < 0)
    `PST_COVER_I(ClampHigh, en_i && qx > FE - 1)
    `PST_COVER_I(Inside, en_i && qx >= 0 && qx <= FE - 1)
    `PST_COVER_I(AlphaZero, en_i && alpha_o == '0)
    `PST_COVER_I(AlphaOne, en_i && 32'(alpha_o) == One)
  end
endmodule

bind pst_octave_fade pst_octave_fade_sva #(.LgW(LgW), .LMW(LMW), .FB(FB), .FE(FE), .IB(IB)) u_sva (.*);

`default_nettype wire

// pst_subband_sva: checker of pst_subband (the subband unit): steps in range and in order
// (pst_noise_steps_sva, as pst_noise), and the value sum V inside the bilinear bound:
// |V| <= 2^VBE (a convex combination of the corners' values, each at most K 2^(VB-1) with
// weights of at most 1.0; pst_subband's VBE) when the token beside the sums (tok_s) is valid.
// Cover points: each step entering; the tile's wrap-around (a corner at the tile's last pixel in
// both axes, so that its neighbours are at pixel 0). The token at the output: pst_noise_out_sva.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_subband_sva #(
  parameter int NoiseSteps = 1,
  parameter int TL   = 1,
  parameter int VBE  = 1,
  parameter int VW   = 1,
  parameter int SUMW = 1
) (
  input logic            clk_i,
  input logic            rst_ni,
  input logic            en_i,
  input logic            valid_i,
  input logic [2:0]      step_i,
  input logic [TL-1:0]   x0,
  input logic [TL-1:0]   x1,
  input logic [SUMW-1:0] sum_out,
  input logic [3:0]      tok_s
);
  // Steps in range and in order, a cover point per step.
  pst_noise_steps_sva #(.NoiseSteps(NoiseSteps)) u_steps (.*);

  // |V| of the sums so far: a partial convex combination, so at most the largest corner value
  // times the weights' total 2^(2 WF).
  logic signed [VW-1:0] v;
  logic                 v_bounded;
  assign v = sum_out[0 +: VW];
  assign v_bounded = (v <= $signed(VW'(1) <<< VBE)) && (v >= -($signed(VW'(1) <<< VBE)));

  logic unused_bits;
  assign unused_bits = ^{sum_out[SUMW-1:VW], tok_s[2:0]};

  `PST_ASSERT(ValueBounded, tok_s[3] |-> v_bounded)
  `PST_COVER(TileWrap, en_i && valid_i && x0 == '1 && x1 == '1)
endmodule

bind pst_subband pst_subband_sva #(.NoiseSteps(NoiseSteps), .TL(TL), .VBE(VBE), .VW(VW), .SUMW(SUMW)) u_sva (.*);

`default_nettype wire

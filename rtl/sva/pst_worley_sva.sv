// pst_worley_sva: checker of pst_worley (the worley unit): steps in range and in order
// (pst_noise_steps_sva, as pst_noise); the list of the K nearest candidates is sorted by S
// after every step; after the square roots the distances F_k of a valid token are
// non-decreasing in k and every gradient component g_k,a has |g| <= 1 (2^NF). Cover points:
// each step entering; a later step putting a new nearest point in front (the cube search
// matters); a cube with all M points; the last step's empty slots (NoiseSteps not dividing the
// cube count). The token at the output: pst_noise_out_sva.
`include "sva/pst_assert.svh"
`default_nettype none

module pst_worley_sva #(
  parameter int NoiseSteps = 1,
  parameter int K   = 1,
  parameter int M   = 1,
  parameter int CPS = 1,
  parameter int SW  = 1,
  parameter int EW  = 1,
  parameter int FW  = 1,
  parameter int GKW = 2,
  parameter int NF  = 1
) (
  input logic               clk_i,
  input logic               rst_ni,
  input logic               en_i,
  input logic               valid_i,
  input logic [2:0]         step_i,
  input logic [K*EW-1:0]    list_in,
  input logic [K*EW-1:0]    list_out,
  input logic [CPS-1:0]     cube_on,
  input logic [CPS*M-1:0]   cand_on,
  input logic [3:0]         tok_c,
  input logic [K*FW-1:0]    f_c,
  input logic [K*3*GKW-1:0] g_c
);
  // Steps in range and in order, a cover point per step.
  pst_noise_steps_sva #(.NoiseSteps(NoiseSteps)) u_steps (.*);

  logic sorted, f_sorted, g_bounded, cube_full;
  always_comb begin
    sorted = 1'b1;
    f_sorted = 1'b1;
    for (int k = 1; k < K; k++) begin
      if (list_out[k*EW +: SW] < list_out[(k-1)*EW +: SW]) sorted = 1'b0;
      if (f_c[k*FW +: FW] < f_c[(k-1)*FW +: FW]) f_sorted = 1'b0;
    end
    g_bounded = 1'b1;
    for (int i = 0; i < 3 * K; i++) begin
      logic signed [GKW-1:0] g;
      g = g_c[i*GKW +: GKW];
      if (g > $signed(GKW'(1 << NF)) || g < -$signed(GKW'(1 << NF))) g_bounded = 1'b0;
    end
    cube_full = 1'b0;
    for (int i = 0; i < CPS; i++) if (cand_on[i*M + M - 1]) cube_full = 1'b1;
  end

  logic unused_bits;
  assign unused_bits = ^{list_in[K*EW-1:SW], tok_c[2:0]};

  `PST_ASSERT(ListSorted, valid_i |-> sorted)
  `PST_ASSERT(DistancesSorted, tok_c[3] |-> f_sorted)
  `PST_ASSERT(GradientBounded, tok_c[3] |-> g_bounded)
  `PST_COVER(NewNearestLater, en_i && valid_i && step_i != 3'd0 &&
                              list_out[0 +: SW] < list_in[0 +: SW])
  `PST_COVER(CubeFull, en_i && valid_i && cube_full)
  `PST_COVER(EmptySlots, en_i && valid_i && !cube_on[CPS-1])
endmodule

bind pst_worley pst_worley_sva #(.NoiseSteps(NoiseSteps), .K(K), .M(M), .CPS(CPS), .SW(SW), .EW(EW),
                                 .FW(FW), .GKW(GKW), .NF(NF)) u_sva (.*);

`default_nettype wire

// pst_noise_hash: the noise unit's hash chain (part of rtl/noise/pst_noise.sv, unit 2 of
// docs/HARDWARE.md, step 2 and pipeline boundary b0): the corner indices of the lattice cell
// and the chained table lookups that give each corner of the step its hash h3.
// Golden: pst::noiseFx (model/golden/noise_fx.cpp); model/noise.cpp's noiseHash.
//
// 2. Hash, 2 + 4 + 8 = 14 ROM lookups (corner indices: X in {L_x, L_x + 1 mod 4096}, ...):
//      h1[bx] = T[X_bx], h2[bx,by] = T[h1[bx] ^ Y_by], h3[c] = T[h2[bx,by] ^ Z_bz]
//    NoiseHash = 0 (rayshade): T = Rayshade's 4096 x 12 table (the caller takes m = h3 & 0xff).
//    NoiseHash = 1 (perm256): T = the 256 x 8 permutation, indices L & 0xff (the same as
//    Rayshade's (floor(x) + 1e6) & 0xff, since L = floor(x) + 576 mod 4096).
//    NoiseHash = 2 (perlin256, Perlin 2002): T = ImprovedNoise.java's permutation, the chain
//    adds instead of XOR (h2 = T[(h1 + Y) mod 256], ...), indices X = (L - 64) mod 256 =
//    floor(x) & 255 (576 mod 256 = 64).
//    Corner c = bx + 2 by + 4 bz; the step's corner i is c = step CPS + i (CPS = 8 / NoiseSteps).
//
// The table T (pst_noise_hash_rom, two banks by bit 0): a corner pair's two lookups (X and
// X + 1, or h ^ Y and h ^ (Y + 1), h ^ Z and h ^ (Z + 1)) always differ in bit 0 and take one
// read of each bank (parallel: 7 pairs, 7 read ports per half-size bank instead of 14 on the
// whole table); a lookup without a partner reads both banks (a single port).
//   parallel: pair 0 = X; 1, 2 = h1[bx] ^ Y; 3..6 = h2 ^ Z of corners i, i + 4.
//   serial:   singles 0..CPS-1 = level 2, CPS..2 CPS-1 = level 3, 2 CPS = level 1 when
//             CPS = 1 (else pair 0 = X: corners 2j and 2j + 1).
// Levels 1-2 come before boundary b0, level 3 after it: a register (pst_delay, enabled by
// en_i) holds each corner's h2 and z index when Reg = 1.
//
// Parameters:
//   NoiseHash   0 rayshade 4096 x 12 ROM, 1 perm256 256 x 8 ROM, 2 perlin256 256 x 8 ROM
//               (additive chain)
//   NoiseSteps  cycles per evaluation (1, 2, 4, 8): the corners hashed per step (above)
//   Reg         1: the register at boundary b0 (the profile's noise_regs > 0)
//
// Ports:
//   step_i  the step entering (0..NoiseSteps-1; its corners)
//   lat_i   3 x 12-bit lattice index (after +576, mod 4096), axis k at [12k +: 12]
//   h3_o    the hash of the step's corner i at [i*HW +: HW] (HW = 12 rayshade, else 8), after
//           boundary b0 (of the step that entered Reg advances earlier)
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_noise_hash #(
  `PST_HASH_PARAMS,
  parameter bit Reg = 1'b0,
  localparam int LB = pst_pkg::LatticeBits,                      // one lattice index
  localparam int HW = (NoiseHash == pst_pkg::NoiseHashRayshade) ? LB : 8,
  localparam int CPS = 8 / NoiseSteps                            // corners per step
) (
  input  logic                             clk_i,   // the register at b0
  input  logic                             rst_ni,
  input  logic                             en_i,    // advance
  input  logic [2:0]                       step_i,
  input  logic [pst_pkg::LatticeWidth-1:0] lat_i,
  output logic [CPS*HW-1:0]                h3_o
);

  // ---- corner indices -----------------------------------------------------------------------
  logic [6*HW-1:0]  idx;   // corner indices: axis k, b at [(2k+b)*HW +: HW]

  // perlin256: X = (L - 64) mod 256, i.e. floor(x) & 255 (L = floor(x) + 576 mod 4096).
  localparam int IdxBias = (NoiseHash == pst_pkg::NoiseHashPerlin256) ? pst_pkg::LatticeOffset % 256 : 0;
  for (genvar k = 0; k < 3; k++) begin : g_idx
    logic [LB-1:0] l_this;  // L - IdxBias mod 4096
    logic [LB-1:0] l_next;  // L - IdxBias + 1 mod 4096
    assign l_this = lat_i[LB*k +: LB] - LB'(IdxBias);
    assign l_next = l_this + LB'(1);
    assign idx[(2*k)*HW +: HW]   = l_this[HW-1:0];
    assign idx[(2*k+1)*HW +: HW] = l_next[HW-1:0];
    if (HW < LB) begin : g_unused_high
      logic unused_l;
      assign unused_l = ^{l_this[LB-1:HW], l_next[LB-1:HW]};
    end
  end

  // ---- the table ----------------------------------------------------------------------------
  localparam int Pairs   = (NoiseSteps == 1) ? 7 : (CPS > 1 ? 1 : 0);
  localparam int Singles = (NoiseSteps == 1) ? 0 : 2 * CPS + (CPS == 1 ? 1 : 0);
  localparam int PW = (Pairs > 0) ? Pairs : 1;
  localparam int SW = (Singles > 0) ? Singles : 1;
  logic [PW*HW-1:0] pa0 /*verilator split_var*/, pa1 /*verilator split_var*/;
  logic [PW*HW-1:0] ph0 /*verilator split_var*/, ph1 /*verilator split_var*/;
  logic [SW*HW-1:0] sa /*verilator split_var*/, sh /*verilator split_var*/;
  pst_noise_hash_rom #(`PST_HASH_ROM_PASS, .Pairs(Pairs), .Singles(Singles)) u_hash (
    .pair_a0_i (pa0), .pair_a1_i (pa1), .pair_h0_o (ph0), .pair_h1_o (ph1),
    .single_a_i (sa), .single_h_o (sh)
  );
  // The chain's combining step: XOR (rayshade, perm256) or an HW-bit add (perlin256).
  function automatic logic [HW-1:0] chain_op(logic [HW-1:0] h, logic [HW-1:0] x);
    if (NoiseHash == pst_pkg::NoiseHashPerlin256) chain_op = h + x;
    else chain_op = h ^ x;
  endfunction

  // ---- the chain ----------------------------------------------------------------------------
  // Levels 1-2 (before b0): per corner of the step, h2 and the z index its level 3 takes.
  //   parallel: the lookups shared along the chain (2 + 4 + 8 = 14); serial: three chained
  //   lookups per corner.
  logic [CPS*HW-1:0] h2_d, z_d, h2_q, z_q;   // corner i at [i*HW +: HW]
  if (NoiseSteps == 1) begin : g_hash_par
    logic [2*HW-1:0] h1;   // T[X_bx] at [bx*HW +: HW]
    assign pa0[0 +: HW] = idx[0*HW +: HW];
    assign pa1[0 +: HW] = idx[1*HW +: HW];
    assign h1 = {ph1[0 +: HW], ph0[0 +: HW]};
    for (genvar bx = 0; bx < 2; bx++) begin : g_h2
      assign pa0[(1 + bx)*HW +: HW] = chain_op(h1[bx*HW +: HW], idx[2*HW +: HW]);
      assign pa1[(1 + bx)*HW +: HW] = chain_op(h1[bx*HW +: HW], idx[3*HW +: HW]);
    end
    for (genvar c = 0; c < 8; c++) begin : g_c   // h2 = T[h1 ^ Y_by] of corner c
      assign h2_d[c*HW +: HW] = ((c % 4) < 2) ? ph0[(1 + c % 2)*HW +: HW] : ph1[(1 + c % 2)*HW +: HW];
      assign z_d[c*HW +: HW]  = idx[(4 + c/4)*HW +: HW];
    end
    // Level 3 (after b0): corners i and i + 4 (Z_0 and Z_1) pair up.
    for (genvar i = 0; i < 4; i++) begin : g_h3
      assign pa0[(3 + i)*HW +: HW] = chain_op(h2_q[i*HW +: HW], z_q[i*HW +: HW]);
      assign pa1[(3 + i)*HW +: HW] = chain_op(h2_q[(i + 4)*HW +: HW], z_q[(i + 4)*HW +: HW]);
      assign h3_o[i*HW +: HW]       = ph0[(3 + i)*HW +: HW];
      assign h3_o[(i + 4)*HW +: HW] = ph1[(3 + i)*HW +: HW];
    end
    assign sa = '0;
    logic unused_sh;
    assign unused_sh = ^{sh, step_i};
  end else begin : g_hash_ser
    // The step's corners, three chained lookups each (only the level-1 lookups of corners
    // 2j, 2j + 1, X_0 and X_1, pair up).
    logic [CPS*HW-1:0] h1;
    for (genvar i = 0; i < CPS; i++) begin : g_chain
      logic [2:0]    c;
      logic [HW-1:0] y;
      assign c  = step_i * 3'(CPS) + 3'(i);
      assign y  = c[1] ? idx[3*HW +: HW] : idx[2*HW +: HW];
      assign z_d[i*HW +: HW] = c[2] ? idx[5*HW +: HW] : idx[4*HW +: HW];
      assign sa[i*HW +: HW]   = chain_op(h1[i*HW +: HW], y);
      assign h2_d[i*HW +: HW] = sh[i*HW +: HW];
      // Level 3 (after b0).
      assign sa[(CPS + i)*HW +: HW] = chain_op(h2_q[i*HW +: HW], z_q[i*HW +: HW]);
      assign h3_o[i*HW +: HW]       = sh[(CPS + i)*HW +: HW];
      logic unused_c;
      assign unused_c = c[0];
    end
    if (CPS == 1) begin : g_h1_single
      assign sa[2*HW +: HW] = step_i[0] ? idx[1*HW +: HW] : idx[0*HW +: HW];
      assign h1 = sh[2*HW +: HW];
      assign pa0 = '0;
      assign pa1 = '0;
      logic unused_ph;
      assign unused_ph = ^{ph0, ph1};
    end else begin : g_h1_pairs
      // Corners 2j (x = X_0) and 2j + 1 (X_1) share one read per bank.
      assign pa0 = idx[0*HW +: HW];
      assign pa1 = idx[1*HW +: HW];
      for (genvar j = 0; j < CPS / 2; j++) begin : g_pair
        assign h1[(2*j)*HW +: HW]     = ph0;
        assign h1[(2*j + 1)*HW +: HW] = ph1;
      end
    end
  end
  pst_delay #(.Width(2*CPS*HW), .Depth(Reg ? 1 : 0)) u_b0 (
    .clk_i, .rst_ni, .en_i, .d_i ({z_d, h2_d}), .q_o ({z_q, h2_q})
  );

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (NoiseHash != pst_pkg::NoiseHashRayshade && NoiseHash != pst_pkg::NoiseHashPerm256 &&
        NoiseHash != pst_pkg::NoiseHashPerlin256)
      $error("pst_noise_hash: NoiseHash must be rayshade, perm256 or perlin256");
    if (NoiseSteps != 1 && NoiseSteps != 2 && NoiseSteps != 4 && NoiseSteps != 8)
      $error("pst_noise_hash: NoiseSteps must be 1, 2, 4 or 8");
  end
`endif

endmodule

`default_nettype wire

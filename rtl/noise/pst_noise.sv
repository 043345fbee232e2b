// pst_noise: the noise unit (docs/HARDWARE.md stage 2). Rayshade's Noise3
// (value-plus-gradient lattice noise) and its analytic gradient in fixed point, with the
// cheaper variants as parameters. Combinational when NoiseRegs = 0, else a pipeline (below).
// Golden: pst::noiseFx
// (model/golden/noise_fx.cpp, same steps and floors; the unit tests compare every bit).
//
// Notation: LF = NoiseLatticeFrac, VF = NoiseValueFrac, OF = NoiseOutFrac,
// NF = NodeFrac = OF + NoiseGuardBits (the profile's noise.guard_bits: internal node fraction
// bits below the output LSB), F = GradFloor = NF - NoiseGradFrac when that is > 0, else 0 (the
// profile's noise.grad_frac: the derivative lanes keep min(NoiseGradFrac, NF) fraction bits).
// Corner c = bx + 2 by + 4 bz (x fastest, Rayshade's order).
//
// 1. Weights (pst_noise_weight, one per axis): s (weight of the upper corner) and ds = ds/du,
//    unsigned at LF fraction bits. scurve: u2 = floor(u u), s = floor(u2 (3 - 2u)),
//    ds = 6 (u - u2); linear: s = u, ds = 1.
// 2. Hash, 2 + 4 + 8 = 14 ROM lookups (corner indices: X in {L_x, L_x + 1 mod 4096}, ...):
//      h1[bx] = T[X_bx], h2[bx,by] = T[h1[bx] ^ Y_by], h3[c] = T[h2[bx,by] ^ Z_bz]
//    NoiseHash = 0 (rayshade): T = Rayshade's 4096 x 12 table, m = h3 & 0xff.
//    NoiseHash = 1 (perm256): T = the 256 x 8 permutation, indices L & 0xff (the same as
//    Rayshade's (floor(x) + 1e6) & 0xff, since L = floor(x) + 576 mod 4096), m = h3.
//    NoiseHash = 2 (perlin256, Perlin 2002): T = ImprovedNoise.java's permutation, the chain
//    adds instead of XOR (h2 = T[(h1 + Y) mod 256], ...), indices X = (L - 64) mod 256 =
//    floor(x) & 255 (576 mod 256 = 64), m = h3.
//    This is model/noise.cpp's noiseHash for the same lattice point.
// 3. Value ROM: R[m + k], k = 0..3 (m + 3 <= 258 < 267), Q1.VF = value16 >>> (15 - VF), i.e.
//    the top VF + 1 bits of the 16-bit entry (floor; exact at VF = 15).
// 4. Corners (pst_noise_corner, eight): value_gradient v = 0.5 R[m] + R[m+1] d_x + R[m+2] d_y
//    + R[m+3] d_z exact at VF + LF bits, d = u - b; value v = 0.5 R[m]. Node = (floor(v to NF),
//    R[m+1..3] to NF) (gradient zero for value corners); grad12 (Perlin 2002) reads no value
//    ROM: v = +-d_a +-d_b and the gradient +-1 on axes a, b chosen by m's low four bits.
//    The derivatives are then floored to multiples of 2^F (their F low bits cleared).
// 5. Lerps (pst_noise_lerp, seven): L(x, y) = x + floor((y - x) s / 2^LF) on v; on the three
//    derivatives L_F(x, y) = x + 2^F floor(((y - x) / 2^F) s / 2^LF) (= L when F = 0); the
//    derivative on the lerp's own axis adds 2^F floor(floor((b.v - a.v) / 2^F) ds / 2^LF).
//    Every derivative is a multiple of 2^F: its F low bits are constant zeros in every lerp
//    and register (the products and registers narrow; F = 0 is the exact unit).
//    x: nodes 0..3 from corners (2j, 2j+1); y: nodes 4, 5 from (0, 1), (2, 3); z: node 6.
// 6. Out: n = floor(v to OF) (Q4.OF), grad_k = floor(g_k to OF) (Q6.OF).
//
// Ranges (why the widths hold; they make the contract's saturations no-ops):
//   |R| <= 1, |d| <= 1: |v| <= 0.5 + 3 = 3.5 -> node values Q3.NF (VW = 3 + NF bits); a lerp
//   stays between its inputs, so every node value is Q3; differences b - a are Q4.
//   |b - a| < 6 for any two nodes of one lerp; the derivative on the own axis is at most
//   ds_max |b - a| + max|g| <= 1.5 * 6 + 1 (+ a few LSB) < 16 -> node derivatives Q5.NF
//   (GW = 5 + NF bits). The outputs Q4.OF and Q6.OF contain these ranges: n_o is the node value
//   sign-extended by one bit, grad_o the node derivative sign-extended by one bit.
// Multipliers: 3 weights x 2 (scurve), 8 corners x 3 (value_gradient), 7 lerps x 4 (+1 own-axis
// ds product for scurve); no weight products w_x w_y w_z as in Rayshade's sum of 8 terms.
//
// Serial evaluation (NoiseSteps = 2, 4, 8): the caller offers step_i = 0..NoiseSteps-1 with
// valid_i on consecutive advances (lat_i and frac_i of the evaluation each time); step j
// evaluates corners j CPS .. j CPS + CPS-1 (CPS = 8 / NoiseSteps) and their lerps on the first
// KC = lg CPS axes; the remaining axes are lerped across steps through one lerp and one held
// node per axis (the node of a step with bit l = 0 is held, the next step's node is lerped
// with it). The lerps are the tree's lerps on the same operands, so n_o and grad_o (valid at
// the last step) are the same bit for bit. NoiseSteps = 4: 2 corners + 3 lerps instead of
// 8 + 7, 6 hash lookups and 8 value reads per cycle instead of 14 and 32.
//
// Pipeline (NoiseRegs = the profile's pipeline.noise_regs, 0..6): the unit is a chain of six
// sub-blocks, and a register (pst_delay, enabled by en_i) sits at the first NoiseRegs of the
// six boundaries after them, in this order:
//   b0 hash levels 1-2 (and the weights' u^2) | b1 hash level 3 and the value table |
//   b2 corners | b3, b4, b5 the three lerp levels (the KC in-step levels, then the LS serial
//   levels; b5 is the output).
// A token (valid_i, step_i) travels beside the data: a serial level's held node is stored
// when the token at that level has its bit l = 0 (so the steps' order is kept whatever the
// registers), and valid_o / last_o give the token at the output. The result of step
// NoiseSteps - 1 comes NoiseRegs advances (en_i) after its input; the unit never stalls on its
// own: the caller's en_i is its pipeline's advance.
//
// Parameters (names as scripts/profile.py derives them):
//   NoiseInterp      0 scurve, 1 linear, 2 quintic: weight function (and the own-axis ds
//                    multiplier)
//   NoiseCorner      0 value_gradient, 1 value, 2 grad12: corner term (24 multipliers, none,
//                    or adders and muxes without the value ROM)
//   NoiseHash        0 rayshade 4096 x 12 ROM, 1 perm256 256 x 8 ROM, 2 perlin256 256 x 8 ROM
//                    (additive chain)
//   NoiseValueFrac   fraction bits of R (1..15)
//   NoiseLatticeFrac fraction bits of u, s, ds (LF)
//   NoiseOutFrac     fraction bits of n_o and grad_o
//   NoiseSteps       cycles per evaluation (1, 2, 4, 8): corners and lerps built (above)
//   NoiseGuardBits   node fraction bits below NoiseOutFrac (1..8): every corner, lerp and
//                    held node's width
//   NoiseGradFrac    fraction bits kept on the derivative lanes (the noise gradient, which
//                    feeds only the filter width): >= NF keeps every node bit (the exact
//                    unit); below NF the lanes are floored to 2^-NoiseGradFrac (above) and the
//                    derivative lerps' products, the own-axis products and the node
//                    registers lose NF - NoiseGradFrac low bits
//   NoiseRegs        pipeline registers (0..6, above)
// The tables: pst_noise_hash_rom (T, two banks, pair and single read ports) and
// pst_noise_value_rom (R, four banks); their images `PST_ROM_DIR/*.memh are written by
// sim/tools/pst_roms.
//
// Ports:
//   en_i   the pipeline advances (registers and held nodes store)
//   valid_i, step_i   the token: a step of an evaluation enters; valid_o, last_o: the token at
//                     the output (last_o: its step is NoiseSteps - 1, n_o and grad_o are valid)
//   lat_i  [LatticeWidth-1:0]  3 x 12-bit lattice index (after +576, mod 4096), axis k at [12k +: 12]
//   frac_i [3*LF-1:0]          3 x unsigned fraction u
//   n_o    [NW-1:0]            noise value, signed Q4.OF (pst_pkg::NoiseIntBits)
//   grad_o [3*NGW-1:0]         dn/dx, dn/dy, dn/dz wrt the lattice coordinates, signed Q6.OF each
`include "pst_pkg.sv"
`default_nettype none

`ifndef PST_ROM_DIR
`define PST_ROM_DIR "rom"
`endif

module pst_noise #(
  parameter int NoiseInterp = pst_pkg::NoiseInterpDefault,
  parameter int NoiseCorner = pst_pkg::NoiseCornerDefault,
  parameter int NoiseHash = pst_pkg::NoiseHashDefault,
  parameter int NoiseValueFrac = pst_pkg::NoiseValueFracDefault,
  parameter int NoiseLatticeFrac = pst_pkg::NoiseLatticeFracDefault,
  parameter int NoiseOutFrac = pst_pkg::NoiseOutFracDefault,
  parameter int NoiseSteps = pst_pkg::NoiseStepsDefault,
  parameter int NoiseGuardBits = pst_pkg::NoiseGuardBitsDefault,
  parameter int NoiseGradFrac = pst_pkg::NoiseGradFracDefault,
  parameter int NoiseRegs = pst_pkg::NoiseRegsDefault,
  localparam int LF = NoiseLatticeFrac,  // fraction bits of u
  localparam int OF = NoiseOutFrac,      // fraction bits of the outputs
  localparam int NW = pst_pkg::NoiseIntBits + NoiseOutFrac,      // n_o
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac, // one grad_o component
  localparam int LB = pst_pkg::LatticeBits                       // one lattice index
) (
  input  logic               clk_i,    // pipeline registers, held lerp nodes
  input  logic               rst_ni,
  input  logic               en_i,     // advance
  input  logic               valid_i,  // a step enters
  input  logic [2:0]         step_i,   // 0..NoiseSteps-1: the corners of this step
  input  logic [pst_pkg::LatticeWidth-1:0] lat_i,
  input  logic [3*LF-1:0]    frac_i,
  output logic               valid_o,  // the token at the output
  output logic               last_o,   // ... is the evaluation's last step: n_o, grad_o valid
  output logic signed [NW-1:0]  n_o,
  output logic [3*NGW-1:0]      grad_o
);

  // Guard bits of the internal nodes below the output LSB (golden: noiseNodeFrac).
  localparam int GuardBits = NoiseGuardBits;
  // Fraction bits of every corner and lerp node.
  localparam int NodeFrac = OF + GuardBits;
  // The derivative lanes' floor: they are multiples of 2^GradFloor (golden: noiseGradFloor).
  localparam int GradFloor = (NoiseGradFrac < NodeFrac) ? NodeFrac - NoiseGradFrac : 0;
  // Node value Q3.NodeFrac (|v| <= 3.5), node derivative Q5.NodeFrac (|g| < 16).
  localparam int VW = 3 + NodeFrac;
  localparam int GW = 5 + NodeFrac;
  localparam int NodeW = VW + 3 * GW;
  // Value-table entries as read (Q1.VF: the top VF + 1 bits of the 16-bit image).
  localparam int RW = NoiseValueFrac + 1;
  // Hash table entry / index width: 12 (Rayshade) or 8 (perm256, perlin256).
  localparam int HW = (NoiseHash == pst_pkg::NoiseHashRayshade) ? LB : 8;
  // Corners per step, lerp levels inside a step (axes 0..KC-1), serial levels (axes KC..2).
  localparam int CPS = 8 / NoiseSteps;
  localparam int KC  = $clog2(CPS);
  localparam int LS  = $clog2(NoiseSteps);
  // Boundaries b0..b5 (header): register at b iff b < NoiseRegs.
  localparam int NB  = 3 + KC + LS;   // = 6
  localparam int TW  = 4;             // token: {valid, step}
  localparam int WTW = 3 * LF + 3 * (LF + 2);   // weights s, ds of the three axes

  // ---- tokens and weights along the chain ---------------------------------------------------
  // tok[b]: the token of the sub-block after boundary b-1 (tok[0] = the input); likewise
  // wts[b] (b >= 1): the weights there, frc[b] the fractions (b <= 2).
  logic [(NB+1)*TW-1:0] tok;
  assign tok[0 +: TW] = {valid_i, step_i};
  for (genvar b = 0; b < NB; b++) begin : g_tok
    pst_delay #(.Width(TW), .Depth(b < NoiseRegs ? 1 : 0), .Reset(1'b1)) u_tok (
      .clk_i, .rst_ni, .en_i, .d_i (tok[b*TW +: TW]), .q_o (tok[(b+1)*TW +: TW])
    );
  end

  // ---- 1. weights -------------------------------------------------------------------------
  // Computed beside the hash: u^2 before b0, s and ds after it (pst_noise_weight's register).
  logic [(NB+1)*WTW-1:0] wts;   // {ds, s} per boundary; [0] unused
  logic [3*LF-1:0]     s_w1;
  logic [3*(LF+2)-1:0] ds_w1;
  for (genvar k = 0; k < 3; k++) begin : g_weight
    pst_noise_weight #(
      .NoiseInterp      (NoiseInterp),
      .NoiseLatticeFrac (NoiseLatticeFrac),
      .Reg              (NoiseRegs > 0)
    ) u_weight (
      .clk_i, .rst_ni, .en_i,
      .u_i  (frac_i[k*LF +: LF]),
      .s_o  (s_w1[k*LF +: LF]),
      .ds_o (ds_w1[k*(LF+2) +: LF+2])
    );
  end
  assign wts[0 +: WTW] = '0;
  assign wts[WTW +: WTW] = {ds_w1, s_w1};
  for (genvar b = 1; b < NB; b++) begin : g_wts
    pst_delay #(.Width(WTW), .Depth(b < NoiseRegs ? 1 : 0)) u_wts (
      .clk_i, .rst_ni, .en_i, .d_i (wts[b*WTW +: WTW]), .q_o (wts[(b+1)*WTW +: WTW])
    );
  end
  logic [3*LF-1:0] frc1, frc2;   // the fractions after b0, b1 (the corners use them)
  pst_delay #(.Width(3*LF), .Depth(NoiseRegs > 0 ? 1 : 0)) u_frc1 (
    .clk_i, .rst_ni, .en_i, .d_i (frac_i), .q_o (frc1)
  );
  pst_delay #(.Width(3*LF), .Depth(NoiseRegs > 1 ? 1 : 0)) u_frc2 (
    .clk_i, .rst_ni, .en_i, .d_i (frc1), .q_o (frc2)
  );

  // The corner index c of corner i of the step whose token is tk: c = step CPS + i (all eight
  // at once when NoiseSteps = 1).
  function automatic logic [2:0] corner_of(input logic [2:0] step, input logic [2:0] i);
    corner_of = step * 3'(CPS) + i;
  endfunction

  // ---- 2. hash ----------------------------------------------------------------------------
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

  // The hash table T (pst_noise_hash_rom, two banks by bit 0): a corner pair's two lookups
  // (X and X + 1, or h ^ Y and h ^ (Y + 1), h ^ Z and h ^ (Z + 1)) always differ in bit 0 and
  // take one read of each bank (parallel: 7 pairs, 7 read ports per half-size bank instead of
  // 14 on the whole table); a lookup without a partner reads both banks (a single port).
  //   parallel: pair 0 = X; 1, 2 = h1[bx] ^ Y; 3..6 = h2 ^ Z of corners i, i + 4.
  //   serial:   singles 0..CPS-1 = level 2, CPS..2 CPS-1 = level 3, 2 CPS = level 1 when
  //             CPS = 1 (else pair 0 = X: corners 2j and 2j + 1).
  localparam int Pairs   = (NoiseSteps == 1) ? 7 : (CPS > 1 ? 1 : 0);
  localparam int Singles = (NoiseSteps == 1) ? 0 : 2 * CPS + (CPS == 1 ? 1 : 0);
  localparam int PW = (Pairs > 0) ? Pairs : 1;
  localparam int SW = (Singles > 0) ? Singles : 1;
  logic [PW*HW-1:0] pa0 /*verilator split_var*/, pa1 /*verilator split_var*/;
  logic [PW*HW-1:0] ph0 /*verilator split_var*/, ph1 /*verilator split_var*/;
  logic [SW*HW-1:0] sa /*verilator split_var*/, sh /*verilator split_var*/;
  pst_noise_hash_rom #(.NoiseHash(NoiseHash), .Pairs(Pairs), .Singles(Singles)) u_hash (
    .pair_a0_i (pa0), .pair_a1_i (pa1), .pair_h0_o (ph0), .pair_h1_o (ph1),
    .single_a_i (sa), .single_h_o (sh)
  );
  // The chain's combining step: XOR (rayshade, perm256) or an HW-bit add (perlin256).
  function automatic logic [HW-1:0] chain_op(logic [HW-1:0] h, logic [HW-1:0] x);
    if (NoiseHash == pst_pkg::NoiseHashPerlin256) chain_op = h + x;
    else chain_op = h ^ x;
  endfunction

  // Levels 1-2 (before b0): per corner of the step, h2 and the z index its level 3 takes.
  //   parallel: the lookups shared along the chain (2 + 4 + 8 = 14); serial: three chained
  //   lookups per corner.
  logic [CPS*HW-1:0] h2_d, z_d, h2_q, z_q;   // corner i at [i*HW +: HW]
  logic [CPS*HW-1:0] h3;                     // corner i at [i*HW +: HW]
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
    // Level 3 (before b1): corners i and i + 4 (Z_0 and Z_1) pair up.
    for (genvar i = 0; i < 4; i++) begin : g_h3
      assign pa0[(3 + i)*HW +: HW] = chain_op(h2_q[i*HW +: HW], z_q[i*HW +: HW]);
      assign pa1[(3 + i)*HW +: HW] = chain_op(h2_q[(i + 4)*HW +: HW], z_q[(i + 4)*HW +: HW]);
      assign h3[i*HW +: HW]       = ph0[(3 + i)*HW +: HW];
      assign h3[(i + 4)*HW +: HW] = ph1[(3 + i)*HW +: HW];
    end
    assign sa = '0;
    logic unused_sh;
    assign unused_sh = ^sh;
  end else begin : g_hash_ser
    // The step's corners, three chained lookups each (only the level-1 lookups of corners
    // 2j, 2j + 1, X_0 and X_1, pair up).
    logic [CPS*HW-1:0] h1;
    for (genvar i = 0; i < CPS; i++) begin : g_chain
      logic [2:0]    c;
      logic [HW-1:0] y;
      assign c  = corner_of(tok[0 +: 3], 3'(i));
      assign y  = c[1] ? idx[3*HW +: HW] : idx[2*HW +: HW];
      assign z_d[i*HW +: HW] = c[2] ? idx[5*HW +: HW] : idx[4*HW +: HW];
      assign sa[i*HW +: HW]   = chain_op(h1[i*HW +: HW], y);
      assign h2_d[i*HW +: HW] = sh[i*HW +: HW];
      // Level 3 (before b1).
      assign sa[(CPS + i)*HW +: HW] = chain_op(h2_q[i*HW +: HW], z_q[i*HW +: HW]);
      assign h3[i*HW +: HW]         = sh[(CPS + i)*HW +: HW];
      logic unused_c;
      assign unused_c = c[0];
    end
    if (CPS == 1) begin : g_h1_single
      logic [2:0] c;
      assign c  = corner_of(tok[0 +: 3], 3'd0);
      assign sa[2*HW +: HW] = c[0] ? idx[1*HW +: HW] : idx[0*HW +: HW];
      assign h1 = sh[2*HW +: HW];
      assign pa0 = '0;
      assign pa1 = '0;
      logic unused_ph;
      assign unused_ph = ^{c[2:1], ph0, ph1};
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
  pst_delay #(.Width(2*CPS*HW), .Depth(NoiseRegs > 0 ? 1 : 0)) u_b0 (
    .clk_i, .rst_ni, .en_i, .d_i ({z_d, h2_d}), .q_o ({z_q, h2_q})
  );

  // ---- 3. the value table (before b1) -----------------------------------------------------
  // R[m + k], m = h3 & 0xff (pst_noise_value_rom: four banks, a corner's four entries one read
  // of each); grad12 corners read no value table.
  logic [CPS*4*RW-1:0] r_d, r_q;   // corner i: R[m + k] at [(4i + k)*RW +: RW]
  logic [CPS*4-1:0]    hb_d, hb_q; // corner i: m[3:0] (grad12's direction) at [4i +: 4]
  logic [CPS*8-1:0]    mi;         // corner i's m at [i*8 +: 8]
  for (genvar i = 0; i < CPS; i++) begin : g_m
    assign mi[i*8 +: 8]   = h3[i*HW +: 8];
    assign hb_d[4*i +: 4] = h3[i*HW +: 4];
    if (HW > 8) begin : g_unused_h3
      logic unused_h3;
      assign unused_h3 = ^h3[i*HW+8 +: HW-8];
    end
  end
  // Value-gradient corners read R[m .. m + 3], value corners R[m] (the rest zero), grad12
  // corners nothing.
  localparam int Reads = (NoiseCorner == pst_pkg::NoiseCornerValueGradient) ? 4 : 1;
  if (NoiseCorner != pst_pkg::NoiseCornerGrad12) begin : g_value
    logic [CPS*Reads*RW-1:0] r;
    pst_noise_value_rom #(.Corners(CPS), .Reads(Reads), .Bits(RW)) u_value (.m_i (mi), .r_o (r));
    for (genvar i = 0; i < CPS; i++) begin : g_corner
      for (genvar k = 0; k < 4; k++) begin : g_r
        if (k < Reads) begin : g_read
          assign r_d[(4*i+k)*RW +: RW] = r[(Reads*i+k)*RW +: RW];
        end else begin : g_zero
          assign r_d[(4*i+k)*RW +: RW] = '0;
        end
      end
    end
  end else begin : g_no_value
    assign r_d = '0;
    logic unused_m;   // grad12 corners use the hash's low four bits only
    assign unused_m = ^mi;
  end
  pst_delay #(.Width(CPS*4*RW), .Depth(NoiseRegs > 1 ? 1 : 0)) u_b1 (
    .clk_i, .rst_ni, .en_i, .d_i (r_d), .q_o (r_q)
  );
  if (NoiseCorner == pst_pkg::NoiseCornerGrad12) begin : g_hb1
    pst_delay #(.Width(CPS*4), .Depth(NoiseRegs > 1 ? 1 : 0)) u_hb1 (
      .clk_i, .rst_ni, .en_i, .d_i (hb_d), .q_o (hb_q)
    );
  end else begin : g_no_hb1
    assign hb_q = '0;  // the value-table corners ignore hash_i
    logic unused_hb;
    assign unused_hb = ^hb_d;
  end

  // ---- 4. corners (before b2) -------------------------------------------------------------
  // tree_d / tree_q: level 0 = the step's corners, level t = the lerps on axis t-1 (CPS >> t
  // nodes); node k of level t at [(t*CPS + k)*NodeW +: NodeW]. Level t is registered at
  // boundary b2 + t.
  logic [(KC+1)*CPS*NodeW-1:0] tree_d, tree_q;
  for (genvar i = 0; i < CPS; i++) begin : g_corner
    logic [NodeW-1:0] node;
    pst_noise_corner #(
      .NoiseCorner      (NoiseCorner),
      .NoiseValueFrac   (NoiseValueFrac),
      .NoiseLatticeFrac (NoiseLatticeFrac),
      .NodeFrac         (NodeFrac)
    ) u_corner (
      .corner_i (corner_of(tok[2*TW +: 3], 3'(i))),
      .r_i      (r_q[4*i*RW +: 4*RW]),
      .hash_i   (hb_q[4*i +: 4]),
      .u_i      (frc2),
      .node_o   (node)
    );
    // The derivatives floored to multiples of 2^GradFloor: their low bits cleared.
    assign tree_d[i*NodeW +: VW] = node[0 +: VW];
    for (genvar k = 0; k < 3; k++) begin : g_floor
      if (GradFloor > 0) begin : g_clear
        assign tree_d[i*NodeW + VW + k*GW +: GW] = {node[VW + k*GW + GradFloor +: GW - GradFloor],
                                                    {GradFloor{1'b0}}};
        logic unused_low;
        assign unused_low = ^node[VW + k*GW +: GradFloor];
      end else begin : g_keep
        assign tree_d[i*NodeW + VW + k*GW +: GW] = node[VW + k*GW +: GW];
      end
    end
  end

  // ---- 5. lerp tree -----------------------------------------------------------------------
  // What is known of the corners' derivative lanes (pst_noise_lerp's GradHi, GradLo: values
  // are multiples of 2^Lo and fit Hi bits signed), exact:
  //   value_gradient: R at NodeFrac, R in [-1, 1): Hi = NodeFrac + 1; Lo = NodeFrac - VF when
  //                   VF < NodeFrac (R << (NodeFrac - VF)), else 0 (floored);
  //   value:          0: Hi = 1, Lo = 0;
  //   grad12:         -1, 0, +1: Hi = NodeFrac + 2, Lo = NodeFrac;
  //   and every lane is a multiple of 2^GradFloor (Lo >= GradFloor; value corners' zero
  //   lanes: Hi = GradFloor + 1).
  // A lerp on axis a keeps lane k != a between its inputs (Hi unchanged) and leaves
  // max(GradFloor, Lo - LF) zero bits (2^F floor((y - x) s / 2^(LF + F)) with y - x a
  // multiple of 2^Lo); lane a gets the own-axis term: Q5, Hi = GW, Lo = GradFloor. Axes are
  // lerped in the order x, y, z, so after `done` lerps lanes k < done are (GW, GradFloor) and
  // the others (CornerGHi, max(GradFloor, CornerGLo - done LF)).
  localparam int CornerGLo0 = (NoiseCorner == pst_pkg::NoiseCornerValueGradient) ?
                                (NoiseValueFrac < NodeFrac ? NodeFrac - NoiseValueFrac : 0) :
                              (NoiseCorner == pst_pkg::NoiseCornerGrad12) ? NodeFrac : 0;
  localparam int CornerGLo = (CornerGLo0 > GradFloor) ? CornerGLo0 : GradFloor;
  localparam int CornerGHi = (NoiseCorner == pst_pkg::NoiseCornerValueGradient) ? NodeFrac + 1 :
                             (NoiseCorner == pst_pkg::NoiseCornerGrad12) ? NodeFrac + 2 :
                             GradFloor + 1;
  // A node's significant bits (registers, held nodes): v, then each derivative above its
  // GradFloor zeros (PackW = NodeW when GradFloor = 0).
  localparam int PGW = GW - GradFloor;
  localparam int PackW = VW + 3 * PGW;
  /* verilator lint_off UNUSEDSIGNAL */   // n's GradFloor zeros below each derivative
  function automatic logic [PackW-1:0] pack_node(input logic [NodeW-1:0] n);
    pack_node = {n[VW + 2*GW + GradFloor +: PGW], n[VW + GW + GradFloor +: PGW],
                 n[VW + GradFloor +: PGW], n[0 +: VW]};
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */
  function automatic logic [NodeW-1:0] unpack_node(input logic [PackW-1:0] p);
    unpack_node = {GW'(p[VW + 2*PGW +: PGW]) << GradFloor, GW'(p[VW + PGW +: PGW]) << GradFloor,
                   GW'(p[VW +: PGW]) << GradFloor, p[0 +: VW]};
  endfunction
  function automatic int lane_hi(input int k, input int done);
    lane_hi = (k < done) ? GW : CornerGHi;
  endfunction
  function automatic int lane_lo(input int k, input int done);
    lane_lo = (k < done) ? GradFloor :
              (CornerGLo - done * LF > GradFloor) ? CornerGLo - done * LF : GradFloor;
  endfunction
  for (genvar t = 0; t <= KC; t++) begin : g_level
    // Boundary b2 + t after level t: the nodes' significant bits only (PackW each: the
    // derivatives' GradFloor low zeros are not registered).
    logic [(CPS >> t)*PackW-1:0] pk_d, pk_q;
    for (genvar k = 0; k < (CPS >> t); k++) begin : g_pack
      // (plain slices, no function: Verilator then sees no loop through the flat tree_d/q)
      localparam int N0 = (t*CPS + k)*NodeW;
      assign pk_d[k*PackW +: VW] = tree_d[N0 +: VW];
      assign tree_q[N0 +: VW] = pk_q[k*PackW +: VW];
      for (genvar m = 0; m < 3; m++) begin : g_lane
        assign pk_d[k*PackW + VW + m*PGW +: PGW] = tree_d[N0 + VW + m*GW + GradFloor +: PGW];
        assign tree_q[N0 + VW + m*GW + GradFloor +: PGW] = pk_q[k*PackW + VW + m*PGW +: PGW];
        if (GradFloor > 0) begin : g_zeros
          assign tree_q[N0 + VW + m*GW +: GradFloor] = '0;
          logic unused_zeros;   // the floor's zeros, not registered
          assign unused_zeros = ^tree_d[N0 + VW + m*GW +: GradFloor];
        end
      end
    end
    pst_delay #(.Width((CPS >> t)*PackW), .Depth(2 + t < NoiseRegs ? 1 : 0)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i (pk_d), .q_o (pk_q)
    );
    if ((CPS >> t) < CPS) begin : g_unused_slots
      // The rest of the level's slots are unused.
      assign tree_d[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW] = '0;
      assign tree_q[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW] = '0;
      logic unused_slots;
      assign unused_slots = ^{tree_d[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW],
                              tree_q[(t*CPS + (CPS >> t))*NodeW +: (CPS - (CPS >> t))*NodeW]};
    end
    if (t > 0) begin : g_lerps
      // Level t (axis t-1) lerps nodes 2k, 2k+1 of level t-1, with the weights after b(1+t).
      for (genvar k = 0; k < (CPS >> t); k++) begin : g_lerp
        pst_noise_lerp #(
          .NoiseInterp      (NoiseInterp),
          .NoiseLatticeFrac (NoiseLatticeFrac),
          .NodeFrac         (NodeFrac),
          .Axis             (t - 1),
          .GradHi0          (lane_hi(0, t - 1)),
          .GradHi1          (lane_hi(1, t - 1)),
          .GradHi2          (lane_hi(2, t - 1)),
          .GradLo0          (lane_lo(0, t - 1)),
          .GradLo1          (lane_lo(1, t - 1)),
          .GradLo2          (lane_lo(2, t - 1)),
          .GradFloor        (GradFloor)
        ) u_lerp (
          .a_i    (tree_q[((t-1)*CPS + 2*k)*NodeW +: NodeW]),
          .b_i    (tree_q[((t-1)*CPS + 2*k + 1)*NodeW +: NodeW]),
          .s_i    (wts[(2+t)*WTW + (t-1)*LF +: LF]),
          .ds_i   (wts[(2+t)*WTW + 3*LF + (t-1)*(LF+2) +: LF+2]),
          .node_o (tree_d[(t*CPS + k)*NodeW +: NodeW])
        );
      end
    end
  end

  // Across the steps (NoiseSteps > 1): serial level l (axis KC + l), after boundary b(2+KC+l).
  // At step j the node of the step climbs level l if bit l of j is 1 (it is then the upper
  // node b, the lower one a having been held at step j - 2^l); a node reaching level l with
  // bit l = 0 is held there. The last step (all bits 1) climbs every level to the root.
  logic [(LS+1)*NodeW-1:0] chain;   // node entering serial level l at [l*NodeW +: NodeW]
  assign chain[0 +: NodeW] = tree_q[(KC*CPS)*NodeW +: NodeW];
  for (genvar l = 0; l < LS; l++) begin : g_serial
    localparam int B = 3 + KC + l;   // the token and weights of this level: after b(2+KC+l)
    logic [TW-1:0]    tk;
    logic [NodeW-1:0] hold, node_d, node_q;
    logic [PackW-1:0] hold_q, pk_q;   // significant bits only (pack_node)
    logic             lower_ones;   // bits 0..l-1 of the step are all 1
    assign tk = tok[B*TW +: TW];
    logic unused_tk;   // the step bits above l
    assign unused_tk = ^tk;
    if (l == 0) begin : g_l0
      assign lower_ones = 1'b1;
    end else begin : g_ln
      assign lower_ones = &tk[l-1:0];
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) hold_q <= '0;
      else if (en_i && tk[3] && lower_ones && !tk[l]) hold_q <= pack_node(chain[l*NodeW +: NodeW]);
    end
    assign hold = unpack_node(hold_q);
    pst_noise_lerp #(
      .NoiseInterp      (NoiseInterp),
      .NoiseLatticeFrac (NoiseLatticeFrac),
      .NodeFrac         (NodeFrac),
      .Axis             (KC + l),
      .GradHi0          (lane_hi(0, KC + l)),
      .GradHi1          (lane_hi(1, KC + l)),
      .GradHi2          (lane_hi(2, KC + l)),
      .GradLo0          (lane_lo(0, KC + l)),
      .GradLo1          (lane_lo(1, KC + l)),
      .GradLo2          (lane_lo(2, KC + l)),
      .GradFloor        (GradFloor)
    ) u_lerp (
      .a_i    (hold),
      .b_i    (chain[l*NodeW +: NodeW]),
      .s_i    (wts[B*WTW + (KC+l)*LF +: LF]),
      .ds_i   (wts[B*WTW + 3*LF + (KC+l)*(LF+2) +: LF+2]),
      .node_o (node_d)
    );
    pst_delay #(.Width(PackW), .Depth(B < NoiseRegs ? 1 : 0)) u_reg (
      .clk_i, .rst_ni, .en_i, .d_i (pack_node(node_d)), .q_o (pk_q)
    );
    assign node_q = unpack_node(pk_q);
    assign chain[(l+1)*NodeW +: NodeW] = node_q;
  end

  // ---- 6. outputs -------------------------------------------------------------------------
  // floor to OF (drop GuardBits), sign-extend by one bit (the contract's saturation: the
  // ranges above never reach it).
  logic [NodeW-1:0] root;
  logic [TW-1:0]    tk_out;
  assign root   = chain[LS*NodeW +: NodeW];
  assign tk_out = tok[NB*TW +: TW];
  assign valid_o = tk_out[3];
  assign last_o  = tk_out[3] && (32'(tk_out[2:0]) == NoiseSteps - 1);
  assign n_o = {root[VW-1], root[GuardBits +: VW-GuardBits]};
  for (genvar k = 0; k < 3; k++) begin : g_grad_out
    assign grad_o[k*NGW +: NGW] = {root[VW+(k+1)*GW-1], root[VW+k*GW+GuardBits +: GW-GuardBits]};
  end
  logic unused_guard;
  assign unused_guard = ^{root[0 +: GuardBits], root[VW +: GuardBits], root[VW+GW +: GuardBits],
                          root[VW+2*GW +: GuardBits], wts[0 +: WTW], wts[NB*WTW +: WTW]};

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (NoiseInterp != pst_pkg::NoiseInterpScurve && NoiseInterp != pst_pkg::NoiseInterpLinear &&
        NoiseInterp != pst_pkg::NoiseInterpQuintic)
      $error("pst_noise: NoiseInterp must be scurve, linear or quintic");
    if (NoiseCorner != pst_pkg::NoiseCornerValueGradient && NoiseCorner != pst_pkg::NoiseCornerValue &&
        NoiseCorner != pst_pkg::NoiseCornerGrad12)
      $error("pst_noise: NoiseCorner must be value_gradient, value or grad12");
    if (NoiseHash != pst_pkg::NoiseHashRayshade && NoiseHash != pst_pkg::NoiseHashPerm256 &&
        NoiseHash != pst_pkg::NoiseHashPerlin256)
      $error("pst_noise: NoiseHash must be rayshade, perm256 or perlin256");
    if (NoiseValueFrac < pst_pkg::NoiseValueFracMin || NoiseValueFrac > pst_pkg::NoiseValueFracMax)
      $error("pst_noise: NoiseValueFrac out of range");
    if (NoiseLatticeFrac < pst_pkg::NoiseLatticeFracMin) $error("pst_noise: NoiseLatticeFrac out of range");
    if (NoiseSteps != 1 && NoiseSteps != 2 && NoiseSteps != 4 && NoiseSteps != 8)
      $error("pst_noise: NoiseSteps must be 1, 2, 4 or 8");
    if (NoiseRegs < 0 || NoiseRegs > NB) $error("pst_noise: NoiseRegs must be 0..%0d", NB);
    if (NoiseGradFrac < 1) $error("pst_noise: NoiseGradFrac must be >= 1");
  end
  // The node value never exceeds |3.5| (so n_o never saturates) at a valid last step.
  always_comb begin
    if (last_o)
      assert ($signed(root[0 +: VW]) <= $signed({3'b011, 1'b1, {(VW-4){1'b0}}}) &&
              $signed(root[0 +: VW]) >= -$signed({3'b011, 1'b1, {(VW-4){1'b0}}}))
        else $error("pst_noise: |n| > 3.5");
  end
`endif

endmodule

`default_nettype wire

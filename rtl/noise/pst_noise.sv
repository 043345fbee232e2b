// pst_noise: the noise unit (docs/HARDWARE.md unit 2). Rayshade's Noise3
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
// 2. Hash (pst_noise_hash): the chained table lookups h3[c] = T[T[T[X_bx] ^ Y_by] ^ Z_bz]
//    (rayshade 4096 x 12, perm256, or perlin256's additive chain); m = h3 & 0xff (rayshade),
//    else h3. This is model/noise.cpp's noiseHash for the same lattice point.
// 3. Value ROM: R[m + k], k = 0..3 (m + 3 <= 258 < 267), Q1.VF = value16 >>> (15 - VF), i.e.
//    the top VF + 1 bits of the 16-bit entry (floor; exact at VF = 15).
// 4. Corners (pst_noise_corner, eight): value_gradient v = 0.5 R[m] + R[m+1] d_x + R[m+2] d_y
//    + R[m+3] d_z exact at VF + LF bits, d = u - b; value v = 0.5 R[m]. Node = (floor(v to NF),
//    R[m+1..3] to NF) (gradient zero for value corners); grad12 (Perlin 2002) reads no value
//    ROM: v = +-d_a +-d_b and the gradient +-1 on axes a, b chosen by m's low four bits.
//    The derivatives are then floored to multiples of 2^F (their F low bits cleared).
// 5. Lerps (pst_noise_tree: seven pst_noise_lerp): L(x, y) = x + floor((y - x) s / 2^LF) on v,
//    floored to 2^F on the derivatives, plus the own-axis term (ds) by the product rule;
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
// node per axis (pst_noise_tree). The lerps are the tree's lerps on the same operands, so n_o and grad_o (valid at
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
`include "pst_params.svh"
`default_nettype none

module pst_noise #(
  `PST_LATTICE_PARAMS,
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
  // Corners per step; boundaries b0..b5 (header): register at b iff b < NoiseRegs.
  localparam int CPS = 8 / NoiseSteps;
  localparam int NB  = 3 + $clog2(CPS) + $clog2(NoiseSteps);   // = 6
  localparam int TW  = 4;             // token: {valid, step}
  localparam int WTW = 3 * LF + 3 * (LF + 2);   // weights s, ds of the three axes

  // ---- tokens and weights along the chain ---------------------------------------------------
  // tok[b]: the token of the sub-block after boundary b-1 (tok[0] = the input), b <= 2; the
  // tree carries it on (pst_noise_tree). w1, w2: the weights after b0, b1; frc1, frc2 the
  // fractions.
  logic [3*TW-1:0] tok;
  assign tok[0 +: TW] = {valid_i, step_i};
  for (genvar b = 0; b < 2; b++) begin : g_tok
    pst_delay #(.Width(TW), .Depth(b < NoiseRegs ? 1 : 0), .Reset(1'b1)) u_tok (
      .clk_i, .rst_ni, .en_i, .d_i (tok[b*TW +: TW]), .q_o (tok[(b+1)*TW +: TW])
    );
  end

  // ---- 1. weights -------------------------------------------------------------------------
  // Computed beside the hash: u^2 before b0, s and ds after it (pst_noise_weight's register).
  logic [3*LF-1:0]     s_w1;
  logic [3*(LF+2)-1:0] ds_w1;
  logic [WTW-1:0]      w2;     // {ds, s} after b1
  for (genvar k = 0; k < 3; k++) begin : g_weight
    pst_noise_weight #(`PST_WEIGHT_PASS, .Reg(NoiseRegs > 0)) u_weight (
      .clk_i, .rst_ni, .en_i,
      .u_i  (frac_i[k*LF +: LF]),
      .s_o  (s_w1[k*LF +: LF]),
      .ds_o (ds_w1[k*(LF+2) +: LF+2])
    );
  end
  pst_delay #(.Width(WTW), .Depth(NoiseRegs > 1 ? 1 : 0)) u_wts2 (
    .clk_i, .rst_ni, .en_i, .d_i ({ds_w1, s_w1}), .q_o (w2)
  );
  logic [3*LF-1:0] frc1, frc2;   // the fractions after b0, b1 (the corners use them)
  pst_delay #(.Width(3*LF), .Depth(NoiseRegs > 0 ? 1 : 0)) u_frc1 (
    .clk_i, .rst_ni, .en_i, .d_i (frac_i), .q_o (frc1)
  );
  pst_delay #(.Width(3*LF), .Depth(NoiseRegs > 1 ? 1 : 0)) u_frc2 (
    .clk_i, .rst_ni, .en_i, .d_i (frc1), .q_o (frc2)
  );

  // ---- 2. hash (before b0 and b1) ---------------------------------------------------------
  logic [CPS*HW-1:0] h3;   // corner i of the step after b0 at [i*HW +: HW]
  pst_noise_hash #(`PST_HASH_PASS, .Reg(NoiseRegs > 0)) u_hash (
    .clk_i, .rst_ni, .en_i, .step_i (tok[0 +: 3]), .lat_i, .h3_o (h3)
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
  // Corner i of the step is corner c = step CPS + i (all eight at once when NoiseSteps = 1).
  logic [CPS*NodeW-1:0] corners;   // corner i at [i*NodeW +: NodeW]
  for (genvar i = 0; i < CPS; i++) begin : g_corner
    logic [NodeW-1:0] node;
    pst_noise_corner #(`PST_CORNER_PASS, .NodeFrac(NodeFrac)) u_corner (
      .corner_i (tok[2*TW +: 3] * 3'(CPS) + 3'(i)),
      .r_i      (r_q[4*i*RW +: 4*RW]),
      .hash_i   (hb_q[4*i +: 4]),
      .u_i      (frc2),
      .node_o   (node)
    );
    // The derivatives floored to multiples of 2^GradFloor: their low bits cleared.
    assign corners[i*NodeW +: VW] = node[0 +: VW];
    for (genvar k = 0; k < 3; k++) begin : g_floor
      if (GradFloor > 0) begin : g_clear
        assign corners[i*NodeW + VW + k*GW +: GW] = {node[VW + k*GW + GradFloor +: GW - GradFloor],
                                                    {GradFloor{1'b0}}};
        logic unused_low;
        assign unused_low = ^node[VW + k*GW +: GradFloor];
      end else begin : g_keep
        assign corners[i*NodeW + VW + k*GW +: GW] = node[VW + k*GW +: GW];
      end
    end
  end

  // ---- 5. lerp tree (b2 onwards) -----------------------------------------------------------
  logic [NodeW-1:0] root;
  logic [TW-1:0]    tk_out;
  pst_noise_tree #(`PST_TREE_PASS, .NodeFrac(NodeFrac), .GradFloor(GradFloor)) u_tree (
    .clk_i, .rst_ni, .en_i,
    .tok_i    (tok[2*TW +: TW]),
    .wts_i    (w2),
    .corner_i (corners),
    .tok_o    (tk_out),
    .root_o   (root)
  );

  // ---- 6. outputs -------------------------------------------------------------------------
  // floor to OF (drop GuardBits), sign-extend by one bit (the contract's saturation: the
  // ranges above never reach it).
  logic signed [NW-1:0] n_r;
  logic [3*NGW-1:0]     g_r;
  assign n_r = {root[VW-1], root[GuardBits +: VW-GuardBits]};
  for (genvar k = 0; k < 3; k++) begin : g_grad_out
    assign g_r[k*NGW +: NGW] = {root[VW+(k+1)*GW-1], root[VW+k*GW+GuardBits +: GW-GuardBits]};
  end
  // The token decoded at the output (b5, the tree's last level, is the unit's last register).
  pst_noise_out #(.Width(NW + 3*NGW), .Regs(0), `PST_NOISE_STEPS_PASS) u_out (
    .clk_i, .rst_ni, .en_i, .tok_i (tk_out), .data_i ({g_r, n_r}),
    .valid_o, .last_o, .data_o ({grad_o, n_o}));
  logic unused_guard;
  assign unused_guard = ^{root[0 +: GuardBits], root[VW +: GuardBits], root[VW+GW +: GuardBits],
                          root[VW+2*GW +: GuardBits]};

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

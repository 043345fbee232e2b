// Stage 2 of the texture pipeline (docs/HARDWARE.md): the noise unit. Rayshade's Noise3
// (value-plus-gradient lattice noise) and its analytic gradient in fixed point, with the
// cheaper variants as parameters. Combinational. Golden: pst::noiseFx
// (model/golden/noise_fx.cpp, same steps and floors; the unit tests compare every bit).
//
// Notation: LF = NoiseLatticeFrac, VF = NoiseValueFrac, OF = NoiseOutFrac,
// NF = NodeFrac = OF + GuardBits (GuardBits = 4: internal node fraction bits; the golden
// model's kNoiseGuardBits). Corner c = bx + 2 by + 4 bz (x fastest, Rayshade's order).
//
// 1. Weights (pst_noise_weight, one per axis): s (weight of the upper corner) and ds = ds/du,
//    unsigned at LF fraction bits. scurve: u2 = floor(u u), s = floor(u2 (3 - 2u)),
//    ds = 6 (u - u2); linear: s = u, ds = 1.
// 2. Hash, 2 + 4 + 8 = 14 ROM lookups (corner indices: X in {L_x, L_x + 1 mod 4096}, ...):
//      h1[bx] = T[X_bx], h2[bx,by] = T[h1[bx] ^ Y_by], h3[c] = T[h2[bx,by] ^ Z_bz]
//    NoiseHash = 0 (rayshade): T = Rayshade's 4096 x 12 table, m = h3 & 0xff.
//    NoiseHash = 1 (perm256): T = the 256 x 8 permutation, indices L & 0xff (the same as
//    Rayshade's (floor(x) + 1e6) & 0xff, since L = floor(x) + 576 mod 4096), m = h3.
//    This is model/noise.cpp's noiseHash for the same lattice point.
// 3. Value ROM: R[m + k], k = 0..3 (m + 3 <= 258 < 267), Q1.VF = value16 >>> (15 - VF), i.e.
//    the top VF + 1 bits of the 16-bit entry (floor; exact at VF = 15).
// 4. Corners (pst_noise_corner, eight): value_gradient v = 0.5 R[m] + R[m+1] d_x + R[m+2] d_y
//    + R[m+3] d_z exact at VF + LF bits, d = u - b; value v = 0.5 R[m]. Node = (floor(v to NF),
//    R[m+1..3] to NF) (gradient zero for value corners).
// 5. Lerps (pst_noise_lerp, seven): L(x, y) = x + floor((y - x) s / 2^LF) on v and the three
//    derivatives; the derivative on the lerp's own axis adds floor((b.v - a.v) ds / 2^LF).
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
// Parameters (names as scripts/profile.py derives them):
//   NoiseInterp      0 scurve, 1 linear: weight function (and the own-axis ds multiplier)
//   NoiseCorner      0 value_gradient, 1 value: corner term (24 multipliers, or none)
//   NoiseHash        0 rayshade 4096 x 12 ROM, 1 perm256 256 x 8 ROM
//   NoiseValueFrac   fraction bits of R (1..15)
//   NoiseLatticeFrac fraction bits of u, s, ds (LF)
//   NoiseOutFrac     fraction bits of n_o and grad_o
// ROM images: `PST_ROM_DIR/{hash4096,perm256,value16}.memh, written by sim/tools/pst_roms.
//
// Ports:
//   lat_i  [35:0]          3 x 12-bit lattice index (after +576, mod 4096), axis k at [12k +: 12]
//   frac_i [3*LF-1:0]      3 x unsigned fraction u
//   n_o    [4+OF-1:0]      noise value, signed Q4.OF
//   grad_o [3*(6+OF)-1:0]  dn/dx, dn/dy, dn/dz wrt the lattice coordinates, signed Q6.OF each
`default_nettype none

`ifndef PST_ROM_DIR
`define PST_ROM_DIR "rom"
`endif

module pst_noise #(
  parameter int NoiseInterp = 0,
  parameter int NoiseCorner = 0,
  parameter int NoiseHash = 0,
  parameter int NoiseValueFrac = 15,
  parameter int NoiseLatticeFrac = 16,
  parameter int NoiseOutFrac = 16,
  localparam int LF = NoiseLatticeFrac,  // fraction bits of u
  localparam int OF = NoiseOutFrac       // fraction bits of the outputs
) (
  input  wire logic [35:0]        lat_i,
  input  wire logic [3*LF-1:0]    frac_i,
  output logic signed [4+OF-1:0]  n_o,
  output logic [3*(6+OF)-1:0]     grad_o
);

  // Guard bits of the internal nodes below the output LSB (golden: kNoiseGuardBits).
  localparam int GuardBits = 4;
  // Fraction bits of every corner and lerp node.
  localparam int NodeFrac = OF + GuardBits;
  // Node value Q3.NodeFrac (|v| <= 3.5), node derivative Q5.NodeFrac (|g| < 16).
  localparam int VW = 3 + NodeFrac;
  localparam int GW = 5 + NodeFrac;
  localparam int NodeW = VW + 3 * GW;
  // Value-table entries as read (Q1.VF: the top VF + 1 bits of the 16-bit image).
  localparam int RW = NoiseValueFrac + 1;
  // Hash table entry / index width: 12 (Rayshade) or 8 (perm256).
  localparam int HW = (NoiseHash == 0) ? 12 : 8;

  // ---- 1. weights -------------------------------------------------------------------------
  logic [3*LF-1:0]     s_w;   // s per axis
  logic [3*(LF+2)-1:0] ds_w;  // ds per axis
  for (genvar k = 0; k < 3; k++) begin : g_weight
    pst_noise_weight #(
      .NoiseInterp      (NoiseInterp),
      .NoiseLatticeFrac (NoiseLatticeFrac)
    ) u_weight (
      .u_i  (frac_i[k*LF +: LF]),
      .s_o  (s_w[k*LF +: LF]),
      .ds_o (ds_w[k*(LF+2) +: LF+2])
    );
  end

  // ---- 2. hash ----------------------------------------------------------------------------
  logic [6*HW-1:0] idx;  // corner indices: axis k, b at [(2k+b)*HW +: HW]
  logic [2*HW-1:0] h1;   // T[X_bx] at [bx*HW +: HW]
  logic [4*HW-1:0] h2;   // T[h1 ^ Y_by] at [(bx + 2 by)*HW +: HW]
  logic [8*HW-1:0] h3;   // T[h2 ^ Z_bz] at [c*HW +: HW]
  logic [8*8-1:0]  m;    // value-table index per corner

  for (genvar k = 0; k < 3; k++) begin : g_idx
    logic [11:0] l_next;  // L + 1 mod 4096
    assign l_next = lat_i[12*k +: 12] + 12'd1;
    assign idx[(2*k)*HW +: HW]   = lat_i[12*k +: HW];
    assign idx[(2*k+1)*HW +: HW] = l_next[HW-1:0];
    if (HW < 12) begin : g_unused_high
      logic unused_l;
      assign unused_l = ^{lat_i[12*k+HW +: 12-HW], l_next[11:HW]};
    end
  end

  if (NoiseHash == 0) begin : g_rayshade
    logic [11:0] rom [0:4095];
    initial $readmemh({`PST_ROM_DIR, "/hash4096.memh"}, rom);
    for (genvar bx = 0; bx < 2; bx++) begin : g_h1
      assign h1[bx*HW +: HW] = rom[idx[bx*HW +: HW]];
    end
    for (genvar i = 0; i < 4; i++) begin : g_h2
      assign h2[i*HW +: HW] = rom[h1[(i%2)*HW +: HW] ^ idx[(2 + i/2)*HW +: HW]];
    end
    for (genvar c = 0; c < 8; c++) begin : g_h3
      assign h3[c*HW +: HW] = rom[h2[(c%4)*HW +: HW] ^ idx[(4 + c/4)*HW +: HW]];
      assign m[c*8 +: 8] = h3[c*HW +: 8];
      logic unused_h3;
      assign unused_h3 = ^h3[c*HW+8 +: HW-8];
    end
  end else begin : g_perm256
    logic [7:0] rom [0:255];
    initial $readmemh({`PST_ROM_DIR, "/perm256.memh"}, rom);
    for (genvar bx = 0; bx < 2; bx++) begin : g_h1
      assign h1[bx*HW +: HW] = rom[idx[bx*HW +: HW]];
    end
    for (genvar i = 0; i < 4; i++) begin : g_h2
      assign h2[i*HW +: HW] = rom[h1[(i%2)*HW +: HW] ^ idx[(2 + i/2)*HW +: HW]];
    end
    for (genvar c = 0; c < 8; c++) begin : g_h3
      assign h3[c*HW +: HW] = rom[h2[(c%4)*HW +: HW] ^ idx[(4 + c/4)*HW +: HW]];
      assign m[c*8 +: 8] = h3[c*HW +: 8];
    end
  end

  // ---- 3. value ROM -----------------------------------------------------------------------
  logic [15:0] value_rom [0:266];
  initial $readmemh({`PST_ROM_DIR, "/value16.memh"}, value_rom);

  // ---- 4. corners -------------------------------------------------------------------------
  logic [8*NodeW-1:0] corner;  // corner c at [c*NodeW +: NodeW]
  for (genvar c = 0; c < 8; c++) begin : g_corner
    logic [4*RW-1:0] r;  // R[m + k] at [k*RW +: RW]
    for (genvar k = 0; k < 4; k++) begin : g_r
      if (k == 0 || NoiseCorner == 0) begin : g_read
        logic [15:0] r16;
        assign r16 = value_rom[{1'b0, m[c*8 +: 8]} + 9'(k)];
        assign r[k*RW +: RW] = r16[15 -: RW];  // floor: value16 >>> (15 - VF)
        if (RW < 16) begin : g_unused_low
          logic unused_r16;
          assign unused_r16 = ^r16[15-RW:0];
        end
      end else begin : g_zero
        assign r[k*RW +: RW] = '0;  // value corners read R[m] only
      end
    end
    pst_noise_corner #(
      .NoiseCorner      (NoiseCorner),
      .NoiseValueFrac   (NoiseValueFrac),
      .NoiseLatticeFrac (NoiseLatticeFrac),
      .NodeFrac         (NodeFrac),
      .Corner           (c)
    ) u_corner (
      .r_i    (r),
      .u_i    (frac_i),
      .node_o (corner[c*NodeW +: NodeW])
    );
  end

  // ---- 5. lerp tree -----------------------------------------------------------------------
  logic [7*NodeW-1:0] node;  // 0..3 x lerps (by + 2 bz), 4..5 y lerps (bz), 6 z lerp
  for (genvar i = 0; i < 7; i++) begin : g_lerp
    localparam int Axis = (i < 4) ? 0 : (i < 6) ? 1 : 2;
    logic [NodeW-1:0] a, b;
    if (i < 4) begin : g_x
      assign a = corner[(2*i)*NodeW +: NodeW];
      assign b = corner[(2*i+1)*NodeW +: NodeW];
    end else if (i < 6) begin : g_y
      assign a = node[(2*(i-4))*NodeW +: NodeW];
      assign b = node[(2*(i-4)+1)*NodeW +: NodeW];
    end else begin : g_z
      assign a = node[4*NodeW +: NodeW];
      assign b = node[5*NodeW +: NodeW];
    end
    pst_noise_lerp #(
      .NoiseInterp      (NoiseInterp),
      .NoiseLatticeFrac (NoiseLatticeFrac),
      .NodeFrac         (NodeFrac),
      .Axis             (Axis)
    ) u_lerp (
      .a_i    (a),
      .b_i    (b),
      .s_i    (s_w[Axis*LF +: LF]),
      .ds_i   (ds_w[Axis*(LF+2) +: LF+2]),
      .node_o (node[i*NodeW +: NodeW])
    );
  end

  // ---- 6. outputs -------------------------------------------------------------------------
  // floor to OF (drop GuardBits), sign-extend by one bit (the contract's saturation: the
  // ranges above never reach it).
  logic [NodeW-1:0] root;
  assign root = node[6*NodeW +: NodeW];
  assign n_o = {root[VW-1], root[GuardBits +: VW-GuardBits]};
  for (genvar k = 0; k < 3; k++) begin : g_grad_out
    assign grad_o[k*(6+OF) +: 6+OF] = {root[VW+(k+1)*GW-1], root[VW+k*GW+GuardBits +: GW-GuardBits]};
  end
  logic unused_guard;
  assign unused_guard = ^{root[0 +: GuardBits], root[VW +: GuardBits], root[VW+GW +: GuardBits],
                          root[VW+2*GW +: GuardBits]};

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (NoiseInterp < 0 || NoiseInterp > 1) $error("pst_noise: NoiseInterp must be 0 or 1");
    if (NoiseCorner < 0 || NoiseCorner > 1) $error("pst_noise: NoiseCorner must be 0 or 1");
    if (NoiseHash < 0 || NoiseHash > 1) $error("pst_noise: NoiseHash must be 0 or 1");
    if (NoiseValueFrac < 1 || NoiseValueFrac > 15) $error("pst_noise: NoiseValueFrac must be 1..15");
    if (NoiseLatticeFrac < 1) $error("pst_noise: NoiseLatticeFrac must be >= 1");
  end
  // The node value never exceeds |3.5| (so n_o never saturates).
  always_comb begin
    assert ($signed(root[0 +: VW]) <= $signed({3'b011, 1'b1, {(VW-4){1'b0}}}) &&
            $signed(root[0 +: VW]) >= -$signed({3'b011, 1'b1, {(VW-4){1'b0}}}))
      else $error("pst_noise: |n| > 3.5");
  end
`endif

endmodule

`default_nettype wire

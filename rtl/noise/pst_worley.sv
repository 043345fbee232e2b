// The worley unit: Worley's cellular basis (SIGGRAPH 1996) in fixed point, in place of the
// lattice-noise unit (pst_noise) when the profile's noise.worley_search is not none. Same
// ports and token timing as pst_noise, plus the four coefficient registers. Golden:
// pst::worleyFx (model/golden/worley_fx.cpp, same steps and floors); its double reference is
// the variant of model/worley.h (WorleySearch octant or radius 1, WorleyCubes::Rom256).
//
// Notation: LF = NoiseLatticeFrac, OF = NoiseOutFrac, NF = OF + NoiseGuardBits,
// DF = max(LF, WorleyPointFrac = 9), CF = WorleyCoefFrac, M = NoiseWorleyPoints,
// K = NoiseWorleyOrder, N = 8 (octant) or 27 (cube27) cubes.
//
// 1. Cubes: c = 0 .. N-1; octant: o_a = bit a of c ? (u_a >= 1/2 ? +1 : -1) : 0; cube27:
//    o = (c mod 3, c / 3 mod 3, c / 9) - 1. Step j of NoiseSteps visits cubes j CPS ..
//    j CPS + CPS - 1, CPS = ceil(N / NoiseSteps) (the last step's extra slots are off).
// 2. Cube hash h = P[P[P[X_x] ^ X_y] ^ X_z], X_a = (L_a + o_a) mod 256, P the 256 x 8
//    permutation (perm256.memh); feature-point ROM word h (worley256_pM.memh): count [3:0],
//    point j's position bytes b at [4 + 24 j + 8 a +: 8]. Per step: 3 CPS permutation reads
//    and CPS feature-point reads.
// 3. Candidates (CPS M per step, valid when j < count): d_a = u_a 2^(DF-LF) - (o_a 2^DF +
//    (2 b_a + 1) 2^(DF-9)) (x - p, signed DF + 2 bits), S = d_x^2 + d_y^2 + d_z^2 (exact,
//    unsigned 2 DF + 4 bits: S < 12).
// 4. A sorted list of the K smallest (S, d): step 0 starts from all-ones S, later steps from
//    the list held at the previous step; each candidate in turn goes in before the first
//    entry its S is strictly smaller than (K comparators, a mux per entry).
// 5. At the last step, per k < K: R = isqrt(S_k 2^(2 NF)) (pst_isqrt), F_k = R >> DF;
//    g_k,a = sign(d_a) min(floor(|d_a| 2^(2 NF) / R), 2^NF) (0 if R = 0): one square root and
//    three dividers per k (NF + 1 restoring steps each: the quotient is below 2^(NF+1)).
// 6. n = sat(floor(sum C_k F_k / 2^(CF + NF - OF)), Q4.OF), grad_a likewise (Q6.OF).
//
// Pipeline (NoiseRegs): registers at b0 after the list, b1 after the square roots, b2 after
// the dividers (the first NoiseRegs of the three), the others at the output; the result of
// the last step comes NoiseRegs advances (en_i) after its input, as pst_noise's. The held list stores at every valid advance (steps come on consecutive
// advances, as pst_noise requires).
//
// Parameters: the profile's noise keys (pst_noise's, and NoiseWorleySearch, NoiseWorleyPoints,
// NoiseWorleyOrder).
// Ports: pst_noise's; coef_i [4*CW-1:0] the coefficients C_k (k at [k*CW +: CW], signed
// Q(WorleyCoefInt).CF).
`include "pst_pkg.sv"
`include "pst_params.svh"
`include "noise/pst_rom_dir.svh"
`default_nettype none

module pst_worley #(
  `PST_WORLEY_PARAMS,
  parameter int NoiseWorleySearch = pst_pkg::NoiseWorleySearchOctant,
  localparam int LF  = NoiseLatticeFrac,
  localparam int OF  = NoiseOutFrac,
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,
  localparam int LB  = pst_pkg::LatticeBits,
  localparam int CW  = pst_pkg::WorleyCoefInt + pst_pkg::WorleyCoefFrac
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic               en_i,
  input  logic               valid_i,
  input  logic [2:0]         step_i,
  input  logic [pst_pkg::LatticeWidth-1:0] lat_i,
  input  logic [3*LF-1:0]    frac_i,
  input  logic [4*CW-1:0]    coef_i,
  output logic               valid_o,
  output logic               last_o,
  output logic signed [NW-1:0]  n_o,
  output logic [3*NGW-1:0]      grad_o
);

  localparam int PF   = pst_pkg::WorleyPointFrac;
  localparam int NF   = OF + NoiseGuardBits;
  localparam int DF   = (LF > PF) ? LF : PF;
  localparam int CF   = pst_pkg::WorleyCoefFrac;
  localparam int M    = NoiseWorleyPoints;
  localparam int K    = NoiseWorleyOrder;
  localparam bit Oct  = (NoiseWorleySearch == pst_pkg::NoiseWorleySearchOctant);
  localparam int NC   = Oct ? 8 : 27;
  localparam int CPS  = (NC + NoiseSteps - 1) / NoiseSteps;
  localparam int SW   = 2 * DF + 4;          // S
  localparam int DW   = DF + 2;              // d (signed)
  localparam int EW   = SW + 3 * DW;         // a list entry {d_z, d_y, d_x, S}
  localparam int RomW = pst_pkg::WorleyCountBits + 3 * pst_pkg::WorleyPointBytes * M;
  localparam int RW   = DF + NF + 2;         // R = isqrt(S 2^(2 NF)): (SW + 2 NF) / 2 bits
  localparam int FW   = NF + 2;              // F_k (unsigned, < 3.47)
  localparam int GKW  = NF + 2;              // g_k,a (signed, |g| <= 1)
  localparam int QW   = DF + 1 + 2 * NF;     // |d| 2^(2 NF)
  localparam int AccW = CW + FW + 3;         // sum of K <= 4 products C F (signed)

  // ---- ROMs ------------------------------------------------------------------------------
  logic [7:0]      perm [256];
  logic [RomW-1:0] fpts [256];
  initial $readmemh({`PST_ROM_DIR, "/perm256.memh"}, perm);
  if (M == 1) begin : g_rom1
    initial $readmemh({`PST_ROM_DIR, "/worley256_p1.memh"}, fpts);
  end else if (M == 2) begin : g_rom2
    initial $readmemh({`PST_ROM_DIR, "/worley256_p2.memh"}, fpts);
  end else if (M == 3) begin : g_rom3
    initial $readmemh({`PST_ROM_DIR, "/worley256_p3.memh"}, fpts);
  end else if (M == 4) begin : g_rom4
    initial $readmemh({`PST_ROM_DIR, "/worley256_p4.memh"}, fpts);
  end else if (M == 5) begin : g_rom5
    initial $readmemh({`PST_ROM_DIR, "/worley256_p5.memh"}, fpts);
  end else if (M == 6) begin : g_rom6
    initial $readmemh({`PST_ROM_DIR, "/worley256_p6.memh"}, fpts);
  end else if (M == 7) begin : g_rom7
    initial $readmemh({`PST_ROM_DIR, "/worley256_p7.memh"}, fpts);
  end else if (M == 8) begin : g_rom8
    initial $readmemh({`PST_ROM_DIR, "/worley256_p8.memh"}, fpts);
  end else begin : g_rom9
    initial $readmemh({`PST_ROM_DIR, "/worley256_p9.memh"}, fpts);
  end

  // ---- 1-3. this step's cubes and candidates -----------------------------------------------
  // The cube offset o_a in {-1, 0, 1} of cube c as a 2-bit two's-complement number per axis.
  function automatic logic [5:0] cube_off(input int c, input logic [2:0] dir);
    logic [5:0] o;
    for (int a = 0; a < 3; a++) begin
      if (Oct) o[2*a +: 2] = ((c >> a) & 1) != 0 ? (dir[a] ? 2'b01 : 2'b11) : 2'b00;
      else o[2*a +: 2] = 2'((a == 0 ? c % 3 : a == 1 ? (c / 3) % 3 : c / 9) - 1);
    end
    cube_off = o;
  endfunction

  logic [2:0] dir;   // u_a >= 1/2
  for (genvar a = 0; a < 3; a++) begin : g_dir
    assign dir[a] = frac_i[a*LF + LF - 1];
  end

  logic [CPS-1:0]        cube_on;            // slot i holds a cube of the search
  logic [CPS*M-1:0]      cand_on;            // candidate i M + j is a point of its cube
  logic [CPS*M*EW-1:0]   cand;               // {d_z, d_y, d_x, S}
  always_comb begin
    logic [7:0]      x, h;
    logic [RomW-1:0] w;
    logic [5:0]      o;
    logic signed [DW-1:0] d, p;
    logic [SW-1:0]   s;
    int              c;
    for (int i = 0; i < CPS; i++) begin
      c = 32'(step_i) * CPS + i;
      cube_on[i] = c < NC;
      o = cube_off(c < NC ? c : 0, dir);
      x = lat_i[0 +: 8] + {{6{o[1]}}, o[1:0]};
      h = perm[x];
      x = lat_i[LB +: 8] + {{6{o[3]}}, o[3:2]};
      h = perm[h ^ x];
      x = lat_i[2*LB +: 8] + {{6{o[5]}}, o[5:4]};
      h = perm[h ^ x];
      w = fpts[h];
      for (int j = 0; j < M; j++) begin
        cand_on[i*M + j] = cube_on[i] && (32'(w[3:0]) > j);
        s = '0;
        for (int a = 0; a < 3; a++) begin
          p = (DW'($signed(o[2*a +: 2])) <<< DF)
              + DW'({w[4 + 24*j + 8*a +: 8], 1'b1}) * DW'(1 << (DF - PF));
          d = DW'({2'b00, frac_i[a*LF +: LF]}) * DW'(1 << (DF - LF)) - p;
          s = s + SW'($unsigned(SW'(d) * SW'(d)));
          cand[(i*M + j)*EW + SW + a*DW +: DW] = d;
        end
        cand[(i*M + j)*EW +: SW] = s;
      end
    end
  end

  // ---- 4. the sorted list ------------------------------------------------------------------
  logic [K*EW-1:0] held_q, list_in, list_out;
  always_comb begin
    logic [K*EW-1:0] l, nl;
    logic [SW-1:0]   sc;
    if (step_i == 3'd0) begin
      l = '0;
      for (int k = 0; k < K; k++) l[k*EW +: SW] = '1;
    end else begin
      l = held_q;
    end
    list_in = l;
    for (int q = 0; q < CPS * M; q++) begin
      sc = cand[q*EW +: SW];
      nl = l;
      if (cand_on[q]) begin
        for (int k = 0; k < K; k++) begin
          if (k > 0 && sc < l[(k-1)*EW +: SW]) nl[k*EW +: EW] = l[(k-1)*EW +: EW];
          else if (sc < l[k*EW +: SW]) nl[k*EW +: EW] = cand[q*EW +: EW];
        end
      end
      l = nl;
    end
    list_out = l;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) held_q <= '0;
    else if (en_i && valid_i) held_q <= list_out;
  end

  // Boundary b0 (the first pipeline register): the list and the token.
  localparam int R0 = (NoiseRegs >= 1) ? 1 : 0;
  logic [K*EW-1:0] list_b;
  logic [3:0]      tok_b;
  pst_delay #(.Width(K*EW), .Depth(R0)) u_b0 (
    .clk_i, .rst_ni, .en_i, .d_i (list_out), .q_o (list_b));
  pst_delay #(.Width(4), .Depth(R0), .Reset(1'b1)) u_b0_tok (
    .clk_i, .rst_ni, .en_i, .d_i ({valid_i, step_i}), .q_o (tok_b));

  // floor(num / den) for a quotient below 2^(NF+1): the restoring division's last NF + 1
  // steps (RW + 1-bit compare-subtract each) instead of a QW-step divider. The quotient
  // |d| 2^(2 NF) / R is below 2^NF + 2 whenever R > 0 (R >= |d| 2^NF - 1, |d| >= 2^-DF), so
  // the skipped high steps would give 0 and the result is the exact floor (asserted below).
  function automatic logic [NF:0] qdiv(input logic [QW-1:0] num, input logic [RW-1:0] den);
    logic [RW:0] rem;
    logic [NF:0] q;
    rem = (RW+1)'(num >> (NF + 1));
    for (int i = NF; i >= 0; i--) begin
      rem = {rem[RW-1:0], num[i]};
      q[i] = (rem >= {1'b0, den});
      if (q[i]) rem = rem - {1'b0, den};
    end
    qdiv = q;
  endfunction

  // ---- 5. square roots | b1 | dividers | b2 ------------------------------------------------
  localparam int R1  = (NoiseRegs >= 2) ? 1 : 0;
  localparam int R2  = (NoiseRegs >= 3) ? 1 : 0;
  localparam int RO  = NoiseRegs - R0 - R1 - R2;   // the rest, at the output
  localparam int DLW = 3 * DW;                     // one entry's d
  logic [K*RW-1:0]    r_a, r_c;     // R_k before / after b1
  logic [K*DLW-1:0]   d_a, d_c;     // d_k before / after b1
  logic [K*FW-1:0]    f_c, f_e;     // F_k before / after b2
  logic [K*3*GKW-1:0] g_c, g_e;     // g_k,a before / after b2
  logic [3:0]         tok_c, tok_e;
  for (genvar k = 0; k < K; k++) begin : g_sqrt
    pst_isqrt #(.InWidth(SW + 2*NF), .Regs(0)) u_sqrt (
      .clk_i, .rst_ni, .en_i, .x_i ({list_b[k*EW +: SW], {(2*NF){1'b0}}}), .y_o (r_a[k*RW +: RW]));
    assign d_a[k*DLW +: DLW] = list_b[k*EW + SW +: DLW];
  end
  pst_delay #(.Width(K*(RW + DLW)), .Depth(R1)) u_b1 (
    .clk_i, .rst_ni, .en_i, .d_i ({r_a, d_a}), .q_o ({r_c, d_c}));
  pst_delay #(.Width(4), .Depth(R1), .Reset(1'b1)) u_b1_tok (
    .clk_i, .rst_ni, .en_i, .d_i (tok_b), .q_o (tok_c));

  for (genvar k = 0; k < K; k++) begin : g_k
    logic [RW-1:0] r;
    assign r = r_c[k*RW +: RW];
    assign f_c[k*FW +: FW] = FW'(r >> DF);
    for (genvar a = 0; a < 3; a++) begin : g_axis
      logic signed [DW-1:0] d;
      logic [DW-1:0]  mag_d;
      logic [QW-1:0]  num, quo;
      logic [RW-1:0]  den;
      logic [GKW-1:0] gm;
      assign d     = d_c[k*DLW + a*DW +: DW];
      assign mag_d = d[DW-1] ? -d : d;
      assign num   = {mag_d[DW-2:0], {(2*NF){1'b0}}};
      assign den   = (r == '0) ? RW'(1) : r;
      assign quo   = QW'(qdiv(num, den));
      assign gm    = (r == '0) ? '0 : (quo > QW'(1 << NF)) ? GKW'(1 << NF) : GKW'(quo);
      assign g_c[(3*k + a)*GKW +: GKW] = d[DW-1] ? -gm : gm;
      logic unused_mag;
      assign unused_mag = mag_d[DW-1];
`ifndef SYNTHESIS
      // qdiv's precondition: the quotient fits NF + 1 bits.
      assert property (@(posedge clk_i) disable iff (!rst_ni) (r != '0) |-> ((num >> (NF + 1)) < QW'(r)));
`endif
    end
  end
  pst_delay #(.Width(K*(FW + 3*GKW)), .Depth(R2)) u_b2 (
    .clk_i, .rst_ni, .en_i, .d_i ({f_c, g_c}), .q_o ({f_e, g_e}));
  pst_delay #(.Width(4), .Depth(R2), .Reset(1'b1)) u_b2_tok (
    .clk_i, .rst_ni, .en_i, .d_i (tok_c), .q_o (tok_e));

  // ---- 6. the coefficient sums --------------------------------------------------------------
  logic [K*AccW-1:0]   nk_all;    // C_k F_k
  logic [K*3*AccW-1:0] gk_all;    // C_k g_k,a
  for (genvar k = 0; k < K; k++) begin : g_prod
    logic signed [CW-1:0] ck;
    assign ck = coef_i[k*CW +: CW];
    assign nk_all[k*AccW +: AccW] = AccW'(ck) * AccW'($signed({1'b0, f_e[k*FW +: FW]}));
    for (genvar a = 0; a < 3; a++) begin : g_axis
      logic signed [GKW-1:0] ga;
      assign ga = g_e[(3*k + a)*GKW +: GKW];
      assign gk_all[(3*k + a)*AccW +: AccW] = AccW'(ck) * AccW'(ga);
    end
  end

  logic signed [AccW-1:0] nacc;
  logic [3*AccW-1:0]      gacc;
  always_comb begin
    logic signed [AccW-1:0] ga;
    nacc = '0;
    for (int k = 0; k < K; k++) nacc = nacc + $signed(nk_all[k*AccW +: AccW]);
    for (int a = 0; a < 3; a++) begin
      ga = '0;
      for (int k = 0; k < K; k++) ga = ga + $signed(gk_all[(3*k + a)*AccW +: AccW]);
      gacc[a*AccW +: AccW] = ga;
    end
  end

  logic [NW-1:0]    n_b;
  logic [3*NGW-1:0] g_b;
  pst_floor_sat #(.InWidth(AccW), .InFrac(CF + NF), .OutWidth(NW), .OutFrac(OF)) u_n_sat (
    .x_i (nacc), .y_o (n_b));
  for (genvar a = 0; a < 3; a++) begin : g_grad_sat
    pst_floor_sat #(.InWidth(AccW), .InFrac(CF + NF), .OutWidth(NGW), .OutFrac(OF)) u_sat (
      .x_i (gacc[a*AccW +: AccW]), .y_o (g_b[a*NGW +: NGW]));
  end

  // The remaining pipeline registers at the output, and the token decoded there.
  pst_noise_out #(.Width(NW + 3*NGW), .Regs(RO), `PST_NOISE_STEPS_PASS) u_out (
    .clk_i, .rst_ni, .en_i, .tok_i (tok_e), .data_i ({g_b, n_b}),
    .valid_o, .last_o, .data_o ({grad_o, n_o}));

  logic unused_in;   // lattice bits above the 8-bit cube hash, coefficients above K
  if (K < 4) begin : g_unused_coef
    assign unused_in = ^{list_in, lat_i[LB-1:8], lat_i[2*LB-1:LB+8], lat_i[3*LB-1:2*LB+8], coef_i[4*CW-1:K*CW]};
  end else begin : g_used_coef
    assign unused_in = ^{list_in, lat_i[LB-1:8], lat_i[2*LB-1:LB+8], lat_i[3*LB-1:2*LB+8]};
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (NoiseWorleySearch == pst_pkg::NoiseWorleySearchNone) $error("pst_worley: NoiseWorleySearch is none");
    if (NoiseRegs < 0 || NoiseRegs > 6) $error("pst_worley: NoiseRegs must be 0..6");
  end
  // Every cube has at least one point, so after the last step the list is full (K <= 8).
  assert property (@(posedge clk_i) disable iff (!rst_ni)
                   (tok_b[3] && 32'(tok_b[2:0]) == NoiseSteps - 1) |-> (list_b[(K-1)*EW +: SW] != '1));
`endif

endmodule

`default_nettype wire

// The subband unit: the anisotropic-noise basis of Goldberg, Zwicker, Durand 2008 (model/subband.h)
// as the hardware samples it, in place of the lattice-noise unit (pst_noise) when the profile's
// noise.subband is not none: one octave's subbands read from a tile ROM by bilinear, periodic
// lookups on two lattice axes, one corner per noise step; the isotropic sum (K = 0, eq. 7 with
// every lambda_ij = 1) or K = 4, 8 oriented tiles weighted by the pixel's lambda_i (eq. 7 with
// the anisotropic filter's weights, pst_subband_pixel and pst_octave_fade in
// pst_octave_serial or pst_octave_parallel). Same ports and token timing as pst_noise, plus lam_i. Golden:
// pst::subbandFx (model/golden/subband_fx.cpp, same steps and floors); its double reference is
// pst::subbandRomReference (the bilinear lookup of the unrounded tiles).
//
// Notation: LF = NoiseLatticeFrac, OF = NoiseOutFrac, TL = SubbandTileLog2, UB = TL -
// SubbandPeriodLog2 (ROM pixels per noise unit 2^UB), WF = LF - UB, VB / VF = SubbandValueBits /
// SubbandValueFrac, (A0, A1) the plane's lattice axes (xy: 0, 1; xz: 0, 2; yz: 1, 2), K =
// NoiseSubbandOrientations, FF = FadeFrac (the weights' fraction bits), VF' = VF (K = 0) or VF + FF.
//
// 1. Tile pixel per in-plane axis a: x_a = {lat_a mod 2^(TL - UB), frac_a >> WF} (TL bits), the
//    weight's fraction w_a = frac_a mod 2^WF.
// 2. Corners c = cx + 2 cy: step j reads corners j CPS .. j CPS + CPS - 1, CPS = ceil(4 /
//    NoiseSteps) (one per step on the reduced schedule; the later steps' slots are off): ROM
//    word at {(x_A1 + cy) mod 2^TL, (x_A0 + cx) mod 2^TL}: K = 0 its value v_c; K = 4, 8 its K
//    values v_c,i, v_c = sum_i lambda_i v_c,i (exact); weights u_0 = 2^WF - w, u_1 = w. With the
//    four corners in one step (CPS = 4) and K = 4, 8 the tiles sit in four banks by the pixel's row
//    and column parity (one read a bank: the four corners fall in four banks).
// 3. Exact sums, held across the steps (step 0 starts from 0):
//    V += v_c u_cx(w_A0) u_cy(w_A1), Gx += +-v_c u_cy(w_A1) (+ for cx = 1), Gy += +-v_c u_cx(w_A0).
// 4. n = sat(floor(V / 2^(VF' + 2 WF - OF)), Q4.OF); grad_A0 = sat(floor(Gx / 2^(VF' + WF - UB -
//    OF)), Q6.OF) (2^UB ROM pixels per noise unit), grad_A1 from Gy, the third axis 0.
//
// Pipeline (NoiseRegs): a register at b0 between the step's corner values (the ROM read and the
// weighted sums) and the bilinear sums (the first), the others at the output; the result of the
// last step comes NoiseRegs advances (en_i) after its input, as pst_noise's. The held sums store
// at every valid advance of b0's token (steps come on consecutive advances). With the four
// corners in one step (NoiseSteps = 1) and NoiseRegs >= 2 the sums are formed in two halves with
// the second register between them (b1; the same integers, regrouped): the rows' lerps r_cy =
// sum_cx v_c u_cx and differences d_cy = v_(1,cy) - v_(0,cy) before it, V = sum_cy r_cy u_cy,
// Gx = sum_cy d_cy u_cy, Gy = r_1 - r_0 after it; with the filter (K = 4, 8) and NoiseRegs >= 3
// the first register holds the ROM words and the weights instead and the second (bw) the corner
// values, b1 then being the third.
//
// Parameters: NoiseLatticeFrac, NoiseOutFrac, NoiseSteps, NoiseRegs (the profile's noise keys),
// NoiseSubband (the plane: pst_pkg::NoiseSubbandXy, Xz or Yz), NoiseSubbandOrientations (K: 0,
// 4 or 8).
// Ports: pst_noise's; lam_i [max(1, K)*FadeBits-1:0] the weights lambda_i (i at [i*FadeBits +:
// FadeBits], unsigned, 1.0 = 2^FadeFrac; unused for K = 0), steady over an evaluation's steps.
`include "pst_pkg.sv"
`include "pst_params.svh"
`include "noise/pst_rom_dir.svh"
`default_nettype none

module pst_subband #(
  `PST_SUBBAND_PARAMS,
  parameter int NoiseSubband     = pst_pkg::NoiseSubbandXz,
  parameter int NoiseSubbandOrientations = 0,
  localparam int LF  = NoiseLatticeFrac,
  localparam int KT  = (NoiseSubbandOrientations == 0) ? 1 : NoiseSubbandOrientations,  // tiles
  localparam int FB  = pst_pkg::FadeBits,
  localparam int OF  = NoiseOutFrac,
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,
  localparam int LB  = pst_pkg::LatticeBits
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic               en_i,
  input  logic               valid_i,
  input  logic [2:0]         step_i,
  input  logic [pst_pkg::LatticeWidth-1:0] lat_i,
  input  logic [3*LF-1:0]    frac_i,
  input  logic [KT*FB-1:0]   lam_i,
  output logic               valid_o,
  output logic               last_o,
  output logic signed [NW-1:0]  n_o,
  output logic [3*NGW-1:0]      grad_o
);

  localparam int TL  = pst_pkg::SubbandTileLog2;
  localparam int PL  = pst_pkg::SubbandPeriodLog2;
  localparam int UB  = TL - PL;
  localparam int WF  = LF - UB;
  localparam int VB  = pst_pkg::SubbandValueBits;
  localparam int K   = NoiseSubbandOrientations;
  localparam int VF  = pst_pkg::SubbandValueFrac + ((K == 0) ? 0 : pst_pkg::FadeFrac);
  localparam int CVW = (K == 0) ? VB : VB + FB + 4;  // a corner's value: sum of K <= 8 products
  localparam int A0  = (NoiseSubband == pst_pkg::NoiseSubbandYz) ? 1 : 0;
  localparam int A1  = (NoiseSubband == pst_pkg::NoiseSubbandXy) ? 1 : 2;
  localparam int A2  = 3 - A0 - A1;                 // the axis outside the plane
  localparam int CPS = (4 + NoiseSteps - 1) / NoiseSteps;
  localparam int UW  = WF + 1;                      // a weight u (unsigned, <= 2^WF)
  localparam int VW  = CVW + 2 * UW + 2;            // V (signed): 4 products v u u
  localparam int GW  = CVW + UW + 2;                // Gx, Gy (signed): 4 products +-v u
  localparam int SUMW = VW + 2 * GW;                // the held sums {Gy, Gx, V}
  // |V| <= 2^VBE: a convex combination of corners of |v| <= KT 2^(VB-1) (2^FadeFrac) (pst_subband_sva).
  localparam int VBE = VB - 1 + 2 * WF + ((K == 0) ? 0 : pst_pkg::FadeFrac + $clog2(KT));

  // ---- 1. tile pixel and weights -------------------------------------------------------------
  logic [TL-1:0] x0, x1;
  logic [WF-1:0] w0, w1;
  assign x0 = {lat_i[A0*LB +: PL], frac_i[A0*LF + WF +: UB]};
  assign x1 = {lat_i[A1*LB +: PL], frac_i[A1*LF + WF +: UB]};
  assign w0 = frac_i[A0*LF +: WF];
  assign w1 = frac_i[A1*LF +: WF];

  // ---- 2. this step's corners: the ROM words and (K = 4, 8) their weighted sums --------------
  localparam bit Split = (CPS == 4) && (NoiseRegs >= 2);            // b1 between the rows and the columns
  localparam bit Deep  = Split && (K != 0) && (NoiseRegs >= 3);     // b0 after the ROM read, bw after the sums
  localparam int R0    = (NoiseRegs >= 1) ? 1 : 0;
  logic [CPS*KT*VB-1:0] word_a, word_s;   // slot i: corner step_i CPS + i (a slot past corner 3 is off in step 3)
  logic [KT*FB-1:0]     lam_s;
  logic [CPS*CVW-1:0]   cv_s;
  // The ROM: one tile array (word {row, column}), one read per corner of the step; with the four
  // corners in one step and the filter, four banks by the pixel's row and column parity (bank
  // 2 (row mod 2) + (column mod 2), word {row / 2, column / 2}: subband_k<K>_b<B>.memh), one read
  // a bank, the corners taken from the banks by the parities of x0, x1.
  localparam bit Banked = (CPS == 4) && (K != 0);
  if (!Banked) begin : g_rom
    logic [KT*VB-1:0] tile [1 << (2*TL)];
    if (K == 0) begin : g_iso
      initial $readmemh({`PST_ROM_DIR, "/subband.memh"}, tile);
    end else if (K == 4) begin : g_k4
      initial $readmemh({`PST_ROM_DIR, "/subband_k4.memh"}, tile);
    end else begin : g_k8
      initial $readmemh({`PST_ROM_DIR, "/subband_k8.memh"}, tile);
    end
    always_comb begin
      logic [TL-1:0] cx_addr, cy_addr;
      int            c;
      for (int i = 0; i < CPS; i++) begin
        c = 32'(step_i) * CPS + i;
        cx_addr = x0 + TL'(c & 1);
        cy_addr = x1 + TL'((c >> 1) & 1);
        word_a[i*KT*VB +: KT*VB] = tile[{cy_addr, cx_addr}];
      end
    end
  end else begin : g_banks
    localparam int BA = 2*TL - 2;   // a bank's address
    logic [KT*VB-1:0] rom_b0 [1 << BA];
    logic [KT*VB-1:0] rom_b1 [1 << BA];
    logic [KT*VB-1:0] rom_b2 [1 << BA];
    logic [KT*VB-1:0] rom_b3 [1 << BA];
    if (K == 4) begin : g_k4
      initial $readmemh({`PST_ROM_DIR, "/subband_k4_b0.memh"}, rom_b0);
      initial $readmemh({`PST_ROM_DIR, "/subband_k4_b1.memh"}, rom_b1);
      initial $readmemh({`PST_ROM_DIR, "/subband_k4_b2.memh"}, rom_b2);
      initial $readmemh({`PST_ROM_DIR, "/subband_k4_b3.memh"}, rom_b3);
    end else begin : g_k8
      initial $readmemh({`PST_ROM_DIR, "/subband_k8_b0.memh"}, rom_b0);
      initial $readmemh({`PST_ROM_DIR, "/subband_k8_b1.memh"}, rom_b1);
      initial $readmemh({`PST_ROM_DIR, "/subband_k8_b2.memh"}, rom_b2);
      initial $readmemh({`PST_ROM_DIR, "/subband_k8_b3.memh"}, rom_b3);
    end
    // Bank b holds the corner cx = b[0] ^ x0[0], cy = b[1] ^ x1[0] of this step.
    logic [TL-1:0]      col0, col1, row0, row1;   // the columns of parity 0, 1; the rows
    logic [4*KT*VB-1:0] bword;
    logic x0_even, x1_even;
    assign x0_even = ~x0[0];
    assign x1_even = ~x1[0];
    assign col0 = x0 + TL'(x0[0]);                // x0 or x0 + 1, whichever is even
    assign col1 = x0 + TL'(x0_even);              // the odd one
    assign row0 = x1 + TL'(x1[0]);
    assign row1 = x1 + TL'(x1_even);
    assign bword[0*KT*VB +: KT*VB] = rom_b0[{row0[TL-1:1], col0[TL-1:1]}];
    assign bword[1*KT*VB +: KT*VB] = rom_b1[{row0[TL-1:1], col1[TL-1:1]}];
    assign bword[2*KT*VB +: KT*VB] = rom_b2[{row1[TL-1:1], col0[TL-1:1]}];
    assign bword[3*KT*VB +: KT*VB] = rom_b3[{row1[TL-1:1], col1[TL-1:1]}];
    logic unused_lsb;   // the banks' parities (bit 0 of the rows and columns)
    assign unused_lsb = ^{col0[0], col1[0], row0[0], row1[0]};
    always_comb begin
      logic [1:0] b;
      for (int c = 0; c < 4; c++) begin
        b = {1'((c >> 1) & 1) ^ x1[0], 1'(c & 1) ^ x0[0]};
        word_a[c*KT*VB +: KT*VB] = bword[32'(b)*KT*VB +: KT*VB];
      end
    end
  end
  always_comb begin
    logic signed [CVW-1:0] v;
    for (int i = 0; i < CPS; i++) begin
      if (K == 0) begin
        v = CVW'($signed(word_s[i*KT*VB +: VB]));
      end else begin
        // The corner's weighted sum of its K words (eq. 7), exact.
        v = '0;
        for (int t = 0; t < KT; t++)
          v = v + CVW'($signed(word_s[i*KT*VB + t*VB +: VB])) * CVW'($signed({1'b0, lam_s[t*FB +: FB]}));
      end
      cv_s[i*CVW +: CVW] = v;
    end
  end

  // Boundary b0 (the first pipeline register): the step's corner values, the bilinear weights'
  // fractions and the token; the sums are formed after it. Deep: b0 holds the ROM words and the
  // weights, bw (the second register) the corner values.
  logic [CPS*CVW-1:0] cv_b;
  logic [WF-1:0]      w0_b, w1_b;
  logic [3:0]         tok_b;
  if (Deep) begin : g_deep
    logic [WF-1:0] w0_0, w1_0;
    logic [3:0]    tok_0;
    pst_delay #(.Width(CPS*KT*VB + KT*FB + 2*WF), .Depth(1)) u_b0 (
      .clk_i, .rst_ni, .en_i, .d_i ({word_a, lam_i, w1, w0}), .q_o ({word_s, lam_s, w1_0, w0_0}));
    pst_delay #(.Width(4), .Depth(1), .Reset(1'b1)) u_b0_tok (
      .clk_i, .rst_ni, .en_i, .d_i ({valid_i, step_i}), .q_o (tok_0));
    pst_delay #(.Width(CPS*CVW + 2*WF), .Depth(1)) u_bw (
      .clk_i, .rst_ni, .en_i, .d_i ({cv_s, w1_0, w0_0}), .q_o ({cv_b, w1_b, w0_b}));
    pst_delay #(.Width(4), .Depth(1), .Reset(1'b1)) u_bw_tok (
      .clk_i, .rst_ni, .en_i, .d_i (tok_0), .q_o (tok_b));
  end else begin : g_flat
    assign word_s = word_a;
    assign lam_s  = lam_i;
    pst_delay #(.Width(CPS*CVW + 2*WF), .Depth(R0)) u_b0 (
      .clk_i, .rst_ni, .en_i, .d_i ({cv_s, w1, w0}), .q_o ({cv_b, w1_b, w0_b}));
    pst_delay #(.Width(4), .Depth(R0), .Reset(1'b1)) u_b0_tok (
      .clk_i, .rst_ni, .en_i, .d_i ({valid_i, step_i}), .q_o (tok_b));
  end

  // ---- 3. the sums {Gy, Gx, V} and the token beside them (tok_s) ---------------------------------
  localparam int RO    = NoiseRegs - R0 - (Split ? 1 : 0) - (Deep ? 1 : 0);
  logic [SUMW-1:0] sum_out;
  logic [3:0]      tok_s;
  if (!Split) begin : g_held
    // Held across the steps (step 0 starts from 0).
    logic [SUMW-1:0] held_q, sum_in;
    always_comb begin
      logic signed [VW-1:0]  v_acc;
      logic signed [GW-1:0]  gx_acc, gy_acc;
      logic signed [CVW-1:0] v;
      logic [UW-1:0]         ux, uy;
      int                    c;
      sum_in = (tok_b[2:0] == 3'd0) ? '0 : held_q;
      {gy_acc, gx_acc, v_acc} = sum_in;
      for (int i = 0; i < CPS; i++) begin
        c = 32'(tok_b[2:0]) * CPS + i;
        v  = cv_b[i*CVW +: CVW];
        ux = ((c & 1) != 0) ? UW'(w0_b) : UW'(1 << WF) - UW'(w0_b);
        uy = ((c & 2) != 0) ? UW'(w1_b) : UW'(1 << WF) - UW'(w1_b);
        if (c < 4) begin
          v_acc = v_acc + VW'(v) * VW'($signed({1'b0, ux})) * VW'($signed({1'b0, uy}));
          if ((c & 1) != 0) gx_acc = gx_acc + GW'(v) * GW'($signed({1'b0, uy}));
          else              gx_acc = gx_acc - GW'(v) * GW'($signed({1'b0, uy}));
          if ((c & 2) != 0) gy_acc = gy_acc + GW'(v) * GW'($signed({1'b0, ux}));
          else              gy_acc = gy_acc - GW'(v) * GW'($signed({1'b0, ux}));
        end
      end
      sum_out = {gy_acc, gx_acc, v_acc};
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) held_q <= '0;
      else if (en_i && tok_b[3]) held_q <= sum_out;
    end
    assign tok_s = tok_b;
  end else begin : g_split
    // The rows' lerps along A0 and their differences, register b1, the lerp along A1.
    localparam int RW = CVW + UW + 1;   // r_cy (signed)
    localparam int DW = CVW + 1;        // d_cy (signed)
    logic [2*RW+2*DW+WF-1:0] rows_a, rows_b;
    always_comb begin
      logic signed [CVW-1:0] v00, v10, v01, v11;   // v_(cx,cy)
      logic [UW-1:0]         ux0, ux1;
      logic signed [RW-1:0]  r0, r1;
      logic signed [DW-1:0]  d0, d1;
      {v11, v01, v10, v00} = cv_b;
      ux0 = UW'(1 << WF) - UW'(w0_b);
      ux1 = UW'(w0_b);
      r0 = RW'(v00) * RW'($signed({1'b0, ux0})) + RW'(v10) * RW'($signed({1'b0, ux1}));
      r1 = RW'(v01) * RW'($signed({1'b0, ux0})) + RW'(v11) * RW'($signed({1'b0, ux1}));
      d0 = DW'(v10) - DW'(v00);
      d1 = DW'(v11) - DW'(v01);
      rows_a = {w1_b, d1, d0, r1, r0};
    end
    pst_delay #(.Width(2*RW + 2*DW + WF), .Depth(1)) u_b1 (
      .clk_i, .rst_ni, .en_i, .d_i (rows_a), .q_o (rows_b));
    pst_delay #(.Width(4), .Depth(1), .Reset(1'b1)) u_b1_tok (
      .clk_i, .rst_ni, .en_i, .d_i (tok_b), .q_o (tok_s));
    always_comb begin
      logic signed [RW-1:0] r0, r1;
      logic signed [DW-1:0] d0, d1;
      logic [WF-1:0]        w1_c;
      logic [UW-1:0]        uy0, uy1;
      {w1_c, d1, d0, r1, r0} = rows_b;
      uy0 = UW'(1 << WF) - UW'(w1_c);
      uy1 = UW'(w1_c);
      sum_out = {GW'(r1) - GW'(r0),
                 GW'(d0) * GW'($signed({1'b0, uy0})) + GW'(d1) * GW'($signed({1'b0, uy1})),
                 VW'(r0) * VW'($signed({1'b0, uy0})) + VW'(r1) * VW'($signed({1'b0, uy1}))};
    end
  end
  logic [SUMW-1:0] sum_b;
  assign sum_b = sum_out;

  // ---- 4. floor and saturate -------------------------------------------------------------------
  logic [NW-1:0]  n_b;
  logic [NGW-1:0] gx_b, gy_b;
  pst_floor_sat #(.InWidth(VW), .InFrac(VF + 2*WF), .OutWidth(NW), .OutFrac(OF)) u_n_sat (
    .x_i (sum_b[0 +: VW]), .y_o (n_b));
  pst_floor_sat #(.InWidth(GW), .InFrac(VF + WF - UB), .OutWidth(NGW), .OutFrac(OF)) u_gx_sat (
    .x_i (sum_b[VW +: GW]), .y_o (gx_b));
  pst_floor_sat #(.InWidth(GW), .InFrac(VF + WF - UB), .OutWidth(NGW), .OutFrac(OF)) u_gy_sat (
    .x_i (sum_b[VW + GW +: GW]), .y_o (gy_b));
  logic [3*NGW-1:0] g_b;
  always_comb begin
    g_b = '0;
    g_b[A0*NGW +: NGW] = gx_b;
    g_b[A1*NGW +: NGW] = gy_b;
    g_b[A2*NGW +: NGW] = '0;
  end

  // The remaining pipeline registers at the output, and the token decoded there.
  pst_noise_out #(.Width(NW + 3*NGW), .Regs(RO), `PST_NOISE_STEPS_PASS) u_out (
    .clk_i, .rst_ni, .en_i, .tok_i (tok_s), .data_i ({g_b, n_b}),
    .valid_o, .last_o, .data_o ({grad_o, n_o}));

  logic unused_in;   // lattice bits above the period, the third axis, the token's step
  assign unused_in = ^{lat_i[A0*LB + PL +: LB - PL], lat_i[A1*LB + PL +: LB - PL],
                       lat_i[A2*LB +: LB], frac_i[A2*LF +: LF], (K == 0) ? ^{lam_i, lam_s} : 1'b0};

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (NoiseSubband == pst_pkg::NoiseSubbandNone) $error("pst_subband: NoiseSubband is none");
    if (WF < 1) $error("pst_subband: NoiseLatticeFrac must exceed SubbandTileLog2 - SubbandPeriodLog2");
    if (NoiseRegs < 0 || NoiseRegs > 6) $error("pst_subband: NoiseRegs must be 0..6");
    if (K != 0 && K != 4 && K != 8) $error("pst_subband: NoiseSubbandOrientations must be 0, 4 or 8");
  end
`endif

endmodule

`default_nettype wire

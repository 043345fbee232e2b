// pst_octave_parallel: the parallel octave datapath of pst_octave_stage: every product every
// cycle, a fragment per Passes x NoiseSteps cycles (a pixel per clock with one pass of one
// step; Passes = ceil(Octaves / NoiseUnits): when NoiseUnits does not divide Octaves, the last
// pass's lanes beyond the octaves evaluate noise whose term is zero). Each cycle of a fragment
// in [A] issues a beat (its pass, step, first / last flags) into a pipeline of
// Lat = TR + XR + NoiseRegs + MR registers, which carries side_i (the tag and
// Jacobian) beside it; [A] is released at the last beat's issue. Per lane (pst_octave_lane):
//   issue     octave transform of the beat's pass            -> TR + XR registers (OctaveRegs 3: TR
//             between its products and their sum; >= 2: XR after it, two with the subband filter
//             and OctaveRegs 3)
//   noise     the noise units (outside, pst_octave_noise)     -> NoiseRegs registers
//   term      octave term, zero unless the lane's octave is active -> MR registers (OctaveRegs >= 1)
// The quadric (pst_quadric, folded over the last two beats when a fragment has two or more:
// pst_quadric_fold) runs beside, pipelined through the first min(2, Lat) registers.
// At the end the beat's terms go to the accumulators (acc_en_o, acc_first_o); the last beat
// offers the fragment to [B] (valid_o) and the whole pipeline stalls while [B] refuses it.
// busy_o: a beat is inside the pipeline's registers.
//
// Bandlimited octaves: the fade chain of a beat is spread over the XR + NoiseRegs registers
// between its issue and its term: a register after the pixel's lengths (F1), one after their
// lg (F2, pst_fade_pixel), the rest after the lanes' fades (F3); fewer registers leave the
// chain combinational.
//
// The subband unit's anisotropic filter (noise.subband_orientations K = 4, 8): the weights
// lambda_i of a beat reach the noise units with its lattice point, so their chain is spread
// over the TR + XR registers between the issue and the noise units (OctaveRegs 3 puts a second
// register after the transform, XR = 2, for it): the pixel's lengths along the K orientations
// and their lg (pst_subband_pixel, shared by the lanes; a register after the lengths when TR + XR
// = 3, SL0, one after the lg when >= 2, SL1), then per lane the K weights from its octave's
// lg ||M|| and the fade table (pst_octave_fade per orientation), registered (SL2 = 1 when TR + XR
// >= 1). The term is then not faded (the lanes' TermFade = 0).
//
// Parameters: pst_octave_stage's (the profile's formats and registers); DebugProbes = 0 ties
// the pr_* outputs to zero.
`include "pst_pkg.sv"
`include "pst_params.svh"
`include "octave/pst_octave_datapath_ports.svh"
`default_nettype none

module pst_octave_parallel #(
  `PST_OCTAVE_PARAMS,
  `PST_LANE_PARAMS,
  parameter int SideW = pst_pkg::TagBits, parameter bit DebugProbes = 1'b1,
  parameter int NoiseSubband = pst_pkg::NoiseSubbandNone,   // the subband unit's plane
  parameter int NoiseSubbandOrientations = 0,               // its filter's orientations K (0: none)
  `PST_OCTAVE_DATAPATH_WIDTHS
) (
  `PST_OCTAVE_DATAPATH_PORTS
);

  localparam int Passes   = pst_pkg::octave_passes(Octaves, NoiseUnits);
  localparam int PassBits = (Passes > 1) ? $clog2(Passes) : 1;
  localparam int SK       = NoiseSubbandOrientations;
  localparam bit Aniso    = (NoiseSubband != pst_pkg::NoiseSubbandNone) && (SK != 0);
  localparam int TR       = (OctaveRegs >= 3) ? 1 : 0;   // inside the transform (products | sum)
  // after the transform; with the subband filter and OctaveRegs 3 two (the weights' chain: three)
  localparam int XR       = ((OctaveRegs >= 2) ? 1 : 0) + ((Aniso && OctaveRegs >= 3) ? 1 : 0);
  localparam int NR       = NoiseRegs;                    // inside the noise units
  localparam int MR       = pst_pkg::term_regs(OctaveRegs);   // after the term
  localparam int Lat      = TR + XR + NR + MR;
  localparam int Cycles   = pst_pkg::octave_cycles(Octaves, NoiseUnits, NoiseSteps, pst_pkg::DatapathParallel,
                                                 NoiseRegs, OctaveRegs);   // a fragment's beats
  localparam int CycBits  = (Cycles > 1) ? $clog2(Cycles) : 1;
  localparam bit Bl       = (FilterBandlimit == pst_pkg::FilterBandlimitIsotropic);
  localparam int LgW      = $clog2((JW + 1) << pst_pkg::FadeLgFrac) + 1;
  localparam int FL       = TR + XR + NR;                 // the fade chain's registers
  localparam int F1       = (FL >= 3) ? 1 : 0;
  localparam int F2       = (FL >= 2) ? 1 : 0;
  localparam int F3       = FL - F1 - F2;
  localparam bit BlTerm   = Bl && !Aniso;                // the term's fade
  localparam int SL0      = (TR + XR >= 3) ? 1 : 0;      // the weights' chain: after the lengths
  localparam int SL1      = (TR + XR >= 2) ? 1 : 0;      // after the lg
  localparam int SL2      = TR + XR - SL0 - SL1;         // after the lanes' weights

  typedef struct packed {
    logic                valid;
    logic [PassBits-1:0] pass;
    logic [Passes-1:0]   pass_oh;   // the pass one-hot (the term's register select)
    logic [NoiseUnits-1:0] on;      // lane u's octave is active (decided at issue)
    logic [2:0]          step;
    logic                first;
    logic                last;
  } beat_t;

  // The fragment's cycle in [A] and the beat it issues: pass p, noise step j at cycle
  // p NoiseSteps + j.
  logic [CycBits-1:0] cyc_q, cyc_d;
  logic               en;         // the pipeline advances
  beat_t              beat_f, beat_x, beat_n, beat_e;   // at issue, after [X], after the noise, at the end
  logic [SideW-1:0]   side_x, side_n, side_e;
  logic [PassBits-1:0] npass;
  logic [2:0]          nstep;
  assign npass  = PassBits'(32'(cyc_q) / NoiseSteps);
  assign nstep  = 3'(32'(cyc_q) % NoiseSteps);
  assign beat_f.valid = valid_i;
  assign beat_f.pass  = npass;
  assign beat_f.pass_oh = Passes'(1) << npass;
  for (genvar u = 0; u < NoiseUnits; u++) begin : g_on
    assign beat_f.on[u] = (OctBits + 1)'(32'(npass) * NoiseUnits + u) < {1'b0, active_i};
  end
  assign beat_f.step  = nstep;
  assign beat_f.first = (cyc_q == '0);
  assign beat_f.last  = (32'(cyc_q) + 1 >= Cycles);

  // The pipeline stalls only while the end holds a last beat that [B] refuses.
  assign en      = ~(valid_o & ~ready_i);
  assign ready_o = beat_f.last & en;
  always_comb begin
    cyc_d = cyc_q;
    if (en && valid_i) cyc_d = beat_f.last ? '0 : cyc_q + 1'b1;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) cyc_q <= '0;
    else cyc_q <= cyc_d;
  end

  // Quadric, pipelined through the first min(2, Lat) registers and delayed through the rest:
  // every product every beat with one beat per fragment; with two or more, folded over the
  // last two (rows 0 and 1 on the beat before the last, row 2 on the last: pst_quadric_fold).
  localparam int QR = (Lat < 2) ? Lat : 2;
  logic [FW-1:0]   q_f;
  logic [3*GW-1:0] gradq_f;
  if (Cycles >= 2) begin : g_quad_fold
    // cyc_q == Cycles - 2, registered from cyc_d (the rows' select without the compare)
    logic fold_first_d, fold_first_q;
    assign fold_first_d = (32'(cyc_d) == Cycles - 2);
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) fold_first_q <= (Cycles == 2);
      else fold_first_q <= fold_first_d;
    end
    pst_quadric_fold #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac),
      .Regs(QR), .SelReg(Cycles >= 3)
    ) u_quadric (
      .clk_i, .rst_ni, .en_i (en), .first_i (fold_first_q), .first_next_i (fold_first_d),
      .s_i (s_i), .coef_i (quad_i),
      .q_o (q_f), .gradq_o (gradq_f)
    );
  end else begin : g_quad
    pst_quadric #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac),
      .Regs(QR)
    ) u_quadric (
      .clk_i, .rst_ni, .en_i (en), .s_i (s_i), .coef_i (quad_i), .q_o (q_f), .gradq_o (gradq_f)
    );
  end
  pst_delay #(.Width(FW + 3*GW), .Depth(Lat - QR)) u_q_delay (
    .clk_i, .rst_ni, .en_i (en), .d_i ({gradq_f, q_f}), .q_o ({gradq_o, q_o}));

  // Beats and side payload: [X] after the transform, NR beside the noise units, [M] after the
  // term.
  pst_delay #(.Width($bits(beat_f)), .Depth(TR + XR), .Reset(1'b1)) u_beat_x (
    .clk_i, .rst_ni, .en_i (en), .d_i (beat_f), .q_o (beat_x));
  pst_delay #(.Width($bits(beat_f)), .Depth(NR), .Reset(1'b1)) u_beat_n (
    .clk_i, .rst_ni, .en_i (en), .d_i (beat_x), .q_o (beat_n));
  pst_delay #(.Width($bits(beat_f)), .Depth(MR), .Reset(1'b1)) u_beat_e (
    .clk_i, .rst_ni, .en_i (en), .d_i (beat_n), .q_o (beat_e));
  pst_delay #(.Width(SideW), .Depth(TR + XR)) u_side_x (
    .clk_i, .rst_ni, .en_i (en), .d_i (side_i), .q_o (side_x));
  pst_delay #(.Width(SideW), .Depth(NR)) u_side_n (
    .clk_i, .rst_ni, .en_i (en), .d_i (side_x), .q_o (side_n));
  pst_delay #(.Width(SideW), .Depth(MR)) u_side_e (
    .clk_i, .rst_ni, .en_i (en), .d_i (side_n), .q_o (side_e));

  logic nlast_n;   // the beat after the noise units ends its pass's evaluation
  assign nlast_n    = beat_n.valid && (32'(beat_n.step) == NoiseSteps - 1);
  assign nz_en_o    = en;
  assign nz_valid_o = beat_x.valid;
  assign nz_step_o  = beat_x.step;

  // Beats in the pipeline's registers (issued, not yet past the end).
  if (Lat > 0) begin : g_count
    localparam int IW = $clog2(Lat + 2);
    logic [IW-1:0] inflight_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) inflight_q <= '0;
      else if (en) inflight_q <= inflight_q + IW'(valid_i) - IW'(beat_e.valid);
    end
    assign busy_o = (inflight_q != '0);
  end else begin : g_nocount
    assign busy_o = 1'b0;
  end

  // The pixel's lg edge lengths for the fades (F1 + F2 registers after the issue).
  logic [LgW-1:0] lgx, lgy;
  if (BlTerm) begin : g_fade_px
    pst_fade_pixel #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac), .LenRegs(F1), .LgRegs(F2)) u_px (
      .clk_i, .rst_ni, .en_i (en), .j_i (side_i[TB +: 6*JW]), .lgx_o (lgx), .lgy_o (lgy));
  end else begin : g_no_fade
    assign lgx = '0;
    assign lgy = '0;
  end

  // The pixel's lg edges along the subband unit's K orientations (SL1 registers after the issue).
  logic [2*(Aniso ? SK : 1)*LgW-1:0] sb_lg;
  if (Aniso) begin : g_sb_px
    pst_subband_pixel #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac), .NoiseSubband(NoiseSubband),
      .K(SK), .LenRegs(SL0), .LgRegs(SL1)) u_sb_px (
      .clk_i, .rst_ni, .en_i (en), .j_i (side_i[TB +: 6*JW]), .lg_o (sb_lg));
  end else begin : g_no_sb_px
    assign sb_lg = '0;
    logic unused_sb_lg;
    assign unused_sb_lg = ^sb_lg;
  end

  for (genvar u = 0; u < NoiseUnits; u++) begin : g_lane
    // The register arrays indexed by the octave of the beat: at issue (transform, lg ||M||)
    // and after the noise units (term); a constant when Passes = 1.
    logic [9*MW-1:0]  m_sel;
    logic [3*OW-1:0]  o_sel;
    logic [AW-1:0]    a_sel;
    logic [FW-1:0]    fm_sel;
    logic [9*GMW-1:0] gm_sel;
    logic [LMW-1:0]   lgm_sel;
    always_comb begin
      m_sel   = oct_m_i[u*9*MW +: 9*MW];
      o_sel   = oct_o_i[u*3*OW +: 3*OW];
      lgm_sel = oct_lgm_i[u*LMW +: LMW];
      a_sel   = oct_a_i[u*AW +: AW];
      fm_sel  = oct_fm_i[u*FW +: FW];
      gm_sel  = oct_gm_i[u*9*GMW +: 9*GMW];
      for (int p = 1; p < Passes; p++) begin
        // (a lane of the last pass beyond the octaves keeps its first selection: its term is
        // zero, lane_on below)
        if (p * NoiseUnits + u < Octaves) begin
          if (32'(npass) == p) begin
            m_sel   = oct_m_i[(p * NoiseUnits + u)*9*MW +: 9*MW];
            o_sel   = oct_o_i[(p * NoiseUnits + u)*3*OW +: 3*OW];
            lgm_sel = oct_lgm_i[(p * NoiseUnits + u)*LMW +: LMW];
          end
          if (beat_n.pass_oh[p]) begin
            a_sel  = oct_a_i[(p * NoiseUnits + u)*AW +: AW];
            fm_sel = oct_fm_i[(p * NoiseUnits + u)*FW +: FW];
            gm_sel = oct_gm_i[(p * NoiseUnits + u)*9*GMW +: 9*GMW];
          end
        end
      end
    end
    // The lane's octave after the noise units is active (lane_on, decided at the beat's issue).
    logic lane_on;
    assign lane_on = beat_n.on[u];

    logic [LTW-1:0]  lat_f;
    logic [3*LF-1:0] frac_f;
    logic [LMW-1:0]  lgm_2;
    logic [FB-1:0]   alpha_2, alpha_n;
    logic [FW-1:0]   fterm;
    logic [3*GW-1:0] gterm;
    pst_octave_lane #(.Rows(3), .TransformRegs(TR), .LgW(LgW), .TermFade(BlTerm), `PST_LANE_PASS
    ) u_lane (
      .clk_i, .rst_ni, .en_i (en),
      .s_i (s_i), .m_i (m_sel), .o_i (o_sel), .lat_o (lat_f), .frac_o (frac_f),
      .bl_i (bl_i), .lgx_i (lgx), .lgy_i (lgy), .lgm_i (lgm_2), .fade_i (fade_i), .alpha_o (alpha_2),
      .n_i (nz_n_i[u*NW +: NW]), .g_i (nz_g_i[u*3*NGW +: 3*NGW]), .a_i (a_sel), .gm_i (gm_sel),
      .alpha_i (alpha_n), .fm_i (fm_sel), .fterm_o (fterm), .gterm_o (gterm)
    );
    pst_delay #(.Width(LTW + 3*LF), .Depth(XR)) u_x (
      .clk_i, .rst_ni, .en_i (en), .d_i ({lat_f, frac_f}),
      .q_o ({nz_lat_o[u*LTW +: LTW], nz_frac_o[u*3*LF +: 3*LF]}));
    // The octave's lg ||M|| carried with the pixel's lg (F1 + F2), its fade delayed beside the
    // noise unit to the term (F3).
    pst_delay #(.Width(LMW), .Depth(BlTerm ? F1 + F2 : 0)) u_lgm (
      .clk_i, .rst_ni, .en_i (en), .d_i (lgm_sel), .q_o (lgm_2));
    pst_delay #(.Width(FB), .Depth(BlTerm ? F3 : 0)) u_alpha (
      .clk_i, .rst_ni, .en_i (en), .d_i (alpha_2), .q_o (alpha_n));

    // The subband unit's weights of the beat's octave: its lg ||M|| carried with the pixel's lg
    // (SL0 + SL1), the K weights registered (SL2), so that they meet the beat at the noise unit.
    if (Aniso) begin : g_sb_lam
      logic [LMW-1:0] lgm_s;
      logic [SLW-1:0] lam_d;
      pst_delay #(.Width(LMW), .Depth(SL0 + SL1)) u_sb_lgm (
        .clk_i, .rst_ni, .en_i (en), .d_i (lgm_sel), .q_o (lgm_s));
      for (genvar i = 0; i < SK; i++) begin : g_dir
        pst_octave_fade #(.LgW(LgW)) u_lam (
          .en_i (bl_i), .lgx_i (sb_lg[i*LgW +: LgW]), .lgy_i (sb_lg[(SK + i)*LgW +: LgW]), .lgm_i (lgm_s),
          .table_i (fade_i), .alpha_o (lam_d[i*FB +: FB]));
      end
      pst_delay #(.Width(SLW), .Depth(SL2)) u_sb_lam (
        .clk_i, .rst_ni, .en_i (en), .d_i (lam_d), .q_o (nz_lam_o[u*SLW +: SLW]));
    end else begin : g_no_sb_lam
      // No filter: the weights are 1.0.
      for (genvar i = 0; i < SLW / FB; i++) begin : g_one
        assign nz_lam_o[u*SLW + i*FB +: FB] = FB'(1 << pst_pkg::FadeFrac);
      end
    end
    pst_delay #(.Width(FW + 3*GW), .Depth(MR)) u_m (
      .clk_i, .rst_ni, .en_i (en), .d_i ((lane_on && nlast_n) ? {gterm, fterm} : '0),
      .q_o ({gterm_o[u*3*GW +: 3*GW], fterm_o[u*FW +: FW]}));
  end

  assign acc_en_o    = en & beat_e.valid;
  assign acc_first_o = beat_e.first;
  assign valid_o     = beat_e.valid & beat_e.last;
  assign side_o      = side_e;

  assign pr_valid_o  = DebugProbes & nlast_n;
  assign pr_pass_o   = DebugProbes ? PPB'(beat_n.pass) : '0;
  assign pr_tag_o    = DebugProbes ? side_n[TB-1:0] : '0;
  assign pr_q_tag_o  = DebugProbes ? side_e[TB-1:0] : '0;
  logic unused;   // nz_last_i: the beats carry their own step
  assign unused = ^{nz_last_i, beat_x.pass, beat_x.pass_oh, beat_x.on, beat_x.first, beat_x.last, beat_n.first,
                    beat_n.last, beat_e.pass, beat_e.pass_oh, beat_e.on, beat_e.step, side_n[SideW-1:TB]};

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (OctaveRegs < 0 || OctaveRegs > 3) $error("pst_octave_parallel: OctaveRegs must be 0..3");
    if (Bl && SideW < TB + 6*JW) $error("pst_octave_parallel: SideW must hold the Jacobian above the tag");
  end
  assert property (@(posedge clk_i) disable iff (!rst_ni) 32'(cyc_q) < Cycles);
`endif

endmodule

`default_nettype wire

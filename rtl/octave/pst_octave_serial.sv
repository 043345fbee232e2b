// pst_octave_serial: the serial octave datapath of pst_octave_stage: the fragment stays in [A]
// for Cycles = Passes NoiseSteps + 2 SR + NoiseRegs + MR cycles (pst_pkg::
// SerialOctaveExtraCycles = 2 SR), counted by cyc_q, on the schedule of pst_octave_sched: per
// lane (pst_octave_lane, Rows = 1) one row of M_i s + o_i and one of a_i M_i^T g per cycle.
// The serial quadric (pst_quadric_serial) is stepped by the same count; a fragment whose octave
// cycles end first waits for it. With the term register (OctaveRegs >= 1, MR) the terms and
// the quadric pass a register before the accumulators.
//
// Bandlimited octaves: the pixel's lengths and their lg registered (pst_fade_pixel,
// free-running: the fragment's Jacobian stays in side_i while it is in [A]; the first term
// row's fade, registered one cycle ahead, is formed at cycle SR + NR + NoiseSteps - 1 >= 6,
// after both), each term pass's fade registered with the term rows' operands.
//
// Parameters: pst_octave_stage's (the profile's formats and registers); DebugProbes = 0 ties
// the pr_* outputs to zero.
`include "pst_pkg.sv"
`include "pst_params.svh"
`include "octave/pst_octave_datapath_ports.svh"
`default_nettype none

module pst_octave_serial #(
  `PST_OCTAVE_PARAMS,
  `PST_LANE_PARAMS,
  parameter int SideW = pst_pkg::TagBits, parameter bit DebugProbes = 1'b1,
  parameter int NoiseSubband = pst_pkg::NoiseSubbandNone,   // the subband unit's plane
  parameter int NoiseSubbandOrientations = 0,               // its filter's orientations K (0: none)
  localparam int LB  = pst_pkg::LatticeBits,
  `PST_OCTAVE_DATAPATH_WIDTHS
) (
  `PST_OCTAVE_DATAPATH_PORTS
);

  localparam int SR       = pst_pkg::SerialRows;
  localparam int SB       = pst_pkg::StepBits;
  localparam int Passes   = pst_pkg::octave_passes(Octaves, NoiseUnits);
  localparam int PassBits = (Passes > 1) ? $clog2(Passes) : 1;
  localparam int NR       = NoiseRegs;
  localparam int MR       = pst_pkg::term_regs(OctaveRegs);
  localparam int Cycles   = pst_pkg::octave_cycles(Octaves, NoiseUnits, NoiseSteps, pst_pkg::DatapathSerial,
                                                 NoiseRegs, OctaveRegs);
  // The serial quadric needs up to StepMax cycles: a fragment with fewer octave cycles waits
  // for it, so the counter reaches StepMax there.
  localparam int CycMax   = (Cycles < pst_pkg::StepMax + 1) ? pst_pkg::StepMax + 1 : Cycles;
  localparam int CycBits  = (CycMax > 1) ? $clog2(CycMax) : 1;
  localparam bit Bl       = (FilterBandlimit == pst_pkg::FilterBandlimitIsotropic);
  localparam int LgW      = pst_pkg::fade_lg_width(JW);

  typedef struct packed {
    logic                noise_on;   // a noise evaluation runs a step
    logic [PassBits-1:0] npass;
    logic [2:0]          nstep;
    logic                xf_on;      // a transform row is computed
    logic [PassBits-1:0] xpass;
    logic [1:0]          xrow;
    logic                tm_on;      // a term row is computed
    logic [PassBits-1:0] tpass;
    logic [1:0]          trow;
  } sched_t;

  logic [CycBits-1:0] cyc_q, cyc_d;
  logic               quad_done;   // the quadric's result is at q_o
  logic               last_cycle;  // the fragment's last cycle in the octave stage
  logic               advance;     // the fragment moves to its next cycle at this edge
  logic               en;          // advance, or the fragment leaves
  sched_t             sch, sch_next;
  pst_octave_sched #(.Passes(Passes), `PST_NOISE_SCHED_PASS, .CycBits(CycBits)) u_sched (
    .clk_i, .rst_ni, .cyc_next_i (cyc_d), .sch_o (sch), .next_o (sch_next));

  assign last_cycle = (32'(cyc_q) + 1 >= Cycles) && quad_done;
  pst_pipe_flow #(.Depth(0), .SideW(SideW)) u_flow (
    .clk_i, .rst_ni, .valid_i, .done_i (last_cycle), .ready_o, .side_i, .valid_o, .ready_i, .side_o,
    .adv_o (advance), .move_o (en), .busy_o);
  pst_step_counter #(.Width(CycBits)) u_cyc (
    .clk_i, .rst_ni, .valid_i, .done_i (last_cycle), .ready_i, .step_o (cyc_q), .step_next_o (cyc_d));

  // Quadric: one multiplier stepped by the cycle count, its result complete by the last cycle,
  // where it is added; with MR it passes a register too, so the last cycle comes one cycle
  // after the quadric's last step at the earliest.
  logic [SB-1:0]   qstep, qstep_d;   // this cycle's step, the next cycle's
  logic            qdone;
  logic [FW-1:0]   q_s;
  logic [3*GW-1:0] gradq_s;
  assign qstep   = (32'(cyc_q) < pst_pkg::StepMax) ? SB'(cyc_q) : SB'(pst_pkg::StepMax);
  assign qstep_d = (32'(cyc_d) < pst_pkg::StepMax) ? SB'(cyc_d) : SB'(pst_pkg::StepMax);
  pst_quadric_serial #(`PST_QUADRIC_PASS, .Regs(MR)) u_quadric (
    .clk_i, .rst_ni, .step_i (qstep), .step_next_i (qstep_d), .adv_i (advance), .done_o (qdone),
    .s_i (s_i), .coef_i (quad_i), .q_o (q_s), .gradq_o (gradq_s)
  );
  pst_delay #(.Width(1 + FW + 3*GW), .Depth(MR)) u_q_reg (
    .clk_i, .rst_ni, .en_i (en), .d_i ({qdone, gradq_s, q_s}), .q_o ({quad_done, gradq_o, q_o}));

  assign nz_en_o    = en;
  assign nz_valid_o = sch.noise_on;
  assign nz_step_o  = sch.nstep;

  // The pixel's lg edge lengths for the fades (registered, free-running).
  logic [LgW-1:0] lgx, lgy;
  if (Bl) begin : g_fade_px
    pst_fade_pixel #(`PST_JACOBIAN_PASS, .LenRegs(1), .LgRegs(1)) u_px (
      .clk_i, .rst_ni, .en_i (1'b1), .j_i (side_i[TB +: 6*JW]), .lgx_o (lgx), .lgy_o (lgy));
  end else begin : g_no_fade
    assign lgx = '0;
    assign lgy = '0;
  end

  // The subband unit's filter (noise.subband_orientations K = 4, 8): the pixel's lg edges along
  // the K orientations (pst_subband_pixel, registered like the fade's, free-running), per lane the
  // weights of the next cycle's noise pass from its lg ||M|| and the fade table (pst_octave_fade
  // per orientation), registered as the fragment moves on: the first noise step (cycle SR = 3)
  // finds them (the pixel's lg are registered from cycle 2). The table is then the weights', not
  // a fade of the term.
  localparam int SK = NoiseSubbandOrientations;
  localparam bit Aniso = (NoiseSubband != pst_pkg::NoiseSubbandNone) && (SK != 0);
  logic [2*(Aniso ? SK : 1)*LgW-1:0] sb_lg;
  if (Aniso) begin : g_sb_px
    pst_subband_pixel #(`PST_JACOBIAN_PASS, .NoiseSubband(NoiseSubband), .K(SK), .LenRegs(1), .LgRegs(1)
    ) u_sb_px (
      .clk_i, .rst_ni, .en_i (1'b1), .j_i (side_i[TB +: 6*JW]), .lg_o (sb_lg));
  end else begin : g_no_sb_px
    assign sb_lg = '0;
    logic unused_sb_lg;
    assign unused_sb_lg = ^sb_lg;
  end
  logic bl_term;   // the term's fade: not on a subband unit with its filter
  assign bl_term = bl_i & ~Aniso;

  // The pass of the noise units' output (the probes name it).
  logic [PassBits-1:0] pass_n;
  if (DebugProbes) begin : g_probe_pass
    pst_delay #(.Width(PassBits), .Depth(NR)) u_pass_n (
      .clk_i, .rst_ni, .en_i (en), .d_i (sch.npass), .q_o (pass_n));
  end else begin : g_no_probe_pass
    assign pass_n = '0;
  end

  for (genvar u = 0; u < NoiseUnits; u++) begin : g_lane
    // Register reads for the next cycle (its schedule, sch_next), registered like the
    // schedule: row xrow of M and o of the transform's octave, row trow of GM and a, lg ||M||
    // of the term's.
    logic [3*MW-1:0]  m_row, m_row_d;
    logic [OW-1:0]    o_row, o_row_d;
    logic [3*GMW-1:0] gm_row, gm_row_d;
    logic [AW-1:0]    a_t, a_t_d;
    logic [FW-1:0]    fm_t, fm_t_d;
    logic [LMW-1:0]   lgm_t_d;
    // The noise pass of the next cycle from this cycle's (registered) schedule, so that the
    // weights' path does not start at the stall: the pass after this one at a pass's last step,
    // else this one (pass 0 before the first step).
    logic [PassBits-1:0] lam_pass;
    assign lam_pass = !sch.noise_on ? '0 : (32'(sch.nstep) == NoiseSteps - 1) ? sch.npass + 1'b1 : sch.npass;
    logic [LMW-1:0]   lgm_n_d;    // that pass's lg ||M|| (the subband filter)
    always_comb begin
      lgm_n_d = '0;
      for (int p = 0; p < Passes; p++) begin
        if (32'(lam_pass) == p) lgm_n_d = oct_lgm_i[(p * NoiseUnits + u)*LMW +: LMW];
      end
    end
    if (Aniso) begin : g_sb_lam
      logic [SLW-1:0] lam_d, lam_q;
      for (genvar i = 0; i < SK; i++) begin : g_dir
        pst_octave_fade #(.LgW(LgW)) u_lam (
          .en_i (bl_i), .lgx_i (sb_lg[i*LgW +: LgW]), .lgy_i (sb_lg[(SK + i)*LgW +: LgW]), .lgm_i (lgm_n_d),
          .table_i (fade_i), .alpha_o (lam_d[i*FB +: FB]));
      end
      // Loaded as the fragment moves on (en), so it holds the next cycle's pass's weights.
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) lam_q <= '0;
        else if (en) lam_q <= lam_d;
      end
      assign nz_lam_o[u*SLW +: SLW] = lam_q;
    end else begin : g_no_sb_lam
      for (genvar i = 0; i < SLW / FB; i++) begin : g_one
        assign nz_lam_o[u*SLW + i*FB +: FB] = FB'(1 << pst_pkg::FadeFrac);
      end
      logic unused_lgm_n;
      assign unused_lgm_n = ^lgm_n_d;
    end
    always_comb begin
      m_row_d  = '0;
      o_row_d  = '0;
      gm_row_d = '0;
      a_t_d    = '0;
      fm_t_d   = '0;
      lgm_t_d  = '0;
      for (int p = 0; p < Passes; p++) begin
        for (int r = 0; r < SR; r++) begin
          if (32'(sch_next.xpass) == p && 32'(sch_next.xrow) == r) begin
            m_row_d = oct_m_i[((p * NoiseUnits + u)*9 + 3*r)*MW +: 3*MW];
            o_row_d = oct_o_i[((p * NoiseUnits + u)*3 + r)*OW +: OW];
          end
          if (32'(sch_next.tpass) == p && 32'(sch_next.trow) == r) begin
            gm_row_d = oct_gm_i[((p * NoiseUnits + u)*9 + 3*r)*GMW +: 3*GMW];
          end
        end
        if (32'(sch_next.tpass) == p) begin
          a_t_d   = oct_a_i[(p * NoiseUnits + u)*AW +: AW];
          fm_t_d  = oct_fm_i[(p * NoiseUnits + u)*FW +: FW];
          lgm_t_d = oct_lgm_i[(p * NoiseUnits + u)*LMW +: LMW];
        end
      end
    end
    always_ff @(posedge clk_i) begin
      m_row  <= m_row_d;
      o_row  <= o_row_d;
      gm_row <= gm_row_d;
      a_t    <= a_t_d;
      fm_t   <= fm_t_d;
    end

    logic [LB-1:0]    lat_r;      // the transform's row xrow: lattice index and fraction
    logic [LF-1:0]    frac_r;
    logic [NW-1:0]    n_q;        // the noise result, waiting for its term rows
    logic [3*NGW-1:0] g_q;
    logic [FB-1:0]    alpha_d, alpha_t;
    logic [FW-1:0]    fterm_raw, fterm_d;
    logic [GW-1:0]    gterm_raw;
    logic [3*GW-1:0]  gterm_d;
    pst_octave_lane #(.Rows(1), .LgW(LgW), `PST_LANE_PASS
    ) u_lane (
      .clk_i, .rst_ni, .en_i (1'b1),   // (no register inside: TransformRegs = 0)
      .s_i (s_i), .m_i (m_row), .o_i (o_row), .lat_o (lat_r), .frac_o (frac_r),
      .bl_i (bl_term), .lgx_i (lgx), .lgy_i (lgy), .lgm_i (lgm_t_d), .fade_i (fade_i), .alpha_o (alpha_d),
      .n_i (n_q), .g_i (g_q), .a_i (a_t), .gm_i (gm_row), .alpha_i (alpha_t), .fm_i (fm_t), .fterm_o (fterm_raw),
      .gterm_o (gterm_raw)
    );
    // The term pass's fade, registered with its operands.
    if (Bl) begin : g_fade
      always_ff @(posedge clk_i) alpha_t <= alpha_d;
    end else begin : g_whole
      assign alpha_t = alpha_d;
    end

    // Rows 0, 1 wait in nxt; at row 2 the noise unit's input (cur) is loaded whole.
    logic [2*LB-1:0] nxt_lat_q;
    logic [2*LF-1:0] nxt_frac_q;
    logic [LTW-1:0]  cur_lat_q;
    logic [3*LF-1:0] cur_frac_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        nxt_lat_q  <= '0;
        nxt_frac_q <= '0;
        cur_lat_q  <= '0;
        cur_frac_q <= '0;
      end else if (advance && sch.xf_on) begin
        if (sch.xrow == 2'd2) begin
          cur_lat_q  <= {lat_r, nxt_lat_q};
          cur_frac_q <= {frac_r, nxt_frac_q};
        end else begin
          nxt_lat_q[sch.xrow*LB +: LB]  <= lat_r;
          nxt_frac_q[sch.xrow*LF +: LF] <= frac_r;
        end
      end
    end
    assign nz_lat_o[u*LTW +: LTW]    = cur_lat_q;
    assign nz_frac_o[u*3*LF +: 3*LF] = cur_frac_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        n_q <= '0;
        g_q <= '0;
      end else if (en && nz_last_i[u]) begin
        n_q <= nz_n_i[u*NW +: NW];
        g_q <= nz_g_i[u*3*NGW +: 3*NGW];
      end
    end

    // The term row: a n (at row 0) and row trow of a M^T g, zero unless the lane's octave is
    // active; the term register (MR) is loaded on every move of the fragment, so it holds
    // zero when the next fragment starts.
    logic [OctBits:0] t_oct;
    logic             lane_on;
    assign t_oct   = (OctBits + 1)'(sch.tpass) * (OctBits + 1)'(NoiseUnits) + (OctBits + 1)'(u);
    assign lane_on = sch.tm_on && (t_oct < {1'b0, active_i});
    assign fterm_d = (lane_on && sch.trow == 2'd0) ? fterm_raw : '0;
    for (genvar k = 0; k < 3; k++) begin : g_gterm
      assign gterm_d[k*GW +: GW] = (lane_on && 32'(sch.trow) == k) ? gterm_raw : '0;
    end
    pst_delay #(.Width(FW + 3*GW), .Depth(MR)) u_m (
      .clk_i, .rst_ni, .en_i (en), .d_i ({gterm_d, fterm_d}),
      .q_o ({gterm_o[u*3*GW +: 3*GW], fterm_o[u*FW +: FW]}));
  end

  assign acc_en_o    = advance;
  assign acc_first_o = (cyc_q == '0);

  assign pr_valid_o  = DebugProbes & valid_i & nz_last_i[0];
  assign pr_pass_o   = PPB'(pass_n);
  assign pr_tag_o    = DebugProbes ? side_i[TB-1:0] : '0;
  assign pr_q_tag_o  = DebugProbes ? side_i[TB-1:0] : '0;
  logic unused;
  assign unused = ^{sch.xpass, sch_next.noise_on, sch_next.npass, sch_next.nstep, sch_next.xf_on,
                    sch_next.tm_on};

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (OctaveRegs < 0 || OctaveRegs > 2) $error("pst_octave_serial: OctaveRegs must be 0..2");
    if (Bl && SideW < TB + 6*JW) $error("pst_octave_serial: SideW must hold the Jacobian above the tag");
  end
  assert property (@(posedge clk_i) disable iff (!rst_ni) 32'(cyc_q) < CycMax);
`endif

endmodule

`default_nettype wire

// pst_octave_stage: the octave stage of pst_top (docs/HARDWARE.md stages 1-4): the quadric
// and NoiseUnits octave lanes (octave transform, noise, octave term) over Passes =
// Octaves / NoiseUnits passes, their terms accumulated and saturated to f and grad f.
// A fragment (valid_i, s_i) stays Cycles cycles, counted by cyc_q; valid_o/ready_o hand it on
// at its last cycle (valid_o = valid_i at the last cycle; ready_o = that cycle's ready_i).
//
// Parameters: the profile's (pst_top's header); Datapath selects the schedule below.
// Registers (pst_regs, flat): quad_i A..J; oct_*_i octave i's M, o, a, GM at block i.
`include "pst_pkg.sv"
`default_nettype none

module pst_octave_stage #(
  parameter int Octaves          = pst_pkg::OctavesDefault,
  parameter int NoiseUnits       = pst_pkg::NoiseUnitsDefault,
  parameter int Datapath         = pst_pkg::DatapathDefault,
  parameter int NoiseInterp      = pst_pkg::NoiseInterpDefault,
  parameter int NoiseCorner      = pst_pkg::NoiseCornerDefault,
  parameter int NoiseHash        = pst_pkg::NoiseHashDefault,
  parameter int NoiseValueFrac   = pst_pkg::NoiseValueFracDefault,
  parameter int NoiseLatticeFrac = pst_pkg::NoiseLatticeFracDefault,
  parameter int NoiseOutFrac     = pst_pkg::NoiseOutFracDefault,
  parameter int NoiseSteps       = pst_pkg::NoiseStepsDefault,
  parameter int NoiseGuardBits   = pst_pkg::NoiseGuardBitsDefault,
  parameter int CoordInt         = pst_pkg::CoordIntDefault,
  parameter int CoordFrac        = pst_pkg::CoordFracDefault,
  parameter int MatrixInt        = pst_pkg::MatrixIntDefault,
  parameter int MatrixFrac       = pst_pkg::MatrixFracDefault,
  parameter int OffsetInt        = pst_pkg::OffsetIntDefault,
  parameter int OffsetFrac       = pst_pkg::OffsetFracDefault,
  parameter int AmplitudeInt     = pst_pkg::AmplitudeIntDefault,
  parameter int AmplitudeFrac    = pst_pkg::AmplitudeFracDefault,
  parameter int GradMatrixInt    = pst_pkg::GradMatrixIntDefault,
  parameter int GradMatrixFrac   = pst_pkg::GradMatrixFracDefault,
  parameter int QuadricInt       = pst_pkg::QuadricIntDefault,
  parameter int QuadricFrac      = pst_pkg::QuadricFracDefault,
  parameter int FInt             = pst_pkg::FIntDefault,
  parameter int FFrac            = pst_pkg::FFracDefault,
  parameter int GradInt          = pst_pkg::GradIntDefault,
  parameter int GradFrac         = pst_pkg::GradFracDefault,
  parameter bit DebugProbes      = 1'b1,
  localparam int CW  = CoordInt + CoordFrac,
  localparam int MW  = MatrixInt + MatrixFrac,
  localparam int OW  = OffsetInt + OffsetFrac,
  localparam int AW  = AmplitudeInt + AmplitudeFrac,
  localparam int GMW = GradMatrixInt + GradMatrixFrac,
  localparam int QW  = QuadricInt + QuadricFrac,
  localparam int FW  = FInt + FFrac,
  localparam int GW  = GradInt + GradFrac,
  localparam int LF  = NoiseLatticeFrac,
  localparam int NW  = pst_pkg::NoiseIntBits + NoiseOutFrac,      // noise value
  localparam int NGW = pst_pkg::NoiseGradIntBits + NoiseOutFrac,  // one noise gradient component
  localparam int LTW = pst_pkg::LatticeWidth,                     // one lane's lattice index
  localparam int PPB = pst_pkg::ProbePassBits,
  localparam int OctBits = $clog2(Octaves + 1)                    // active octave count
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  // The fragment in [A] and its hand-over to [B]
  input  logic                      valid_i,
  output logic                      ready_o,
  input  logic [3*CW-1:0]           s_i,
  output logic                      valid_o,
  input  logic                      ready_i,
  output logic [FW-1:0]             f_o,
  output logic [3*GW-1:0]           grad_o,
  // Registers
  input  logic [OctBits-1:0]        active_i,
  input  logic [10*QW-1:0]          quad_i,
  input  logic [Octaves*9*MW-1:0]   oct_m_i,
  input  logic [Octaves*3*OW-1:0]   oct_o_i,
  input  logic [Octaves*AW-1:0]     oct_a_i,
  input  logic [Octaves*9*GMW-1:0]  oct_gm_i,
  // Debug probes (pst_top's; zero when DebugProbes = 0)
  output logic                      probe_valid_o,
  output logic [PPB-1:0]            probe_pass_o,
  output logic                      probe_q_valid_o,
  output logic [FW-1:0]             probe_q_o,
  output logic [NoiseUnits*LTW-1:0] probe_lat_o,
  output logic [NoiseUnits*3*LF-1:0]  probe_frac_o,
  output logic [NoiseUnits*NW-1:0]    probe_n_o,
  output logic [NoiseUnits*3*NGW-1:0] probe_g_o
);

  localparam bit Serial    = (Datapath == pst_pkg::DatapathSerial);
  localparam int SR        = pst_pkg::SerialRows;    // serial: transform / term rows
  localparam int SB        = pst_pkg::StepBits;      // the serial quadric's step
  localparam int LB        = pst_pkg::LatticeBits;   // one lattice index
  localparam int Passes    = Octaves / NoiseUnits;   // octave passes per fragment
  localparam int PassBits  = (Passes > 1) ? $clog2(Passes) : 1;
  // Cycles per fragment: NoiseSteps cycles per pass (one noise evaluation per lane per pass),
  // plus, for the serial datapath, the first pass's transform rows and the last pass's term
  // rows (pst_pkg::SerialOctaveExtraCycles).
  localparam int Cycles    = Passes * NoiseSteps + (Serial ? pst_pkg::SerialOctaveExtraCycles : 0);
  // The serial quadric needs up to StepMax cycles (pst_quadric_serial's NSteps): a fragment
  // with fewer octave cycles waits for it, so the counter reaches StepMax there.
  localparam int CycMax    = (Serial && Cycles < pst_pkg::StepMax + 1) ? pst_pkg::StepMax + 1 : Cycles;
  localparam int CycBits   = (CycMax > 1) ? $clog2(CycMax) : 1;
  // Guard bits: the accumulators add q and up to Octaves terms without overflow.
  localparam int AccGuard  = $clog2(Octaves + 1) + 1;
  localparam int FAccW     = FW + AccGuard;
  localparam int GAccW     = GW + AccGuard;

  // The fragment in [A] stays Cycles cycles; cyc_q counts them. Schedule of a lane:
  //   parallel: pass p, noise step j at cycle p NoiseSteps + j; the octave transform and
  //             the octave term are combinational around the noise unit.
  //   serial:   one row of M_i s + o_i and of a_i M_i^T g per cycle (3 + 3 multipliers
  //             instead of 9 + 9), software-pipelined around the noise unit (SR = 3 rows):
  //               transform of pass p, row r   cycle p NoiseSteps + r         (r < SR)
  //               noise of pass p, step j      cycle SR + p NoiseSteps + j
  //               term of pass p, row r        cycle SR + (p + 1) NoiseSteps + r
  //             so Cycles = Passes NoiseSteps + 2 SR (NoiseSteps >= 4 keeps the three apart:
  //             rows 0, 1 wait in a buffer while the previous pass's noise runs, row 2
  //             completes the noise unit's input at its last step).
  logic [CycBits-1:0]  cyc_q, cyc_d;
  logic                advance;     // the fragment moves to its next cycle at this edge
  logic                last_cycle;  // the fragment's last cycle in the octave stage
  logic                noise_on;    // a noise evaluation runs this cycle
  logic [PassBits-1:0] npass;       // its pass
  logic [2:0]          nstep;       // its step
  logic                nlast;       // its last step: n and g are valid
  logic                xf_on;       // serial: a transform row is computed this cycle
  logic [PassBits-1:0] xpass;
  logic [1:0]          xrow;
  logic                tm_on;       // serial: a term row is computed this cycle
  logic [PassBits-1:0] tpass;
  logic [1:0]          trow;

  logic quad_done;   // the quadric's result is valid (always, when parallel)
  assign last_cycle = (32'(cyc_q) + 1 >= Cycles) && quad_done;
  assign advance    = valid_i & ~last_cycle;

  always_comb begin
    int c, cn;
    c  = 32'(cyc_q);
    cn = c - SR;
    if (!Serial) begin
      noise_on = 1'b1;
      npass    = PassBits'(c / NoiseSteps);
      nstep    = 3'(c % NoiseSteps);
      xf_on    = 1'b0;
      xpass    = '0;
      xrow     = '0;
      tm_on    = 1'b0;
      tpass    = '0;
      trow     = '0;
    end else begin
      noise_on = (c >= SR) && (c < SR + Passes * NoiseSteps);
      npass    = noise_on ? PassBits'(cn / NoiseSteps) : '0;
      nstep    = noise_on ? 3'(cn % NoiseSteps) : '0;
      xf_on    = (c < Passes * NoiseSteps) && (c % NoiseSteps < SR);
      xpass    = PassBits'(c / NoiseSteps);
      xrow     = 2'(c % NoiseSteps);
      tm_on    = (c >= SR + NoiseSteps) && (c < SR + (Passes + 1) * NoiseSteps) &&
                 (cn % NoiseSteps < SR);
      tpass    = tm_on ? PassBits'(cn / NoiseSteps - 1) : '0;
      trow     = tm_on ? 2'(cn % NoiseSteps) : '0;
    end
  end
  assign nlast = noise_on && (32'(nstep) == NoiseSteps - 1);
  if (!Serial) begin : g_unused_sched
    logic unused_sched;   // the serial schedule's signals (constant here)
    assign unused_sched = ^{xf_on, xpass, xrow, tm_on, tpass, trow};
  end

  logic signed [FAccW-1:0] facc_q, facc_d;
  logic [3*GAccW-1:0]      gacc_q, gacc_d;

  logic [FW-1:0]   q;
  logic [3*GW-1:0] gradq;

  // parallel: the whole quadric every cycle; serial: one multiplier stepped by the cycle count
  // (pst_quadric_serial), its result complete by the last cycle, where it is added.
  if (!Serial) begin : g_quadric_par
    pst_quadric #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
    ) u_quadric (
      .s_i (s_i), .coef_i (quad_i), .q_o (q), .gradq_o (gradq)
    );
    assign quad_done = 1'b1;
  end else begin : g_quadric_ser
    logic [SB-1:0] qstep;
    logic          qdone;
    assign qstep = (32'(cyc_q) < pst_pkg::StepMax) ? SB'(cyc_q) : SB'(pst_pkg::StepMax);
    pst_quadric_serial #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
    ) u_quadric (
      .clk_i, .rst_ni,
      .step_i (qstep), .adv_i (advance), .done_o (qdone),
      .s_i (s_i), .coef_i (quad_i), .q_o (q), .gradq_o (gradq)
    );
    assign quad_done = qdone;
  end

  // Per lane, this cycle's contribution to the sums (zero when it has none).
  logic [FW-1:0]   fterm [NoiseUnits];
  logic [3*GW-1:0] gterm [NoiseUnits];

  for (genvar u = 0; u < NoiseUnits; u++) begin : g_lane
    logic [LTW-1:0]   lat;    // the noise unit's input
    logic [3*LF-1:0]  frac;
    logic [NW-1:0]    n;      // its output (valid at nlast)
    logic [3*NGW-1:0] g;

    if (!Serial) begin : g_par
      // Octave index of this lane in this pass.
      logic [OctBits:0] oct_idx;
      logic             lane_on;
      logic [FW-1:0]    fterm_raw;
      logic [3*GW-1:0]  gterm_raw;

      if (Passes > 1) begin : g_shared
        assign oct_idx = (OctBits + 1)'(npass) * (OctBits + 1)'(NoiseUnits) + (OctBits + 1)'(u);
      end else begin : g_parallel
        assign oct_idx = (OctBits + 1)'(u);
      end
      assign lane_on = oct_idx < {1'b0, active_i};

      // The register arrays are indexed by the octave of this pass (a constant when Passes = 1).
      logic [9*MW-1:0]  m_sel;
      logic [3*OW-1:0]  o_sel;
      logic [AW-1:0]    a_sel;
      logic [9*GMW-1:0] gm_sel;
      always_comb begin
        m_sel  = oct_m_i[u*9*MW +: 9*MW];
        o_sel  = oct_o_i[u*3*OW +: 3*OW];
        a_sel  = oct_a_i[u*AW +: AW];
        gm_sel = oct_gm_i[u*9*GMW +: 9*GMW];
        for (int p = 1; p < Passes; p++) begin
          if (32'(npass) == p) begin
            m_sel  = oct_m_i[(p * NoiseUnits + u)*9*MW +: 9*MW];
            o_sel  = oct_o_i[(p * NoiseUnits + u)*3*OW +: 3*OW];
            a_sel  = oct_a_i[(p * NoiseUnits + u)*AW +: AW];
            gm_sel = oct_gm_i[(p * NoiseUnits + u)*9*GMW +: 9*GMW];
          end
        end
      end

      pst_octave_transform #(
        .CoordInt(CoordInt), .CoordFrac(CoordFrac), .MatrixInt(MatrixInt), .MatrixFrac(MatrixFrac),
        .OffsetInt(OffsetInt), .OffsetFrac(OffsetFrac), .NoiseLatticeFrac(NoiseLatticeFrac)
      ) u_transform (
        .s_i (s_i), .m_i (m_sel), .o_i (o_sel), .lat_o (lat), .frac_o (frac)
      );

      pst_octave_term #(
        .NoiseOutFrac(NoiseOutFrac), .AmplitudeInt(AmplitudeInt), .AmplitudeFrac(AmplitudeFrac),
        .GradMatrixInt(GradMatrixInt), .GradMatrixFrac(GradMatrixFrac), .FInt(FInt),
        .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
      ) u_term (
        .n_i (n), .g_i (g), .a_i (a_sel), .gm_i (gm_sel), .fterm_o (fterm_raw), .gterm_o (gterm_raw)
      );

      assign fterm[u] = (lane_on && nlast) ? fterm_raw : '0;
      assign gterm[u] = (lane_on && nlast) ? gterm_raw : '0;
    end else begin : g_ser
      // Octave of this lane's term rows (lane_on: an active octave).
      logic [OctBits:0] t_oct;
      assign t_oct = (OctBits + 1)'(tpass) * (OctBits + 1)'(NoiseUnits) + (OctBits + 1)'(u);

      // Register reads: row xrow of M and o of octave x_oct; row trow of GM and a of t_oct.
      logic [3*MW-1:0]  m_row;
      logic [OW-1:0]    o_row;
      logic [3*GMW-1:0] gm_row;
      logic [AW-1:0]    a_t;
      always_comb begin
        m_row  = '0;
        o_row  = '0;
        gm_row = '0;
        a_t    = '0;
        for (int p = 0; p < Passes; p++) begin
          for (int r = 0; r < SR; r++) begin
            if (32'(xpass) == p && 32'(xrow) == r) begin
              m_row = oct_m_i[((p * NoiseUnits + u)*9 + 3*r)*MW +: 3*MW];
              o_row = oct_o_i[((p * NoiseUnits + u)*3 + r)*OW +: OW];
            end
            if (32'(tpass) == p && 32'(trow) == r) begin
              gm_row = oct_gm_i[((p * NoiseUnits + u)*9 + 3*r)*GMW +: 3*GMW];
            end
          end
          if (32'(tpass) == p) a_t = oct_a_i[(p * NoiseUnits + u)*AW +: AW];
        end
      end

      // Transform, one row: lattice index and fraction of axis xrow.
      logic [LB-1:0]    lat_r;
      logic [LF-1:0]    frac_r;
      pst_octave_transform #(
        .CoordInt(CoordInt), .CoordFrac(CoordFrac), .MatrixInt(MatrixInt), .MatrixFrac(MatrixFrac),
        .OffsetInt(OffsetInt), .OffsetFrac(OffsetFrac), .NoiseLatticeFrac(NoiseLatticeFrac),
        .Rows(1)
      ) u_transform (
        .s_i (s_i), .m_i (m_row), .o_i (o_row), .lat_o (lat_r), .frac_o (frac_r)
      );

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
        end else if (advance && xf_on) begin
          if (xrow == 2'd2) begin
            cur_lat_q  <= {lat_r, nxt_lat_q};
            cur_frac_q <= {frac_r, nxt_frac_q};
          end else begin
            nxt_lat_q[xrow*LB +: LB]  <= lat_r;
            nxt_frac_q[xrow*LF +: LF] <= frac_r;
          end
        end
      end
      assign lat  = cur_lat_q;
      assign frac = cur_frac_q;

      // The noise result waits for the term rows of the next NoiseSteps cycles.
      logic [NW-1:0]    n_q;
      logic [3*NGW-1:0] g_q;
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          n_q <= '0;
          g_q <= '0;
        end else if (advance && nlast) begin
          n_q <= n;
          g_q <= g;
        end
      end

      // Term, one row: a n (used at row 0) and row trow of a M^T g.
      logic [FW-1:0] fterm_raw;
      logic [GW-1:0] gterm_raw;
      logic          lane_on;
      pst_octave_term #(
        .NoiseOutFrac(NoiseOutFrac), .AmplitudeInt(AmplitudeInt), .AmplitudeFrac(AmplitudeFrac),
        .GradMatrixInt(GradMatrixInt), .GradMatrixFrac(GradMatrixFrac), .FInt(FInt),
        .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac), .Rows(1)
      ) u_term (
        .n_i (n_q), .g_i (g_q), .a_i (a_t), .gm_i (gm_row), .fterm_o (fterm_raw), .gterm_o (gterm_raw)
      );
      assign lane_on  = tm_on && (t_oct < {1'b0, active_i});
      assign fterm[u] = (lane_on && trow == 2'd0) ? fterm_raw : '0;
      for (genvar k = 0; k < 3; k++) begin : g_gterm
        assign gterm[u][k*GW +: GW] = (lane_on && 32'(trow) == k) ? gterm_raw : '0;
      end
    end

    pst_noise #(
      .NoiseInterp(NoiseInterp), .NoiseCorner(NoiseCorner), .NoiseHash(NoiseHash),
      .NoiseValueFrac(NoiseValueFrac), .NoiseLatticeFrac(NoiseLatticeFrac),
      .NoiseOutFrac(NoiseOutFrac), .NoiseSteps(NoiseSteps), .NoiseGuardBits(NoiseGuardBits)
    ) u_noise (
      .clk_i, .rst_ni, .step_i (nstep), .adv_i (advance & noise_on & ~nlast),
      .lat_i (lat), .frac_i (frac), .n_o (n), .grad_o (g)
    );

    if (DebugProbes) begin : g_probe
      assign probe_lat_o[u*LTW +: LTW]        = lat;
      assign probe_frac_o[u*3*LF +: 3*LF]     = frac;
      assign probe_n_o[u*NW +: NW]            = n;
      assign probe_g_o[u*3*NGW +: 3*NGW]      = g;
    end else begin : g_no_probe
      assign probe_lat_o[u*LTW +: LTW]        = '0;
      assign probe_frac_o[u*3*LF +: 3*LF]     = '0;
      assign probe_n_o[u*NW +: NW]            = '0;
      assign probe_g_o[u*3*NGW +: 3*NGW]      = '0;
    end
  end

  // Probes: the noise results of a pass, at its last step; q at the fragment's last cycle
  // (the serial quadric may finish after the last noise step).
  assign probe_valid_o = DebugProbes & valid_i & nlast;
  assign probe_pass_o  = DebugProbes ? PPB'(npass) : '0;
  assign probe_q_valid_o = DebugProbes & valid_i & last_cycle;
  assign probe_q_o     = DebugProbes ? q : '0;

  // Accumulation: every cycle adds the lanes' contributions (cycle 0 starts from zero); the
  // last cycle adds q (where the serial quadric has its result) and saturates. The sums are
  // exact, so the order of the terms does not change a bit.
  logic signed [FAccW-1:0] fsum, fout;
  logic [3*GAccW-1:0]      gsum, gout;

  always_comb begin
    logic signed [GAccW-1:0] gc;
    fsum = (cyc_q == '0) ? '0 : facc_q;
    for (int u = 0; u < NoiseUnits; u++) fsum = fsum + FAccW'($signed(fterm[u]));
    fout = fsum + FAccW'($signed(q));
    for (int k = 0; k < 3; k++) begin
      gc = (cyc_q == '0) ? '0 : $signed(gacc_q[k*GAccW +: GAccW]);
      for (int u = 0; u < NoiseUnits; u++) gc = gc + GAccW'($signed(gterm[u][k*GW +: GW]));
      gsum[k*GAccW +: GAccW] = gc;
      gout[k*GAccW +: GAccW] = gc + GAccW'($signed(gradq[k*GW +: GW]));
    end
  end

  // Saturate to the F and Grad formats (the sums are already at their fraction bits).
  pst_floor_sat #(.InWidth (FAccW), .InFrac (FFrac), .OutWidth (FW), .OutFrac (FFrac)) u_f_sat (
    .x_i (fout), .y_o (f_o)
  );
  for (genvar k = 0; k < 3; k++) begin : g_grad_sat
    pst_floor_sat #(.InWidth (GAccW), .InFrac (GradFrac), .OutWidth (GW), .OutFrac (GradFrac)) u_sat (
      .x_i (gout[k*GAccW +: GAccW]), .y_o (grad_o[k*GW +: GW])
    );
  end

  // The fragment leaves at its last cycle, when the next stage takes it.
  assign valid_o = valid_i & last_cycle;
  assign ready_o = last_cycle & ready_i;

  always_comb begin
    cyc_d  = cyc_q;
    facc_d = facc_q;
    gacc_d = gacc_q;
    if (advance) begin
      cyc_d  = cyc_q + 1'b1;
      facc_d = fsum;
      gacc_d = gsum;
    end else if (valid_i && ready_i) begin
      cyc_d = '0;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cyc_q  <= '0;
      facc_q <= '0;
      gacc_q <= '0;
    end else begin
      cyc_q  <= cyc_d;
      facc_q <= facc_d;
      gacc_q <= gacc_d;
    end
  end


  // Assertions
`ifndef SYNTHESIS
  // The cycle counter stays within the fragment's cycles.
  assert property (@(posedge clk_i) disable iff (!rst_ni) 32'(cyc_q) < CycMax);
`endif

endmodule

`default_nettype wire

// pst_octave_stage: the octave stage of pst_top (docs/HARDWARE.md stages 1-4): the quadric
// and NoiseUnits octave lanes (octave transform, noise, octave term) over Passes =
// Octaves / NoiseUnits passes, their terms accumulated and saturated to f and grad f.
// A fragment (valid_i, s_i, side_i) stays Cycles cycles in [A], counted by cyc_q.
//
// Pipeline registers (profile keys pipeline.noise_regs = NoiseRegs inside each noise unit,
// pipeline.octave_regs = OctaveRegs around it: 1 after the octave term, 2 also after the
// octave transform, parallel datapath only):
//   parallel: a pipeline of Lat = NoiseRegs + OctaveRegs registers. Each cycle of a fragment in
//             [A] issues a beat (its pass, step, first / last flags) into the pipeline, which
//             carries side_i (the tag and Jacobian) beside it; [A] is released at the last
//             beat's issue, so a pixel per clock stays a pixel per clock, Lat cycles later. The
//             accumulators sit at the end; the last beat offers f, grad to [B] (valid_o) and
//             the whole pipeline stalls while [B] refuses it (en).
//   serial:   the fragment stays in [A] (the serial schedule below) and the noise unit's
//             registers and the term register lengthen its schedule: Cycles grows by
//             NoiseRegs + (OctaveRegs >= 1).
// busy_o: a beat is inside the pipeline's registers (pst_top's idle_o).
//
// Bandlimited octaves (FilterBandlimit = isotropic): the pixel's two edges' lengths and their lg
// (pst_fade_norm, pst_fade_lg, from the Jacobian in side_i, once per fragment) and per lane the
// octave's fade alpha (pst_octave_fade), which the octave term multiplies in. Parallel: the
// chain spread over the beat's registers between issue and term (a register after the
// lengths, one after the lg, the fade's delayed beside the noise unit); serial: lengths and lg
// registered, the fade registered with the term rows' operands.
//
// Parameters: the profile's (pst_top's header); Datapath selects the schedule below.
// Registers (pst_regs, flat): quad_i A..J; oct_*_i octave i's M, o, a, GM, lg ||M|| at block i;
// bl_i, fade_i: control.bandlimit and the fade table.
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
  parameter int NoiseGradFrac    = pst_pkg::NoiseGradFracDefault,  // lattice units only
  parameter int NoiseWorleySearch = pst_pkg::NoiseWorleySearchDefault,  // not none: worley units
  parameter int NoiseWorleyPoints = pst_pkg::NoiseWorleyPointsDefault,
  parameter int NoiseWorleyOrder  = pst_pkg::NoiseWorleyOrderDefault,
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
  parameter int JacobianInt      = pst_pkg::JacobianIntDefault,
  parameter int JacobianFrac     = pst_pkg::JacobianFracDefault,
  parameter int FilterBandlimit  = pst_pkg::FilterBandlimitDefault,
  parameter int NoiseRegs        = pst_pkg::NoiseRegsDefault,
  parameter int OctaveRegs       = pst_pkg::OctaveRegsDefault,
  parameter int SideW            = pst_pkg::TagBits,   // side_i: the tag at its low TagBits, the
                                                       // Jacobian (6 x Jacobian) above it
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
  localparam int OctBits = $clog2(Octaves + 1),                   // active octave count
  localparam int FB  = pst_pkg::FadeBits,                         // a fade table entry, alpha
  localparam int LMW = pst_pkg::FadeLgBits                        // lg ||M||
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  // The fragment in [A] and its hand-over to [B]
  input  logic                      valid_i,
  output logic                      ready_o,
  input  logic [3*CW-1:0]           s_i,
  input  logic [SideW-1:0]          side_i,   // carried to side_o with the fragment
  output logic                      valid_o,
  input  logic                      ready_i,
  output logic [FW-1:0]             f_o,
  output logic [3*GW-1:0]           grad_o,
  output logic [SideW-1:0]          side_o,
  output logic                      busy_o,
  // Registers
  input  logic [OctBits-1:0]        active_i,
  input  logic [10*QW-1:0]          quad_i,
  input  logic [Octaves*9*MW-1:0]   oct_m_i,
  input  logic [Octaves*3*OW-1:0]   oct_o_i,
  input  logic [Octaves*AW-1:0]     oct_a_i,
  input  logic [Octaves*9*GMW-1:0]  oct_gm_i,
  input  logic [pst_pkg::RegWorleyCount*(pst_pkg::WorleyCoefInt+pst_pkg::WorleyCoefFrac)-1:0] worley_c_i,
  input  logic [Octaves*LMW-1:0]    oct_lgm_i,
  input  logic                      bl_i,
  input  logic [pst_pkg::FadeEntries*FB-1:0] fade_i,
  // Debug probes (pst_top's; zero when DebugProbes = 0)
  output logic                      probe_valid_o,
  output logic [pst_pkg::TagBits-1:0] probe_tag_o,
  output logic [PPB-1:0]            probe_pass_o,
  output logic                      probe_q_valid_o,
  output logic [pst_pkg::TagBits-1:0] probe_q_tag_o,
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
  localparam int TB        = pst_pkg::TagBits;
  localparam int Passes    = Octaves / NoiseUnits;   // octave passes per fragment
  localparam int PassBits  = (Passes > 1) ? $clog2(Passes) : 1;
  // Pipeline registers: after the transform (parallel only), inside the noise unit, after the
  // term.
  localparam int XR        = (!Serial && OctaveRegs >= 2) ? 1 : 0;
  localparam int NR        = NoiseRegs;
  localparam int MR        = (OctaveRegs >= 1) ? 1 : 0;
  localparam int Lat       = Serial ? 0 : XR + NR + MR;   // parallel: a beat's issue to the end
  // Cycles per fragment in [A]: NoiseSteps cycles per pass (one noise evaluation per lane per
  // pass), plus, for the serial datapath, the first pass's transform rows and the last pass's
  // term rows (pst_pkg::SerialOctaveExtraCycles) and the registers the last pass's noise and
  // term pass through.
  localparam int Cycles    = Passes * NoiseSteps + (Serial ? pst_pkg::SerialOctaveExtraCycles + NR + MR : 0);
  // The serial quadric needs up to StepMax cycles (pst_quadric_serial's NSteps): a fragment
  // with fewer octave cycles waits for it, so the counter reaches StepMax there.
  localparam int CycMax    = (Serial && Cycles < pst_pkg::StepMax + 1) ? pst_pkg::StepMax + 1 : Cycles;
  localparam int CycBits   = (CycMax > 1) ? $clog2(CycMax) : 1;
  // Guard bits: the accumulators add q and up to Octaves terms without overflow.
  localparam int AccGuard  = $clog2(Octaves + 1) + 1;
  localparam int FAccW     = FW + AccGuard;
  localparam int GAccW     = GW + AccGuard;
  // A beat (parallel): {valid, pass, step, first, last}.
  localparam int BW        = 1 + PassBits + 3 + 2;
  // Bandlimited octaves.
  localparam bit Bl        = (FilterBandlimit == pst_pkg::FilterBandlimitIsotropic);
  localparam int JW        = JacobianInt + JacobianFrac;
  localparam int LgW       = $clog2((JW + 1) << pst_pkg::FadeLgFrac) + 1;   // pst_fade_lg's lg_o
  localparam logic [FB-1:0] AlphaOne = FB'(1 << pst_pkg::FadeFrac);

  // The pixel's edges' lengths (the fragment's Jacobian in side_i: dsdx, then dsdy), at the
  // fragment's issue; their lg (pst_fade_lg) and the fades follow behind registers (below).
  logic [JW-1:0]  lenx_f, leny_f;
  logic [LgW-1:0] lgx, lgy;   // the lg the lanes' fades use (parallel: with the beat at g_flow's F1 + F2)
  if (Bl) begin : g_len
    pst_fade_norm #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_nx (
      .e_i (side_i[TB +: 3*JW]), .len_o (lenx_f));
    pst_fade_norm #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_ny (
      .e_i (side_i[TB + 3*JW +: 3*JW]), .len_o (leny_f));
  end else begin : g_no_len
    assign lenx_f = '0;
    assign leny_f = '0;
    assign lgx    = '0;
    assign lgy    = '0;
    logic unused_fade;
    assign unused_fade = ^{bl_i, fade_i, oct_lgm_i, lenx_f, leny_f, lgx, lgy};
  end

  // The fragment in [A] stays Cycles cycles; cyc_q counts them. Schedule of a lane:
  //   parallel: pass p, noise step j at cycle p NoiseSteps + j (a beat each); the octave
  //             transform at the beat's issue, the octave term after the noise unit.
  //   serial:   one row of M_i s + o_i and of a_i M_i^T g per cycle (3 + 3 multipliers
  //             instead of 9 + 9), software-pipelined around the noise unit (SR = 3 rows,
  //             NR = its registers):
  //               transform of pass p, row r   cycle p NoiseSteps + r         (r < SR)
  //               noise of pass p, step j      cycle SR + p NoiseSteps + j
  //               term of pass p, row r        cycle SR + NR + (p + 1) NoiseSteps + r
  //             and the term register (MR) adds one cycle before the accumulators, so
  //             Cycles = Passes NoiseSteps + 2 SR + NR + MR (NoiseSteps >= 4 keeps the three
  //             apart: rows 0, 1 wait in a buffer while the previous pass's noise runs, row 2
  //             completes the noise unit's input at its last step; a pass's result waits in
  //             n_q for its term rows).
  logic [CycBits-1:0]  cyc_q, cyc_d;
  logic                last_cycle;  // the fragment's last cycle in the octave stage
  logic                noise_on;    // a noise evaluation starts a step this cycle
  logic [PassBits-1:0] npass;       // its pass
  logic [2:0]          nstep;       // its step
  logic                xf_on;       // serial: a transform row is computed this cycle
  logic [PassBits-1:0] xpass;
  logic [1:0]          xrow;
  logic                tm_on;       // serial: a term row is computed this cycle
  logic [PassBits-1:0] tpass;
  logic [1:0]          trow;

  logic quad_done;   // the quadric's result is valid (always, when parallel)
  assign last_cycle = (32'(cyc_q) + 1 >= Cycles) && quad_done;

  // The schedule of cycle c: {noise_on, npass, nstep, xf_on, xpass, xrow, tm_on, tpass, trow}.
  localparam int SchW = 3 * PassBits + 10;
  function automatic logic [SchW-1:0] sched(input int c);
    int                  cn, ct;
    logic                no, xo, to;
    logic [PassBits-1:0] np, xp, tp;
    logic [2:0]          ns;
    logic [1:0]          xr, tr;
    cn = c - SR;
    ct = c - SR - NR;
    if (!Serial) begin
      no = 1'b1;
      np = PassBits'(c / NoiseSteps);
      ns = 3'(c % NoiseSteps);
      xo = 1'b0;
      xp = '0;
      xr = '0;
      to = 1'b0;
      tp = '0;
      tr = '0;
    end else begin
      no = (c >= SR) && (c < SR + Passes * NoiseSteps);
      np = no ? PassBits'(cn / NoiseSteps) : '0;
      ns = no ? 3'(cn % NoiseSteps) : '0;
      xo = (c < Passes * NoiseSteps) && (c % NoiseSteps < SR);
      xp = PassBits'(c / NoiseSteps);
      xr = 2'(c % NoiseSteps);
      to = (ct >= NoiseSteps) && (ct < (Passes + 1) * NoiseSteps) && (ct % NoiseSteps < SR);
      tp = to ? PassBits'(ct / NoiseSteps - 1) : '0;
      tr = to ? 2'(ct % NoiseSteps) : '0;
    end
    sched = {no, np, ns, xo, xp, xr, to, tp, tr};
  endfunction

  // Parallel: decoded from cyc_q. Serial: registered, the next cycle's decoded from cyc_d
  // (the decode stays off the term rows' multiplier paths; sch_q = sched(cyc_q) always).
  logic [SchW-1:0] sch, sch_d;   // this cycle's, the next cycle's
  assign {noise_on, npass, nstep, xf_on, xpass, xrow, tm_on, tpass, trow} = sch;
  assign sch_d = sched(32'(cyc_d));
  if (!Serial) begin : g_sched_comb
    assign sch = sched(32'(cyc_q));
    logic unused_sch_d;
    assign unused_sch_d = ^sch_d;
  end else begin : g_sched_reg
    logic [SchW-1:0] sch_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) sch_q <= sched(0);
      else sch_q <= sch_d;
    end
    assign sch = sch_q;
    logic unused_xpass;   // the lanes select their rows from sch_d
    assign unused_xpass = ^xpass;
  end
  if (!Serial) begin : g_unused_sched
    logic unused_sched;   // the serial schedule's signals (constant here)
    assign unused_sched = ^{xf_on, xpass, xrow, tm_on, tpass, trow, noise_on, last_cycle};
  end

  // en: the pipeline advances (parallel: everything but a refused last beat at the end;
  // serial: the fragment moves to its next cycle, or leaves).
  logic en;
  logic advance;     // serial: the fragment moves to its next cycle at this edge

  // Per lane at the end of the pipeline: this beat's contribution to the sums (zero when it
  // has none). acc_en, acc_first: the beat is added (first: from zero); q_e, gradq_e: the
  // quadric there (used with the last beat).
  // (Flat vectors, lane u at [u*W +: W]: Yosys 0.23 drops unpacked-array elements driven by
  // instance ports.)
  logic [NoiseUnits*FW-1:0]   fterm;
  logic [NoiseUnits*3*GW-1:0] gterm;
  logic            acc_en, acc_first;
  logic [FW-1:0]   q_e;
  logic [3*GW-1:0] gradq_e;

  // Noise unit ports per lane.
  logic            nz_en, nz_valid;
  logic [2:0]      nz_step;
  logic [NoiseUnits*LTW-1:0]   nz_lat;
  logic [NoiseUnits*3*LF-1:0]  nz_frac;
  logic [NoiseUnits*NW-1:0]    nz_n;
  logic [NoiseUnits*3*NGW-1:0] nz_g;
  logic [NoiseUnits-1:0] nz_last;   // the output token is an evaluation's last step

  // Probe sources: the beat / fragment whose noise results are at the noise units' outputs.
  logic            pr_valid;
  logic [PPB-1:0]  pr_pass;
  logic [TB-1:0]   pr_tag;
  logic [NoiseUnits*LTW-1:0]  pr_lat;
  logic [NoiseUnits*3*LF-1:0] pr_frac;

  if (!Serial) begin : g_flow
    // ---- parallel: beats through the pipeline --------------------------------------------
    logic [BW-1:0]    beat_f, beat_x, beat_n, beat_e;     // at issue, after [X], after the noise, at the end
    logic [SideW-1:0] side_x, side_n, side_e;
    logic             first_f, last_f;
    logic [FW-1:0]    q_f;
    logic [3*GW-1:0]  gradq_f;

    assign first_f = (cyc_q == '0);
    assign last_f  = (32'(cyc_q) + 1 >= Cycles);
    assign beat_f  = {valid_i, npass, nstep, first_f, last_f};
    assign advance = 1'b0;
    logic unused_adv;
    assign unused_adv = advance;

    // The pipeline stalls only while the end holds a last beat that [B] refuses.
    assign en      = ~(valid_o & ~ready_i);
    assign ready_o = last_f & en;

    always_comb begin
      cyc_d = cyc_q;
      if (en && valid_i) cyc_d = last_f ? '0 : cyc_q + 1'b1;
    end

    // Quadric (every product every beat), pipelined through the first min(2, Lat) registers
    // (pst_quadric's Regs) and delayed through the rest.
    localparam int QR = (Lat < 2) ? Lat : 2;
    pst_quadric #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac),
      .Regs(QR)
    ) u_quadric (
      .clk_i, .rst_ni, .en_i (en), .s_i (s_i), .coef_i (quad_i), .q_o (q_f), .gradq_o (gradq_f)
    );
    pst_delay #(.Width(FW + 3*GW), .Depth(Lat - QR)) u_q_delay (
      .clk_i, .rst_ni, .en_i (en), .d_i ({gradq_f, q_f}), .q_o ({gradq_e, q_e})
    );
    assign quad_done = 1'b1;

    // Beats and side payload: [X] after the transform, NR beside the noise units, [M] after
    // the term.
    pst_delay #(.Width(BW), .Depth(XR), .Reset(1'b1)) u_beat_x (
      .clk_i, .rst_ni, .en_i (en), .d_i (beat_f), .q_o (beat_x));
    pst_delay #(.Width(BW), .Depth(NR), .Reset(1'b1)) u_beat_n (
      .clk_i, .rst_ni, .en_i (en), .d_i (beat_x), .q_o (beat_n));
    pst_delay #(.Width(BW), .Depth(MR), .Reset(1'b1)) u_beat_e (
      .clk_i, .rst_ni, .en_i (en), .d_i (beat_n), .q_o (beat_e));
    pst_delay #(.Width(SideW), .Depth(XR)) u_side_x (
      .clk_i, .rst_ni, .en_i (en), .d_i (side_i), .q_o (side_x));
    pst_delay #(.Width(SideW), .Depth(NR)) u_side_n (
      .clk_i, .rst_ni, .en_i (en), .d_i (side_x), .q_o (side_n));
    pst_delay #(.Width(SideW), .Depth(MR)) u_side_e (
      .clk_i, .rst_ni, .en_i (en), .d_i (side_n), .q_o (side_e));

    // Field views of the beats.
    logic                valid_n, valid_e, first_e, last_e, nlast_n;
    logic [PassBits-1:0] pass_n;
    logic [2:0]          step_x, step_n;
    assign valid_n  = beat_n[BW-1];
    assign pass_n   = beat_n[5 +: PassBits];
    assign step_x   = beat_x[2 +: 3];
    assign step_n   = beat_n[2 +: 3];
    assign nlast_n  = valid_n && (32'(step_n) == NoiseSteps - 1);
    assign valid_e  = beat_e[BW-1];
    assign first_e  = beat_e[1];
    assign last_e   = beat_e[0];
    logic unused_beat;
    assign unused_beat = ^{beat_x[BW-1], beat_x[1:0], beat_n[1:0], beat_e[BW-2:2], nz_last};

    assign nz_en    = en;
    assign nz_valid = beat_x[BW-1];
    assign nz_step  = step_x;

    // Beats in the pipeline's registers (issued, not yet past the end).
    if (Lat > 0) begin : g_count
      localparam int IW = $clog2(Lat + 2);
      logic [IW-1:0] inflight_q;
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) inflight_q <= '0;
        else if (en) inflight_q <= inflight_q + IW'(valid_i) - IW'(valid_e);
      end
      assign busy_o = (inflight_q != '0);
    end else begin : g_nocount
      assign busy_o = 1'b0;
    end

    // Bandlimited octaves: the fade chain of a beat spread over the registers between its issue
    // and its term (XR + NR): a register after the lengths (F1), one after their lg (F2), the
    // rest after the lanes' fades (F3); fewer registers leave the chain combinational.
    localparam int FL = XR + NR;
    localparam int F1 = (FL >= 3) ? 1 : 0;
    localparam int F2 = (FL >= 2) ? 1 : 0;
    localparam int F3 = FL - F1 - F2;
    if (Bl) begin : g_fade_px
      logic [2*JW-1:0]  len_1;
      logic [LgW-1:0]   lgx_1, lgy_1;
      pst_delay #(.Width(2*JW), .Depth(F1)) u_len (
        .clk_i, .rst_ni, .en_i (en), .d_i ({leny_f, lenx_f}), .q_o (len_1));
      pst_fade_lg #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_lgx (
        .len_i (len_1[0 +: JW]), .lg_o (lgx_1));
      pst_fade_lg #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_lgy (
        .len_i (len_1[JW +: JW]), .lg_o (lgy_1));
      pst_delay #(.Width(2*LgW), .Depth(F2)) u_lg (
        .clk_i, .rst_ni, .en_i (en), .d_i ({lgy_1, lgx_1}), .q_o ({lgy, lgx}));
    end

    for (genvar u = 0; u < NoiseUnits; u++) begin : g_lane
      // Octave of this lane in the beat's pass at the front (transform) and after the noise
      // unit (term); lane_on: an active octave.
      logic [OctBits:0] oct_n;
      logic             lane_on;
      logic [FW-1:0]    fterm_raw;
      logic [3*GW-1:0]  gterm_raw;
      if (Passes > 1) begin : g_shared
        assign oct_n = (OctBits + 1)'(pass_n) * (OctBits + 1)'(NoiseUnits) + (OctBits + 1)'(u);
      end else begin : g_parallel
        assign oct_n = (OctBits + 1)'(u);
      end
      assign lane_on = oct_n < {1'b0, active_i};

      // The register arrays are indexed by the octave of the beat (a constant when Passes = 1).
      logic [9*MW-1:0]  m_sel;
      logic [3*OW-1:0]  o_sel;
      logic [AW-1:0]    a_sel;
      logic [9*GMW-1:0] gm_sel;
      logic [LMW-1:0]   lgm_sel;
      always_comb begin
        m_sel  = oct_m_i[u*9*MW +: 9*MW];
        o_sel  = oct_o_i[u*3*OW +: 3*OW];
        lgm_sel = oct_lgm_i[u*LMW +: LMW];
        a_sel  = oct_a_i[u*AW +: AW];
        gm_sel = oct_gm_i[u*9*GMW +: 9*GMW];
        for (int p = 1; p < Passes; p++) begin
          if (32'(npass) == p) begin
            m_sel  = oct_m_i[(p * NoiseUnits + u)*9*MW +: 9*MW];
            o_sel  = oct_o_i[(p * NoiseUnits + u)*3*OW +: 3*OW];
            lgm_sel = oct_lgm_i[(p * NoiseUnits + u)*LMW +: LMW];
          end
          if (32'(pass_n) == p) begin
            a_sel  = oct_a_i[(p * NoiseUnits + u)*AW +: AW];
            gm_sel = oct_gm_i[(p * NoiseUnits + u)*9*GMW +: 9*GMW];
          end
        end
      end

      logic [LTW-1:0]  lat_f;
      logic [3*LF-1:0] frac_f;
      pst_octave_transform #(
        .CoordInt(CoordInt), .CoordFrac(CoordFrac), .MatrixInt(MatrixInt), .MatrixFrac(MatrixFrac),
        .OffsetInt(OffsetInt), .OffsetFrac(OffsetFrac), .NoiseLatticeFrac(NoiseLatticeFrac)
      ) u_transform (
        .s_i (s_i), .m_i (m_sel), .o_i (o_sel), .lat_o (lat_f), .frac_o (frac_f)
      );
      pst_delay #(.Width(LTW + 3*LF), .Depth(XR)) u_x (
        .clk_i, .rst_ni, .en_i (en), .d_i ({lat_f, frac_f}),
        .q_o ({nz_lat[u*LTW +: LTW], nz_frac[u*3*LF +: 3*LF]})
      );

      // The octave's fade: its lg ||M|| selected at the beat's issue and carried with the lg
      // lengths (F1 + F2), the fade, delayed beside the noise unit to the term (F3).
      logic [FB-1:0] alpha_n;
      if (Bl) begin : g_fade
        logic [LMW-1:0] lgm_2;
        logic [FB-1:0]  alpha_2;
        pst_delay #(.Width(LMW), .Depth(F1 + F2)) u_lgm (
          .clk_i, .rst_ni, .en_i (en), .d_i (lgm_sel), .q_o (lgm_2));
        pst_octave_fade #(.LgW(LgW)) u_fade (
          .en_i (bl_i), .lgx_i (lgx), .lgy_i (lgy), .lgm_i (lgm_2), .table_i (fade_i), .alpha_o (alpha_2));
        pst_delay #(.Width(FB), .Depth(F3)) u_alpha (
          .clk_i, .rst_ni, .en_i (en), .d_i (alpha_2), .q_o (alpha_n));
      end else begin : g_whole
        assign alpha_n = AlphaOne;
        logic unused_lgm;
        assign unused_lgm = ^lgm_sel;
      end

      pst_octave_term #(
        .NoiseOutFrac(NoiseOutFrac), .AmplitudeInt(AmplitudeInt), .AmplitudeFrac(AmplitudeFrac),
        .GradMatrixInt(GradMatrixInt), .GradMatrixFrac(GradMatrixFrac), .FInt(FInt),
        .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac), .Bandlimit(Bl)
      ) u_term (
        .n_i (nz_n[u*NW +: NW]), .g_i (nz_g[u*3*NGW +: 3*NGW]), .a_i (a_sel), .gm_i (gm_sel),
        .alpha_i (alpha_n), .fterm_o (fterm_raw), .gterm_o (gterm_raw)
      );
      pst_delay #(.Width(FW + 3*GW), .Depth(MR)) u_m (
        .clk_i, .rst_ni, .en_i (en),
        .d_i ((lane_on && nlast_n) ? {gterm_raw, fterm_raw} : '0),
        .q_o ({gterm[u*3*GW +: 3*GW], fterm[u*FW +: FW]})
      );

      // Probes: the lattice input beside the noise unit.
      if (DebugProbes) begin : g_probe
        pst_delay #(.Width(LTW + 3*LF), .Depth(NR)) u_pr (
          .clk_i, .rst_ni, .en_i (en), .d_i ({nz_lat[u*LTW +: LTW], nz_frac[u*3*LF +: 3*LF]}),
          .q_o ({pr_lat[u*LTW +: LTW], pr_frac[u*3*LF +: 3*LF]})
        );
      end else begin : g_no_probe
        assign pr_lat[u*LTW +: LTW]     = '0;
        assign pr_frac[u*3*LF +: 3*LF]  = '0;
      end
    end

    assign acc_en    = en & valid_e;
    assign acc_first = first_e;
    assign valid_o   = valid_e & last_e;
    assign side_o    = side_e;

    assign pr_valid  = nlast_n;
    assign pr_pass   = PPB'(pass_n);
    assign pr_tag    = side_n[TB-1:0];
    assign probe_q_tag_o = DebugProbes ? side_e[TB-1:0] : '0;
    logic unused_side;
    assign unused_side = ^{side_n, step_n};

  end else begin : g_hold
    // ---- serial: the fragment stays in [A] -------------------------------------------------
    assign advance = valid_i & ~last_cycle;
    assign en      = valid_i & (~last_cycle | ready_i);   // advance, or the fragment leaves
    assign ready_o = last_cycle & ready_i;
    assign valid_o = valid_i & last_cycle;
    assign side_o  = side_i;
    assign busy_o  = 1'b0;

    always_comb begin
      cyc_d = cyc_q;
      if (advance) cyc_d = cyc_q + 1'b1;
      else if (valid_i && ready_i) cyc_d = '0;
    end

    // Quadric: one multiplier stepped by the cycle count (pst_quadric_serial), its result
    // complete by the last cycle, where it is added. With the term register (MR) its result
    // passes a register too, so the last cycle's sum starts at registers: the last cycle
    // comes one cycle after the quadric's last step at the earliest.
    logic [SB-1:0]   qstep, qstep_d;   // this cycle's step, the next cycle's (from cyc_d)
    logic            qdone, qdone_e;
    logic [FW-1:0]   q_s;
    logic [3*GW-1:0] gradq_s;
    assign qstep   = (32'(cyc_q) < pst_pkg::StepMax) ? SB'(cyc_q) : SB'(pst_pkg::StepMax);
    assign qstep_d = (32'(cyc_d) < pst_pkg::StepMax) ? SB'(cyc_d) : SB'(pst_pkg::StepMax);
    pst_quadric_serial #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac),
      .Regs(MR)
    ) u_quadric (
      .clk_i, .rst_ni,
      .step_i (qstep), .step_next_i (qstep_d), .adv_i (advance), .done_o (qdone),
      .s_i (s_i), .coef_i (quad_i), .q_o (q_s), .gradq_o (gradq_s)
    );
    pst_delay #(.Width(1 + FW + 3*GW), .Depth(MR)) u_q_reg (
      .clk_i, .rst_ni, .en_i (en), .d_i ({qdone, gradq_s, q_s}), .q_o ({qdone_e, gradq_e, q_e}));
    assign quad_done = qdone_e;

    assign nz_en    = en;
    assign nz_valid = noise_on;
    assign nz_step  = nstep;

    // Bandlimited octaves: the lengths and their lg registered (free-running: the fragment's
    // Jacobian stays in side_i while it is in [A]; the first term row's fade, registered one
    // cycle ahead, is formed at cycle SR + NR + NoiseSteps - 1 >= 6, after both).
    if (Bl) begin : g_fade_px
      logic [2*JW-1:0]  len_q;
      logic [LgW-1:0]   lgx_s, lgy_s, lgx_q, lgy_q;
      always_ff @(posedge clk_i) len_q <= {leny_f, lenx_f};
      pst_fade_lg #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_lgx (
        .len_i (len_q[0 +: JW]), .lg_o (lgx_s));
      pst_fade_lg #(.JacobianInt(JacobianInt), .JacobianFrac(JacobianFrac)) u_lgy (
        .len_i (len_q[JW +: JW]), .lg_o (lgy_s));
      always_ff @(posedge clk_i) begin
        lgx_q <= lgx_s;
        lgy_q <= lgy_s;
      end
      assign lgx = lgx_q;
      assign lgy = lgy_q;
    end

    // The pass of the noise units' output token (the probes name it).
    logic [PassBits-1:0] pass_n;
    pst_delay #(.Width(PassBits), .Depth(NR)) u_pass_n (
      .clk_i, .rst_ni, .en_i (en), .d_i (npass), .q_o (pass_n));

    for (genvar u = 0; u < NoiseUnits; u++) begin : g_lane
      // Octave of this lane's term rows (lane_on: an active octave).
      logic [OctBits:0] t_oct;
      assign t_oct = (OctBits + 1)'(tpass) * (OctBits + 1)'(NoiseUnits) + (OctBits + 1)'(u);

      // Register reads: row xrow of M and o of octave x_oct; row trow of GM and a of t_oct.
      // Selected for the next cycle (its schedule from cyc_d) and registered, like sch: the
      // register arrays do not change while a fragment is in flight (pst_top: writes only
      // while idle).
      logic [3*MW-1:0]  m_row, m_row_d;
      logic [OW-1:0]    o_row, o_row_d;
      logic [3*GMW-1:0] gm_row, gm_row_d;
      logic [AW-1:0]    a_t, a_t_d;
      logic [LMW-1:0]   lgm_t_d;
      logic [PassBits-1:0] xp, tp;   // the next cycle's transform and term rows (sched's fields)
      logic [1:0]          xr, tr;
      assign tr = sch_d[0 +: 2];
      assign tp = sch_d[2 +: PassBits];
      assign xr = sch_d[PassBits + 3 +: 2];
      assign xp = sch_d[PassBits + 5 +: PassBits];
      always_comb begin
        m_row_d  = '0;
        o_row_d  = '0;
        gm_row_d = '0;
        a_t_d    = '0;
        lgm_t_d  = '0;
        for (int p = 0; p < Passes; p++) begin
          for (int r = 0; r < SR; r++) begin
            if (32'(xp) == p && 32'(xr) == r) begin
              m_row_d = oct_m_i[((p * NoiseUnits + u)*9 + 3*r)*MW +: 3*MW];
              o_row_d = oct_o_i[((p * NoiseUnits + u)*3 + r)*OW +: OW];
            end
            if (32'(tp) == p && 32'(tr) == r) begin
              gm_row_d = oct_gm_i[((p * NoiseUnits + u)*9 + 3*r)*GMW +: 3*GMW];
            end
          end
          if (32'(tp) == p) begin
            a_t_d   = oct_a_i[(p * NoiseUnits + u)*AW +: AW];
            lgm_t_d = oct_lgm_i[(p * NoiseUnits + u)*LMW +: LMW];
          end
        end
      end
      always_ff @(posedge clk_i) begin
        m_row  <= m_row_d;
        o_row  <= o_row_d;
        gm_row <= gm_row_d;
        a_t    <= a_t_d;
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
      assign nz_lat[u*LTW +: LTW]    = cur_lat_q;
      assign nz_frac[u*3*LF +: 3*LF] = cur_frac_q;

      // The noise result waits for the term rows of the next NoiseSteps cycles.
      logic [NW-1:0]    n_q;
      logic [3*NGW-1:0] g_q;
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          n_q <= '0;
          g_q <= '0;
        end else if (en && nz_last[u]) begin
          n_q <= nz_n[u*NW +: NW];
          g_q <= nz_g[u*3*NGW +: 3*NGW];
        end
      end

      // Term, one row: a n (used at row 0) and row trow of a M^T g.
      logic [FW-1:0] fterm_raw, fterm_d;
      logic [GW-1:0] gterm_raw;
      logic [3*GW-1:0] gterm_d;
      logic          lane_on;
      // The term pass's fade, registered with its operands (from the registered lg above).
      logic [FB-1:0] alpha_t;
      if (Bl) begin : g_fade
        logic [FB-1:0] alpha_t_d;
        pst_octave_fade #(.LgW(LgW)) u_fade (
          .en_i (bl_i), .lgx_i (lgx), .lgy_i (lgy), .lgm_i (lgm_t_d), .table_i (fade_i), .alpha_o (alpha_t_d));
        always_ff @(posedge clk_i) alpha_t <= alpha_t_d;
      end else begin : g_whole
        assign alpha_t = AlphaOne;
        logic unused_lgm;
        assign unused_lgm = ^lgm_t_d;
      end
      pst_octave_term #(
        .NoiseOutFrac(NoiseOutFrac), .AmplitudeInt(AmplitudeInt), .AmplitudeFrac(AmplitudeFrac),
        .GradMatrixInt(GradMatrixInt), .GradMatrixFrac(GradMatrixFrac), .FInt(FInt),
        .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac), .Rows(1), .Bandlimit(Bl)
      ) u_term (
        .n_i (n_q), .g_i (g_q), .a_i (a_t), .gm_i (gm_row), .alpha_i (alpha_t), .fterm_o (fterm_raw),
        .gterm_o (gterm_raw)
      );
      assign lane_on = tm_on && (t_oct < {1'b0, active_i});
      assign fterm_d = (lane_on && trow == 2'd0) ? fterm_raw : '0;
      for (genvar k = 0; k < 3; k++) begin : g_gterm
        assign gterm_d[k*GW +: GW] = (lane_on && 32'(trow) == k) ? gterm_raw : '0;
      end
      // The term register: one more cycle to the accumulators (loaded on every move of the
      // fragment, so it holds zero when the next fragment starts).
      pst_delay #(.Width(FW + 3*GW), .Depth(MR)) u_m (
        .clk_i, .rst_ni, .en_i (en), .d_i ({gterm_d, fterm_d}),
        .q_o ({gterm[u*3*GW +: 3*GW], fterm[u*FW +: FW]})
      );

      if (DebugProbes) begin : g_probe
        // The lattice input of the pass at the output: delayed beside the noise unit.
        pst_delay #(.Width(LTW + 3*LF), .Depth(NR)) u_pr (
          .clk_i, .rst_ni, .en_i (en), .d_i ({cur_lat_q, cur_frac_q}),
          .q_o ({pr_lat[u*LTW +: LTW], pr_frac[u*3*LF +: 3*LF]})
        );
      end else begin : g_no_probe
        assign pr_lat[u*LTW +: LTW]    = '0;
        assign pr_frac[u*3*LF +: 3*LF] = '0;
      end
    end

    assign acc_en    = advance;
    assign acc_first = (cyc_q == '0);

    assign pr_valid  = valid_i & nz_last[0];
    assign pr_pass   = PPB'(pass_n);
    assign pr_tag    = side_i[TB-1:0];
    assign probe_q_tag_o = DebugProbes ? side_i[TB-1:0] : '0;
  end

  // ---- noise units ---------------------------------------------------------------------------
  for (genvar u = 0; u < NoiseUnits; u++) begin : g_noise
    logic nz_valid_o;
    // The basis select: the lattice-noise unit, or a worley unit (noise.worley_search).
    if (NoiseWorleySearch == pst_pkg::NoiseWorleySearchNone) begin : g_lattice
      pst_noise #(
        .NoiseInterp(NoiseInterp), .NoiseCorner(NoiseCorner), .NoiseHash(NoiseHash),
        .NoiseValueFrac(NoiseValueFrac), .NoiseLatticeFrac(NoiseLatticeFrac),
        .NoiseOutFrac(NoiseOutFrac), .NoiseSteps(NoiseSteps), .NoiseGuardBits(NoiseGuardBits),
        .NoiseGradFrac(NoiseGradFrac), .NoiseRegs(NoiseRegs)
      ) u_noise (
        .clk_i, .rst_ni, .en_i (nz_en), .valid_i (nz_valid), .step_i (nz_step),
        .lat_i (nz_lat[u*LTW +: LTW]), .frac_i (nz_frac[u*3*LF +: 3*LF]), .valid_o (nz_valid_o),
        .last_o (nz_last[u]), .n_o (nz_n[u*NW +: NW]), .grad_o (nz_g[u*3*NGW +: 3*NGW])
      );
      logic unused_wc;
      assign unused_wc = ^worley_c_i;
    end else begin : g_worley
      pst_worley #(
        .NoiseLatticeFrac(NoiseLatticeFrac), .NoiseOutFrac(NoiseOutFrac), .NoiseSteps(NoiseSteps),
        .NoiseGuardBits(NoiseGuardBits), .NoiseRegs(NoiseRegs), .NoiseWorleySearch(NoiseWorleySearch),
        .NoiseWorleyPoints(NoiseWorleyPoints), .NoiseWorleyOrder(NoiseWorleyOrder)
      ) u_noise (
        .clk_i, .rst_ni, .en_i (nz_en), .valid_i (nz_valid), .step_i (nz_step),
        .lat_i (nz_lat[u*LTW +: LTW]), .frac_i (nz_frac[u*3*LF +: 3*LF]), .coef_i (worley_c_i),
        .valid_o (nz_valid_o), .last_o (nz_last[u]), .n_o (nz_n[u*NW +: NW]),
        .grad_o (nz_g[u*3*NGW +: 3*NGW])
      );
    end
    logic unused_nz;
    assign unused_nz = nz_valid_o;

    if (DebugProbes) begin : g_probe
      assign probe_lat_o[u*LTW +: LTW]        = pr_lat[u*LTW +: LTW];
      assign probe_frac_o[u*3*LF +: 3*LF]     = pr_frac[u*3*LF +: 3*LF];
      assign probe_n_o[u*NW +: NW]            = nz_n[u*NW +: NW];
      assign probe_g_o[u*3*NGW +: 3*NGW]      = nz_g[u*3*NGW +: 3*NGW];
    end else begin : g_no_probe
      assign probe_lat_o[u*LTW +: LTW]        = '0;
      assign probe_frac_o[u*3*LF +: 3*LF]     = '0;
      assign probe_n_o[u*NW +: NW]            = '0;
      assign probe_g_o[u*3*NGW +: 3*NGW]      = '0;
    end
  end

  // Probes: the noise results of a pass at the noise units' output (its last step), with the
  // tag and lattice input of that pass; q with the fragment's last beat at the end.
  assign probe_valid_o   = DebugProbes & pr_valid;
  assign probe_tag_o     = DebugProbes ? pr_tag : '0;
  assign probe_pass_o    = DebugProbes ? pr_pass : '0;
  assign probe_q_valid_o = DebugProbes & valid_o;
  assign probe_q_o       = DebugProbes ? q_e : '0;

  // Accumulation at the end: every beat adds the lanes' contributions (the first from zero);
  // the last adds q and saturates. The sums are exact, so the order of the terms does not
  // change a bit.
  logic signed [FAccW-1:0] facc_q, facc_d, fsum, fout;
  logic [3*GAccW-1:0]      gacc_q, gacc_d, gsum, gout;

  always_comb begin
    logic signed [GAccW-1:0] gc;
    fsum = acc_first ? '0 : facc_q;
    for (int u = 0; u < NoiseUnits; u++) fsum = fsum + FAccW'($signed(fterm[u*FW +: FW]));
    fout = fsum + FAccW'($signed(q_e));
    for (int k = 0; k < 3; k++) begin
      gc = acc_first ? '0 : $signed(gacc_q[k*GAccW +: GAccW]);
      for (int u = 0; u < NoiseUnits; u++) gc = gc + GAccW'($signed(gterm[(3*u + k)*GW +: GW]));
      gsum[k*GAccW +: GAccW] = gc;
      gout[k*GAccW +: GAccW] = gc + GAccW'($signed(gradq_e[k*GW +: GW]));
    end
    facc_d = acc_en ? fsum : facc_q;
    gacc_d = acc_en ? gsum : gacc_q;
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
  initial begin
    if (OctaveRegs < 0 || OctaveRegs > 2) $error("pst_octave_stage: OctaveRegs must be 0..2");
    if (SideW < TB) $error("pst_octave_stage: SideW must hold the tag");
    if (Bl && SideW < TB + 6*JW) $error("pst_octave_stage: SideW must hold the Jacobian above the tag");
  end
  // The cycle counter stays within the fragment's cycles.
  assert property (@(posedge clk_i) disable iff (!rst_ni) 32'(cyc_q) < CycMax);
`endif

endmodule

`default_nettype wire

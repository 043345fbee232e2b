// pst_top: the procedural solid-texturing pipeline of Hart et al. 1999 (docs/HARDWARE.md).
//
//   fragment (tag, s, J) -> [A] -> octave stage (quadric, NoiseUnits x {octave transform,
//   noise, octave term}, accumulation over ceil(Octaves / NoiseUnits) passes) -> [B] ->
//   filter width -> [C] -> colour-table filter -> [D] -> (tag, RGBA, f, grad, W)
//
// [A]..[D] are pst_pipe_reg stages (valid/ready, ready[i] = ready[i+1] | ~valid[i+1]).
//
// Parameters (all from the profile, rtl/configs/NAME.toml, through scripts/profile.py):
//   Octaves, NoiseUnits   K noise terms held; units evaluated per pass. Octaves / NoiseUnits
//                         passes per fragment: 1 = one fragment per clock.
//   NoiseSteps            cycles per pass (a noise evaluation walks its corners over them,
//                         see pst_noise): Octaves / NoiseUnits x NoiseSteps cycles per fragment.
//   Datapath              0 parallel, 1 serial: the quadric one row per cycle, the filter
//                         width one product per cycle (6 cycles in [B], 16 with the euclidean
//                         norm: squares and square root serial too), the colour-table
//                         filter one channel per cycle (4 cycles in [C]).
//   Log2Clut, ColourBits  colour table of 2^Log2Clut entries, ColourBits per channel.
//   Noise*                noise unit variant and precision (see pst_noise).
//   FilterNorm, FilterRecipFrac   |grad| approximation; SAT reciprocal precision.
//   <Format>Int/Frac      every number format (docs/HARDWARE.md).
//
// Register writes (reg_we_i) are legal only while idle_o is high: the driver drains the
// pipeline before it changes the texture, as a driver between two objects would.
`default_nettype none

module pst_top #(
  parameter int Octaves          = 8,
  parameter int NoiseUnits       = 8,
  parameter int Log2Clut         = 8,
  parameter int ColourBits       = 8,
  parameter int Datapath         = 0,
  parameter int NoiseInterp      = 0,
  parameter int NoiseCorner      = 0,
  parameter int NoiseHash        = 0,
  parameter int NoiseValueFrac   = 15,
  parameter int NoiseLatticeFrac = 16,
  parameter int NoiseOutFrac     = 16,
  parameter int NoiseSteps       = 1,
  parameter int NoiseGuardBits   = 4,
  parameter int FilterNorm       = 0,
  parameter int FilterRecipFrac  = 18,
  parameter int CoordInt         = 12,
  parameter int CoordFrac        = 20,
  parameter int JacobianInt      = 8,
  parameter int JacobianFrac     = 24,
  parameter int MatrixInt        = 8,
  parameter int MatrixFrac       = 16,
  parameter int OffsetInt        = 13,
  parameter int OffsetFrac       = 16,
  parameter int AmplitudeInt     = 2,
  parameter int AmplitudeFrac    = 16,
  parameter int GradMatrixInt    = 8,
  parameter int GradMatrixFrac   = 16,
  parameter int QuadricInt       = 8,
  parameter int QuadricFrac      = 16,
  parameter int FInt             = 12,
  parameter int FFrac            = 20,
  parameter int GradInt          = 16,
  parameter int GradFrac         = 16,
  parameter int WidthFrac        = 8,
  parameter bit DebugProbes      = 1'b1,
  // Derived widths (not profile keys).
  localparam int CW  = CoordInt + CoordFrac,         // one texture coordinate
  localparam int JW  = JacobianInt + JacobianFrac,   // one Jacobian entry
  localparam int FW  = FInt + FFrac,                 // f
  localparam int GW  = GradInt + GradFrac,           // one grad_s f component
  localparam int WW  = Log2Clut + 2 + WidthFrac,     // W = w N in entries, < 4N
  localparam int CB4 = 4 * ColourBits                // packed RGBA
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  // Register write port (docs/HARDWARE.md register map)
  input  logic              reg_we_i,
  input  logic [15:0]       reg_addr_i,
  input  logic [31:0]       reg_wdata_i,
  output logic              idle_o,
  // Fragments in
  input  logic              frag_valid_i,
  output logic              frag_ready_o,
  input  logic [31:0]       frag_tag_i,
  input  logic [3*CW-1:0]   frag_s_i,
  input  logic [6*JW-1:0]   frag_j_i,
  // Colours out
  output logic              out_valid_o,
  input  logic              out_ready_i,
  output logic [31:0]       out_tag_o,
  output logic [CB4-1:0]    out_rgba_o,
  output logic [FW-1:0]     out_f_o,
  output logic [3*GW-1:0]   out_grad_o,
  output logic [WW-1:0]     out_w_o,
  // Debug probes of the octave stage (the fragment in [A], this pass): the harness samples
  // them every cycle so the scoreboard can name the first stage that differs. Tied to zero
  // when DebugProbes = 0 (synthesis).
  output logic                          probe_valid_o,
  output logic [31:0]                   probe_tag_o,
  output logic [7:0]                    probe_pass_o,
  output logic                          probe_q_valid_o,   // probe_q_o is final (the last cycle)
  output logic [FW-1:0]                 probe_q_o,
  output logic [NoiseUnits*36-1:0]      probe_lat_o,
  output logic [NoiseUnits*3*NoiseLatticeFrac-1:0] probe_frac_o,
  output logic [NoiseUnits*(4+NoiseOutFrac)-1:0]   probe_n_o,
  output logic [NoiseUnits*3*(6+NoiseOutFrac)-1:0] probe_g_o
);

  localparam int MW  = MatrixInt + MatrixFrac;       // one M_i entry
  localparam int OW  = OffsetInt + OffsetFrac;       // one o_i entry
  localparam int AW  = AmplitudeInt + AmplitudeFrac; // a_i
  localparam int GMW = GradMatrixInt + GradMatrixFrac;  // one a_i M_i^T entry
  localparam int QW  = QuadricInt + QuadricFrac;     // one quadric coefficient
  localparam int LF  = NoiseLatticeFrac;
  localparam int NW  = 4 + NoiseOutFrac;             // noise value Q4.NoiseOutFrac
  localparam int NGW = 6 + NoiseOutFrac;             // noise gradient Q6.NoiseOutFrac
  localparam int Passes    = Octaves / NoiseUnits;   // octave passes per fragment
  localparam int PassBits  = (Passes > 1) ? $clog2(Passes) : 1;
  // Cycles per fragment: NoiseSteps cycles per pass (one noise evaluation per lane per pass),
  // plus, for the serial datapath, the first pass's transform rows and the last pass's term
  // rows (3 + 3 cycles; see the octave stage).
  localparam int Cycles    = Passes * NoiseSteps + ((Datapath != 0) ? 6 : 0);
  // The serial quadric needs up to 31 cycles (pst_quadric_serial's NSteps): a fragment with
  // fewer octave cycles waits for it, so the counter reaches 31 there.
  localparam int CycMax    = (Datapath != 0 && Cycles < 32) ? 32 : Cycles;
  localparam int CycBits   = (CycMax > 1) ? $clog2(CycMax) : 1;
  localparam int OctBits   = $clog2(Octaves + 1);    // active octave count 0..Octaves
  // Guard bits: the accumulators add q and up to Octaves terms without overflow.
  localparam int AccGuard  = $clog2(Octaves + 1) + 1;
  localparam int FAccW     = FW + AccGuard;
  localparam int GAccW     = GW + AccGuard;

  // ---------------------------------------------------------------------------------------
  // Registers: control, quadric, octaves (written only while idle)
  // ---------------------------------------------------------------------------------------
  logic [2:0]         ctrl_q;      // [0] clamp, [2:1] filter kind
  logic [OctBits-1:0] active_q;    // active octaves
  logic [10*QW-1:0]   quad_q;      // A..J
  logic [9*MW-1:0]    oct_m_q  [Octaves];
  logic [3*OW-1:0]    oct_o_q  [Octaves];
  logic [AW-1:0]      oct_a_q  [Octaves];
  logic [9*GMW-1:0]   oct_gm_q [Octaves];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ctrl_q   <= '0;
      active_q <= '0;
      quad_q   <= '0;
    end else if (reg_we_i) begin
      if (reg_addr_i == 16'h0000) ctrl_q <= reg_wdata_i[2:0];
      if (reg_addr_i == 16'h0001) active_q <= reg_wdata_i[OctBits-1:0];
      for (int k = 0; k < 10; k++) begin
        if (reg_addr_i == 16'h0010 + 16'(k)) quad_q[k*QW +: QW] <= reg_wdata_i[QW-1:0];
      end
    end
  end

  // Octave registers: 0x0100 + 32 i + k (no reset: the driver writes every octave it enables).
  always_ff @(posedge clk_i) begin
    if (reg_we_i) begin
      for (int i = 0; i < Octaves; i++) begin
        for (int k = 0; k < 9; k++) begin
          if (reg_addr_i == 16'h0100 + 16'(32 * i + k)) oct_m_q[i][k*MW +: MW] <= reg_wdata_i[MW-1:0];
          if (reg_addr_i == 16'h0100 + 16'(32 * i + 13 + k)) begin
            oct_gm_q[i][k*GMW +: GMW] <= reg_wdata_i[GMW-1:0];
          end
        end
        for (int k = 0; k < 3; k++) begin
          if (reg_addr_i == 16'h0100 + 16'(32 * i + 9 + k)) oct_o_q[i][k*OW +: OW] <= reg_wdata_i[OW-1:0];
        end
        if (reg_addr_i == 16'h0100 + 16'(32 * i + 12)) oct_a_q[i] <= reg_wdata_i[AW-1:0];
      end
    end
  end

  // ---------------------------------------------------------------------------------------
  // [A] fragment register
  // ---------------------------------------------------------------------------------------
  localparam int AWidth = 32 + 3 * CW + 6 * JW;
  logic              a_valid, a_ready;
  logic [AWidth-1:0] a_data;

  pst_pipe_reg #(.Width(AWidth)) u_reg_a (
    .clk_i, .rst_ni,
    .valid_i (frag_valid_i), .ready_o (frag_ready_o),
    .data_i  ({frag_j_i, frag_s_i, frag_tag_i}),
    .valid_o (a_valid), .ready_i (a_ready), .data_o (a_data)
  );

  logic [31:0]     a_tag;
  logic [3*CW-1:0] a_s;
  logic [6*JW-1:0] a_j;
  assign {a_j, a_s, a_tag} = a_data;

  // ---------------------------------------------------------------------------------------
  // Octave stage: quadric + NoiseUnits octave lanes, Passes passes per fragment
  // ---------------------------------------------------------------------------------------
  // The fragment in [A] stays Cycles cycles; cyc_q counts them. Schedule of a lane:
  //   Datapath = 0: pass p, noise step j at cycle p NoiseSteps + j; the octave transform and
  //                 the octave term are combinational around the noise unit.
  //   Datapath = 1: one row of M_i s + o_i and of a_i M_i^T g per cycle (3 + 3 multipliers
  //                 instead of 9 + 9), software-pipelined around the noise unit:
  //                   transform of pass p, row r   cycle p NoiseSteps + r         (r < 3)
  //                   noise of pass p, step j      cycle 3 + p NoiseSteps + j
  //                   term of pass p, row r        cycle 3 + (p + 1) NoiseSteps + r
  //                 so Cycles = Passes NoiseSteps + 6 (NoiseSteps >= 4 keeps the three apart:
  //                 rows 0, 1 wait in a buffer while the previous pass's noise runs, row 2
  //                 completes the noise unit's input at its last step).
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
  assign advance    = a_valid & ~last_cycle;

  always_comb begin
    int c, cn;
    c  = 32'(cyc_q);
    cn = c - 3;
    if (Datapath == 0) begin
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
      noise_on = (c >= 3) && (c < 3 + Passes * NoiseSteps);
      npass    = noise_on ? PassBits'(cn / NoiseSteps) : '0;
      nstep    = noise_on ? 3'(cn % NoiseSteps) : '0;
      xf_on    = (c < Passes * NoiseSteps) && (c % NoiseSteps < 3);
      xpass    = PassBits'(c / NoiseSteps);
      xrow     = 2'(c % NoiseSteps);
      tm_on    = (c >= 3 + NoiseSteps) && (c < 3 + (Passes + 1) * NoiseSteps) &&
                 (cn % NoiseSteps < 3);
      tpass    = tm_on ? PassBits'(cn / NoiseSteps - 1) : '0;
      trow     = tm_on ? 2'(cn % NoiseSteps) : '0;
    end
  end
  assign nlast = noise_on && (32'(nstep) == NoiseSteps - 1);
  if (Datapath == 0) begin : g_unused_sched
    logic unused_sched;   // the serial schedule's signals (constant here)
    assign unused_sched = ^{xf_on, xpass, xrow, tm_on, tpass, trow};
  end

  logic signed [FAccW-1:0] facc_q, facc_d;
  logic [3*GAccW-1:0]      gacc_q, gacc_d;

  logic [FW-1:0]   q;
  logic [3*GW-1:0] gradq;

  // Datapath = 0: the whole quadric every cycle; 1: one multiplier stepped by the cycle count
  // (pst_quadric_serial), its result complete by the last cycle, where it is added.
  if (Datapath == 0) begin : g_quadric_par
    pst_quadric #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
    ) u_quadric (
      .s_i (a_s), .coef_i (quad_q), .q_o (q), .gradq_o (gradq)
    );
    assign quad_done = 1'b1;
  end else begin : g_quadric_ser
    logic [4:0] qstep;
    logic       qdone;
    assign qstep = (32'(cyc_q) < 31) ? 5'(cyc_q) : 5'd31;
    pst_quadric_serial #(
      .CoordInt(CoordInt), .CoordFrac(CoordFrac), .QuadricInt(QuadricInt),
      .QuadricFrac(QuadricFrac), .FInt(FInt), .FFrac(FFrac), .GradInt(GradInt), .GradFrac(GradFrac)
    ) u_quadric (
      .clk_i, .rst_ni,
      .step_i (qstep), .adv_i (advance), .done_o (qdone),
      .s_i (a_s), .coef_i (quad_q), .q_o (q), .gradq_o (gradq)
    );
    assign quad_done = qdone;
  end

  // Per lane, this cycle's contribution to the sums (zero when it has none).
  logic [FW-1:0]   fterm [NoiseUnits];
  logic [3*GW-1:0] gterm [NoiseUnits];

  for (genvar u = 0; u < NoiseUnits; u++) begin : g_lane
    logic [35:0]      lat;    // the noise unit's input
    logic [3*LF-1:0]  frac;
    logic [NW-1:0]    n;      // its output (valid at nlast)
    logic [3*NGW-1:0] g;

    if (Datapath == 0) begin : g_par
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
      assign lane_on = oct_idx < {1'b0, active_q};

      // The register arrays are indexed by the octave of this pass (a constant when Passes = 1).
      logic [9*MW-1:0]  m_sel;
      logic [3*OW-1:0]  o_sel;
      logic [AW-1:0]    a_sel;
      logic [9*GMW-1:0] gm_sel;
      always_comb begin
        m_sel  = oct_m_q[u];
        o_sel  = oct_o_q[u];
        a_sel  = oct_a_q[u];
        gm_sel = oct_gm_q[u];
        for (int p = 1; p < Passes; p++) begin
          if (32'(npass) == p) begin
            m_sel  = oct_m_q[p * NoiseUnits + u];
            o_sel  = oct_o_q[p * NoiseUnits + u];
            a_sel  = oct_a_q[p * NoiseUnits + u];
            gm_sel = oct_gm_q[p * NoiseUnits + u];
          end
        end
      end

      pst_octave_transform #(
        .CoordInt(CoordInt), .CoordFrac(CoordFrac), .MatrixInt(MatrixInt), .MatrixFrac(MatrixFrac),
        .OffsetInt(OffsetInt), .OffsetFrac(OffsetFrac), .NoiseLatticeFrac(NoiseLatticeFrac)
      ) u_transform (
        .s_i (a_s), .m_i (m_sel), .o_i (o_sel), .lat_o (lat), .frac_o (frac)
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
          for (int r = 0; r < 3; r++) begin
            if (32'(xpass) == p && 32'(xrow) == r) begin
              m_row = oct_m_q[p * NoiseUnits + u][3*r*MW +: 3*MW];
              o_row = oct_o_q[p * NoiseUnits + u][r*OW +: OW];
            end
            if (32'(tpass) == p && 32'(trow) == r) begin
              gm_row = oct_gm_q[p * NoiseUnits + u][3*r*GMW +: 3*GMW];
            end
          end
          if (32'(tpass) == p) a_t = oct_a_q[p * NoiseUnits + u];
        end
      end

      // Transform, one row: lattice index and fraction of axis xrow.
      logic [11:0]      lat_r;
      logic [LF-1:0]    frac_r;
      pst_octave_transform #(
        .CoordInt(CoordInt), .CoordFrac(CoordFrac), .MatrixInt(MatrixInt), .MatrixFrac(MatrixFrac),
        .OffsetInt(OffsetInt), .OffsetFrac(OffsetFrac), .NoiseLatticeFrac(NoiseLatticeFrac),
        .Rows(1)
      ) u_transform (
        .s_i (a_s), .m_i (m_row), .o_i (o_row), .lat_o (lat_r), .frac_o (frac_r)
      );

      // Rows 0, 1 wait in nxt; at row 2 the noise unit's input (cur) is loaded whole.
      logic [2*12-1:0] nxt_lat_q;
      logic [2*LF-1:0] nxt_frac_q;
      logic [35:0]     cur_lat_q;
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
            nxt_lat_q[xrow*12 +: 12]  <= lat_r;
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
      assign lane_on  = tm_on && (t_oct < {1'b0, active_q});
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
      assign probe_lat_o[u*36 +: 36]          = lat;
      assign probe_frac_o[u*3*LF +: 3*LF]     = frac;
      assign probe_n_o[u*NW +: NW]            = n;
      assign probe_g_o[u*3*NGW +: 3*NGW]      = g;
    end else begin : g_no_probe
      assign probe_lat_o[u*36 +: 36]          = '0;
      assign probe_frac_o[u*3*LF +: 3*LF]     = '0;
      assign probe_n_o[u*NW +: NW]            = '0;
      assign probe_g_o[u*3*NGW +: 3*NGW]      = '0;
    end
  end

  // Probes: the noise results of a pass, at its last step; q at the fragment's last cycle
  // (the serial quadric may finish after the last noise step).
  assign probe_valid_o = DebugProbes & a_valid & nlast;
  assign probe_tag_o   = DebugProbes ? a_tag : '0;
  assign probe_pass_o  = DebugProbes ? 8'(npass) : '0;
  assign probe_q_valid_o = DebugProbes & a_valid & last_cycle;
  assign probe_q_o     = DebugProbes ? q : '0;

  // Accumulation: every cycle adds the lanes' contributions (cycle 0 starts from zero); the
  // last cycle adds q (where the serial quadric has its result) and saturates. The sums are
  // exact, so the order of the terms does not change a bit.
  logic signed [FAccW-1:0] fsum, fout;
  logic [3*GAccW-1:0]      gsum;
  logic [FW-1:0]           f_sat;
  logic [3*GW-1:0]         grad_sat;

  localparam logic signed [FAccW-1:0] FMax = FAccW'({1'b0, {(FW-1){1'b1}}});
  localparam logic signed [FAccW-1:0] FMin = -FMax - 1;
  localparam logic signed [GAccW-1:0] GMax = GAccW'({1'b0, {(GW-1){1'b1}}});
  localparam logic signed [GAccW-1:0] GMin = -GMax - 1;

  always_comb begin
    logic signed [GAccW-1:0] gc, gout;
    fsum = (cyc_q == '0) ? '0 : facc_q;
    for (int u = 0; u < NoiseUnits; u++) fsum = fsum + FAccW'($signed(fterm[u]));
    fout = fsum + FAccW'($signed(q));
    for (int k = 0; k < 3; k++) begin
      gc = (cyc_q == '0) ? '0 : $signed(gacc_q[k*GAccW +: GAccW]);
      for (int u = 0; u < NoiseUnits; u++) gc = gc + GAccW'($signed(gterm[u][k*GW +: GW]));
      gsum[k*GAccW +: GAccW] = gc;
      gout = gc + GAccW'($signed(gradq[k*GW +: GW]));
      // Saturate to the Grad format.
      if (gout > GMax) grad_sat[k*GW +: GW] = GW'(GMax);
      else if (gout < GMin) grad_sat[k*GW +: GW] = GW'(GMin);
      else grad_sat[k*GW +: GW] = GW'(gout);
    end
    // Saturate to the F format.
    if (fout > FMax) f_sat = FW'(FMax);
    else if (fout < FMin) f_sat = FW'(FMin);
    else f_sat = FW'(fout);
  end

  // [B] register: tag, J, f, grad
  localparam int BWidth = 32 + 6 * JW + FW + 3 * GW;
  logic              b_in_valid, b_in_ready;
  logic              b_valid, b_ready;
  logic [BWidth-1:0] b_data;

  assign b_in_valid = a_valid & last_cycle;
  assign a_ready    = last_cycle & b_in_ready;

  always_comb begin
    cyc_d  = cyc_q;
    facc_d = facc_q;
    gacc_d = gacc_q;
    if (advance) begin
      cyc_d  = cyc_q + 1'b1;
      facc_d = fsum;
      gacc_d = gsum;
    end else if (a_valid && b_in_ready) begin
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

  pst_pipe_reg #(.Width(BWidth)) u_reg_b (
    .clk_i, .rst_ni,
    .valid_i (b_in_valid), .ready_o (b_in_ready),
    .data_i  ({grad_sat, f_sat, a_j, a_tag}),
    .valid_o (b_valid), .ready_i (b_ready), .data_o (b_data)
  );

  logic [31:0]     b_tag;
  logic [6*JW-1:0] b_j;
  logic [FW-1:0]   b_f;
  logic [3*GW-1:0] b_grad;
  assign {b_grad, b_f, b_j, b_tag} = b_data;

  // ---------------------------------------------------------------------------------------
  // Filter width -> [C]
  // ---------------------------------------------------------------------------------------
  logic [WW-1:0] b_w;
  logic          b_done;   // W is valid this cycle
  logic          c_in_ready;

  // Datapath = 1: the six products of the dot products take one multiplier, one per cycle
  // (steps 0..5), the euclidean norm 2 + NSq more (pst_filter_width); the fragment leaves [B]
  // at the module's last step (done).
  logic [4:0] wstep_q;
  pst_step_counter #(.Width(5)) u_wstep (
    .clk_i, .rst_ni, .valid_i (b_valid), .done_i (b_done), .ready_i (c_in_ready), .step_o (wstep_q)
  );
  assign b_ready = b_done & c_in_ready;

  pst_filter_width #(
    .GradInt(GradInt), .GradFrac(GradFrac), .JacobianInt(JacobianInt),
    .JacobianFrac(JacobianFrac), .Log2Clut(Log2Clut), .WidthFrac(WidthFrac),
    .FilterNorm(FilterNorm), .Serial(Datapath != 0)
  ) u_width (
    .clk_i, .rst_ni, .step_i (wstep_q), .adv_i (b_valid & ~b_done), .done_o (b_done),
    .grad_i (b_grad), .j_i (b_j), .w_o (b_w)
  );

  localparam int CWidth = 32 + FW + 3 * GW + WW;
  logic              c_valid, c_ready;
  logic [CWidth-1:0] c_data;

  pst_pipe_reg #(.Width(CWidth)) u_reg_c (
    .clk_i, .rst_ni,
    .valid_i (b_valid & b_done), .ready_o (c_in_ready),
    .data_i  ({b_w, b_grad, b_f, b_tag}),
    .valid_o (c_valid), .ready_i (c_ready), .data_o (c_data)
  );

  logic [31:0]     c_tag;
  logic [FW-1:0]   c_f;
  logic [3*GW-1:0] c_grad;
  logic [WW-1:0]   c_w;
  assign {c_w, c_grad, c_f, c_tag} = c_data;

  // ---------------------------------------------------------------------------------------
  // Colour-table filter -> [D] -> out
  // ---------------------------------------------------------------------------------------
  logic [CB4-1:0] c_rgba;
  logic           c_done;     // RGBA is valid this cycle
  logic           d_in_ready;

  // Datapath = 1: one colour channel per cycle (steps 0..3); the fragment leaves [C] at step 3.
  logic [1:0] cstep_q;
  assign c_done = (Datapath == 0) || (cstep_q == 2'd3);
  pst_step_counter #(.Width(2)) u_cstep (
    .clk_i, .rst_ni, .valid_i (c_valid), .done_i (c_done), .ready_i (d_in_ready), .step_o (cstep_q)
  );
  assign c_ready = c_done & d_in_ready;

  pst_clut_filter #(
    .FInt(FInt), .FFrac(FFrac), .Log2Clut(Log2Clut), .ColourBits(ColourBits),
    .WidthFrac(WidthFrac), .FilterRecipFrac(FilterRecipFrac), .Datapath(Datapath)
  ) u_clut (
    .clk_i,
    .we_i    (reg_we_i),
    .addr_i  (reg_addr_i),
    .wdata_i (reg_wdata_i),
    .f_i     (c_f),
    .w_i     (c_w),
    .clamp_i (ctrl_q[0]),
    .kind_i  (ctrl_q[2:1]),
    .rst_ni,
    .step_i  (cstep_q),
    .adv_i   (c_valid & ~c_done),
    .rgba_o  (c_rgba)
  );

  localparam int DWidth = 32 + CB4 + FW + 3 * GW + WW;
  logic [DWidth-1:0] d_data;

  pst_pipe_reg #(.Width(DWidth)) u_reg_d (
    .clk_i, .rst_ni,
    .valid_i (c_valid & c_done), .ready_o (d_in_ready),
    .data_i  ({c_w, c_grad, c_f, c_rgba, c_tag}),
    .valid_o (out_valid_o), .ready_i (out_ready_i), .data_o (d_data)
  );

  assign {out_w_o, out_grad_o, out_f_o, out_rgba_o, out_tag_o} = d_data;

  assign idle_o = ~(a_valid | b_valid | c_valid | out_valid_o);

  // Assertions
`ifndef SYNTHESIS
  // Registers change only between objects, with the pipeline drained.
  assert property (@(posedge clk_i) disable iff (!rst_ni) reg_we_i |-> idle_o);
  // The driver keeps an offered fragment until it is taken (an assumption on the source).
  assert property (@(posedge clk_i) disable iff (!rst_ni)
                   (frag_valid_i && !frag_ready_o) |=> (frag_valid_i && $stable(frag_tag_i)));
  // The cycle counter stays within the fragment's cycles.
  assert property (@(posedge clk_i) disable iff (!rst_ni) 32'(cyc_q) < CycMax);
  // Profile consistency.
  initial begin
    assert (Octaves % NoiseUnits == 0) else $fatal(1, "NoiseUnits must divide Octaves");
    assert (Octaves <= 16) else $fatal(1, "at most 16 octaves (register map)");
    assert (Datapath == 0 || NoiseSteps >= 4) else $fatal(1, "a serial datapath needs NoiseSteps >= 4");
    assert (NoiseSteps == 1 || NoiseSteps == 2 || NoiseSteps == 4 || NoiseSteps == 8)
      else $fatal(1, "NoiseSteps must be 1, 2, 4 or 8");
  end
`endif

endmodule

`default_nettype wire

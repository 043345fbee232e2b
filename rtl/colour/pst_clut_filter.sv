// pst_clut_filter: unit 6 of docs/HARDWARE.md, the colour-table filter of Hart et al. 1999
// section 3.3 (colour-table MIP map, summed-area colour table eq. 13-15 with every edge case).
// Mirrored bit for bit by model/golden/clut_filter_fx.cpp; the double reference whose
// semantics this approximates is model/colormap.cpp (filterSat, filterMip).
//
// Parameters (profile keys, rtl/configs/NAME.toml, through scripts/profile.py):
//   FInt, FFrac      format of f (QFInt.FFrac, signed): width of f_i and of the window ends.
//   Log2Clut         N = 2^Log2Clut table entries (1..11, the register map's ranges): RAM
//                    depths, MIP levels, SAT and count widths, W's integer bits (Log2Clut + 2).
//   ColourBits       bits per RGBA channel (1..8): RAM widths, output width.
//   WidthFrac        fraction bits of W: window-end precision and the MIP blend weight.
//   FilterRecipFrac  RF, fraction bits of the SAT reciprocal ROM: the division's precision.
//   Datapath         parallel: four channel units, rgba_o combinational. serial: one
//                    channel unit, channel c = step_i per cycle (0..3); adv_i stores the
//                    channel, rgba_o is valid at step 3 + Regs (channels 0..2 from registers).
//                    The arithmetic is the same bit for bit; the SAT table needs 3 read ports
//                    instead of 12.
//   Regs             pipeline registers (pst_delay, enabled by en_i; the profile's
//                    pipeline.colour_regs): the first after the table reads, the second after
//                    the SAT sums and the MIP blend (before the division). Parallel: rgba_o
//                    comes Regs advances after f_i, w_i; serial: channel c's reads at step c,
//                    its result at step c + Regs.
//
// Tables: RAMs written through the register port (clk_i, we_i, addr_i, wdata_i); other
// addresses are ignored. Reads are combinational (a later revision may register them).
// Addresses: pst_pkg::RegClut, RegSat, RegMip (docs/HARDWARE.md register map).
//   RegClut + e      clut[e], e < N: RGBA packed, ColourBits each, R at bit 0
//   RegSat + 4e + c  csat[e] channel c: sum of clut[0..e] channel c, ColourBits + Log2Clut bits
//   RegMip + e       MIP levels 1..Log2Clut concatenated: level k entry j at N - (N >> (k-1)) + j
//                    (entry N-1 is writable and never read)
//
// Arithmetic (f_i = f 2^FFrac signed, w_i = W 2^WidthFrac unsigned with W < 4N; u = f N):
//   P = max(WidthFrac + 1, FFrac - Log2Clut): u and W/2 are exact at P fraction bits.
//   iu = floor(u) (FInt + Log2Clut bits, exact, no saturation needed);
//   pidx = clamp ? clamp(iu, 0, N-1) : iu mod N (low Log2Clut bits).
//   kind 0 (none): clut[pidx].
//   kind 1, 2 (MIP): W < 1 gives clut[pidx] (the point sample). Otherwise Lw = position of the
//     leading one of floor(W) (= floor(lg W), 0..Log2Clut+1), Lc = min(Lw, Log2Clut);
//     a = level Lc entry pidx >> Lc (level 0 = clut; level Log2Clut = the single mean entry),
//     b = level min(Lc+1, Log2Clut) entry pidx >> min(Lc+1, Log2Clut) (index by the shifted
//     point index = the paper's clut_i[f / 2^i], extended by mod/clamp at the level's size);
//     t = 0 for kind 1 or Lw >= Log2Clut, else t = W / 2^Lw - 1 = the bits of W below its
//     leading one, exact at TFrac = Log2Clut - 1 + WidthFrac bits. This is the LINEAR
//     approximation of lg W - Lw (the reference blends with lg W - Lw; they differ by at most
//     0.0861 |b - a|, the maximum of lg(1+x) - x).
//     channel = (a 2^TFrac + (b - a) t + 2^(TFrac-1)) >> TFrac (round half up; kind 1 = a).
//   kind 3 (SAT): lo = floor(u - W/2), hi = floor(u + W/2) (exact at P bits); the window
//     covers entries lo+1..hi; count = hi - lo <= ceil(W) <= 4N (CountBits). There is no
//     W < 1 special case (as in the reference filterSat): W = 0 gives count 0 = clut[floor(u)],
//     0 < W < 1 gives entry hi = floor(u + W/2) or the mean of two entries.
//     mod:   [mean]   W >= N: (csat[N-1] + N/2) >> Log2Clut (the paper's "w >= N" rule;
//                     same as the reference);
//            [entry]  count = 0: clut[hi mod N];
//            [inside] / [wrap] with hm = hi mod N, lm = lo mod N:
//                     sum = csat[hm] - csat[lm] + (hm <= lm ? csat[N-1] : 0). hm > lm is the
//                     whole-window-inside case (eq. 15); hm <= lm is either of the paper's two
//                     mod edge cases (csat[f+w/2-N] + csat[N-1] - csat[f-w/2-1] and
//                     csat[f+w/2] + csat[N-1] - csat[N+f-w/2-1]), one formula in modular
//                     indices; lm = N-1 stands for csat[-1] = 0; count = N (hm = lm) is the
//                     whole table. count <= N here because W < N.
//     clamp: [entry]  count = 0, or lo >= N-1 (window entirely past the top), or hi < 0
//                     (entirely past the bottom): clut[clamp(hi, 0, N-1)];
//            [inside] csat[hi] - csat[lo] (csat[-1] = 0);
//            [above]  hi >= N:  (hi - (N-1)) clut[N-1] + csat[N-1] - csat[lo];
//            [below]  lo < -1:  -(lo+1) clut[0] + csat[hi];
//            [both]   both extension terms: -(lo+1) clut[0] + csat[N-1] + (hi - (N-1)) clut[N-1].
//                     lo and hi may lie anywhere in f's range (they are exact at IW bits) and
//                     need no clamping: the windows entirely outside are the [entry] case, and
//                     every extension count used is <= count <= 4N (below: -(lo+1) <= hi - lo
//                     as hi >= 0; above: hi - (N-1) <= hi - lo as lo <= N-2), so the counts
//                     are taken exactly at CountBits bits. Results are exact sums for any f.
//     Sums are held at SumBits = ColourBits + Log2Clut + 2 bits (enough for tables built by
//     the driver; arbitrary RAM contents wrap, and the golden model wraps the same way).
//     channel = min(2^ColourBits - 1, (sum recip[count] + 2^(RF-1)) >> RF),
//     recip[c] = round(2^RF / c) (ROM, c = 1..4N). Error against the exact sum / count:
//     <= 1/2 + (sum / count) |c recip[c] - 2^RF| / 2^RF (final rounding + reciprocal).
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_clut_filter #(
  `PST_CLUT_FILTER_PARAMS,
  parameter int Regs            = 0,
  localparam int FW  = FInt + FFrac,              // f
  localparam int WW  = pst_pkg::w_width(Log2Clut, WidthFrac),  // W = w N in entries, < 4N
  localparam int CB4 = 4 * ColourBits,            // packed RGBA
  localparam int AB  = pst_pkg::RegAddrBits,
  localparam int DB  = pst_pkg::RegDataBits,
  localparam int KB  = pst_pkg::RegControlKindWidth,  // filter kind
  localparam int SB  = $clog2(pst_pkg::ColourSteps + Regs)   // serial step 0 .. 3 + Regs
) (
  input  logic           clk_i,
  // Table write port (register map; other addresses are ignored).
  input  logic           we_i,
  input  logic [AB-1:0]  addr_i,
  input  logic [DB-1:0]  wdata_i,
  // Filter input: colour index f, width W, wrap mode (0 mod, 1 clamp), kind.
  input  logic [FW-1:0]  f_i,
  input  logic [WW-1:0]  w_i,
  input  logic           clamp_i,
  input  logic [KB-1:0]  kind_i,
  // Datapath = 1: the channel of this cycle and "store it" (unused when Datapath = 0).
  input  logic           rst_ni,
  input  logic [SB-1:0]  step_i,
  input  logic           adv_i,
  input  logic           en_i,    // Regs > 0: the pipeline registers advance
  output logic [CB4-1:0] rgba_o
);

  // ---------------------------------------------------------------------------------------
  // Derived widths
  // ---------------------------------------------------------------------------------------
  localparam int N         = 1 << Log2Clut;
  localparam int CB        = ColourBits;
  localparam int RF        = FilterRecipFrac;
  // Common fraction bits of u = f N and W/2 (both exact there).
  localparam int P         = (WidthFrac + 1 > FFrac - Log2Clut) ? WidthFrac + 1 : FFrac - Log2Clut;
  localparam int UShift    = Log2Clut - FFrac + P;   // f -> u at P bits: left shift (>= 0)
  localparam int HShift    = P - WidthFrac - 1;      // W -> W/2 at P bits: left shift (>= 0)
  localparam int UW        = FW + UShift;            // u at P bits, signed
  localparam int HW        = WW + HShift;            // W/2 at P bits, unsigned
  localparam int EW        = ((UW > HW + 1) ? UW : HW + 1) + 1;  // u -+ W/2, signed, no overflow
  localparam int IUW       = UW - P;                 // floor(u) = FInt + Log2Clut bits, signed
  localparam int IW        = EW - P;                 // lo, hi, signed
  localparam int CountBits = Log2Clut + 3;           // count <= ceil(W) <= 4N
  localparam int SatBits   = ColourBits + Log2Clut;  // csat[N-1] <= N (2^CB - 1)
  localparam int RecipBits = FilterRecipFrac + 1;    // recip[1] = 2^RF
  localparam int TFrac     = Log2Clut - 1 + WidthFrac;  // blend weight: W / 2^Lw - 1, exact for Lw < Log2Clut
  localparam int LW        = $clog2(Log2Clut + 2);      // level / leading-one index 0..Log2Clut+1
  localparam int RomDepth  = 4 * N + 1;                // recip[0..4N]
  // Filter kinds (control register) and the serial channel steps.
  localparam logic [KB-1:0] KindMipBlended = KB'(pst_pkg::FilterKindMipBlended);
  localparam logic [KB-1:0] KindSat        = KB'(pst_pkg::FilterKindSat);
  localparam logic [SB-1:0] LastStep       = SB'(pst_pkg::ColourSteps - 1 + Regs);
  localparam int R0 = (Regs > 0) ? 1 : 0;   // after the table reads
  localparam int R1 = (Regs > 1) ? 1 : 0;   // after the sums and the blend

  // ---------------------------------------------------------------------------------------
  // Table RAMs and the write decoder
  // ---------------------------------------------------------------------------------------
  logic [CB4-1:0]     clut_q [N];
  localparam int SatStrideBits = $clog2(pst_pkg::RegSatStride);   // channels per SAT entry
  logic [SatBits-1:0] sat_q  [4*N];   // index {e, c}
  logic [CB4-1:0]     mip_q  [N];

  logic sel_clut, sel_sat, sel_mip;
  assign sel_clut = addr_i[AB-1:Log2Clut] == (AB - Log2Clut)'(pst_pkg::RegClut >> Log2Clut);
  assign sel_sat  = addr_i[AB-1:Log2Clut+SatStrideBits] ==
                    (AB - Log2Clut - SatStrideBits)'(pst_pkg::RegSat >> (Log2Clut + SatStrideBits));
  assign sel_mip  = addr_i[AB-1:Log2Clut] == (AB - Log2Clut)'(pst_pkg::RegMip >> Log2Clut);

  // Data bits above the RAM widths are ignored (used only when ColourBits = 8).
  logic unused_wdata;
  assign unused_wdata = ^wdata_i;

  always_ff @(posedge clk_i) begin
    if (we_i && sel_clut) clut_q[addr_i[Log2Clut-1:0]] <= wdata_i[CB4-1:0];
    if (we_i && sel_sat)  sat_q[addr_i[Log2Clut+SatStrideBits-1:0]] <= wdata_i[SatBits-1:0];
    if (we_i && sel_mip)  mip_q[addr_i[Log2Clut-1:0]]  <= wdata_i[CB4-1:0];
  end

  // Reciprocal ROM: recip[c] = round(2^RF / c) = floor((2^(RF+1) + c) / 2c); recip[0] unused.
  // A memory with an initial image (a ROM to synthesis: counted as ROM bits, not logic).
  logic [RecipBits-1:0] recip_rom [RomDepth];
  initial begin
    recip_rom[0] = '0;
    for (int c = 1; c < RomDepth; c++) begin
      recip_rom[c] = RecipBits'(((64'd1 << (RF + 1)) + 64'(c)) / (64'd2 * 64'(c)));
    end
  end

  // ---------------------------------------------------------------------------------------
  // u = f N, point index
  // ---------------------------------------------------------------------------------------
  logic signed [UW-1:0]  u_p;    // u at P fraction bits
  logic signed [IUW-1:0] iu;     // floor(u)
  logic [Log2Clut-1:0]   pidx;   // point index (mod / clamp)

  assign u_p = UW'($signed(f_i)) <<< UShift;
  assign iu  = IUW'(u_p >>> P);

  always_comb begin
    if (!clamp_i) begin
      pidx = iu[Log2Clut-1:0];
    end else if (iu < 0) begin
      pidx = '0;
    end else if (iu > $signed(IUW'(N - 1))) begin
      pidx = '1;
    end else begin
      pidx = iu[Log2Clut-1:0];
    end
  end

  // ---------------------------------------------------------------------------------------
  // SAT window ends and indices
  // ---------------------------------------------------------------------------------------
  logic [HW-1:0]          hw_p;        // W/2 at P fraction bits
  logic signed [EW-1:0]   lo_p, hi_p;  // u -+ W/2
  logic signed [IW-1:0]   lo, hi;      // floor of them
  logic [CountBits-1:0]   count;
  logic [Log2Clut-1:0]    hm, lm;      // hi, lo mod N
  logic [Log2Clut-1:0]    hidx;        // clamp: clamp(hi, 0, N-1); mod: hi mod N
  logic                   w_ge_n;      // W >= N
  logic                   mod_wrap;    // mod: window wraps (hm <= lm)
  logic                   cl_entry;    // clamp: window sees one entry
  logic                   cl_below, cl_above;
  logic [CountBits-1:0]   nb, na;      // clamp: extension counts below / above

  assign hw_p = HW'(w_i) << HShift;
  assign lo_p = EW'(u_p) - $signed(EW'(hw_p));
  assign hi_p = EW'(u_p) + $signed(EW'(hw_p));
  assign lo   = IW'(lo_p >>> P);
  assign hi   = IW'(hi_p >>> P);
  assign count = CountBits'(hi - lo);
  assign hm   = hi[Log2Clut-1:0];
  assign lm   = lo[Log2Clut-1:0];
  assign w_ge_n   = |w_i[WW-1:WidthFrac+Log2Clut];
  assign mod_wrap = hm <= lm;

  always_comb begin
    if (!clamp_i) begin
      hidx = hm;
    end else if (hi < 0) begin
      hidx = '0;
    end else if (hi > $signed(IW'(N - 1))) begin
      hidx = '1;
    end else begin
      hidx = hm;
    end
  end

  assign cl_entry = (count == '0) || (lo >= $signed(IW'(N - 1))) || (hi < 0);
  assign cl_below = lo < $signed(IW'(-1));
  assign cl_above = hi > $signed(IW'(N - 1));
  assign nb = cl_below ? CountBits'(~lo) : '0;                      // -(lo + 1)
  assign na = cl_above ? CountBits'(hi - $signed(IW'(N - 1))) : '0;  // hi - (N - 1)

  // ---------------------------------------------------------------------------------------
  // Table reads
  // ---------------------------------------------------------------------------------------
  logic [Log2Clut-1:0] clut_addr;
  logic [CB4-1:0]      clut_e, clut_first, clut_last;
  assign clut_addr  = (kind_i == KindSat) ? hidx : pidx;
  assign clut_e     = clut_q[clut_addr];
  assign clut_first = clut_q[0];
  assign clut_last  = clut_q[N-1];

  // MIP level selection: leading one of floor(W).
  logic [Log2Clut+1:0] w_int;
  logic [LW-1:0]       lw, lc, lb;
  logic                mip_point;
  assign w_int     = w_i[WW-1:WidthFrac];
  assign mip_point = (w_int == '0);
  always_comb begin
    lw = '0;
    for (int i = 0; i < Log2Clut + 2; i++) begin
      if (w_int[i]) lw = LW'(i);
    end
  end
  assign lc = (lw > LW'(Log2Clut)) ? LW'(Log2Clut) : lw;
  assign lb = (lc >= LW'(Log2Clut)) ? LW'(Log2Clut) : lc + LW'(1);

  // Level k >= 1 entry j lives at N - (N >> (k-1)) + j = 2N - (2N >> k) + j.
  logic [Log2Clut-1:0] base_a, base_b;   // < N - 1
  logic [Log2Clut-1:0] mip_addr_a, mip_addr_b;
  logic [CB4-1:0]      lev_a, lev_b;
  assign base_a     = Log2Clut'((Log2Clut + 2)'(2 * N) - ((Log2Clut + 2)'(2 * N) >> lc));
  assign base_b     = Log2Clut'((Log2Clut + 2)'(2 * N) - ((Log2Clut + 2)'(2 * N) >> lb));
  assign mip_addr_a = base_a + (pidx >> lc);
  assign mip_addr_b = base_b + (pidx >> lb);
  assign lev_a      = (lc == '0) ? clut_e : mip_q[mip_addr_a];
  assign lev_b      = mip_q[mip_addr_b];

  // Blend weight: the bits of W below its leading one, left-aligned to TFrac bits.
  logic [TFrac-1:0] t;
  always_comb begin
    t = '0;
    if (kind_i == KindMipBlended && lw < LW'(Log2Clut)) begin
      t = TFrac'(TFrac'(w_i) << (LW'(Log2Clut - 1) - lw));
    end
  end

  logic [RecipBits-1:0] recip;
  assign recip = recip_rom[count];

  // ---------------------------------------------------------------------------------------
  // Per channel (pst_clut_channel): MIP blend, SAT sum and division, output select. Lanes = 4
  // (parallel, lane = channel) or 1 (serial, channel = step_i).
  // ---------------------------------------------------------------------------------------
  localparam int Lanes = (Datapath == pst_pkg::DatapathParallel) ? pst_pkg::ColourSteps : 1;
  logic [Lanes*CB-1:0] lane_out;

  // Shared values past the registers: _1 after the first, _2 after the second.
  localparam int ShW1 = TFrac + RecipBits + 2 * CountBits + 7 + KB;
  logic [TFrac-1:0]     t_1;
  logic [RecipBits-1:0] recip_1, recip_2;
  logic [CountBits-1:0] nb_1, na_1;
  logic                 clamp_1, w_ge_n_1, mod_wrap_1, cl_entry_1, count0_1, lo_neg_1, mip_point_1;
  logic                 clamp_2, w_ge_n_2, cl_entry_2, count0_2, mip_point_2;
  logic [KB-1:0]        kind_1, kind_2;
  pst_delay #(.Width(ShW1), .Depth(R0)) u_sh1 (
    .clk_i, .rst_ni, .en_i,
    .d_i ({t, recip, nb, na, clamp_i, w_ge_n, mod_wrap, cl_entry, count == '0, lo < 0, mip_point,
           kind_i}),
    .q_o ({t_1, recip_1, nb_1, na_1, clamp_1, w_ge_n_1, mod_wrap_1, cl_entry_1, count0_1, lo_neg_1,
           mip_point_1, kind_1})
  );
  localparam int ShW2 = RecipBits + 5 + KB;
  pst_delay #(.Width(ShW2), .Depth(R1)) u_sh2 (
    .clk_i, .rst_ni, .en_i,
    .d_i ({recip_1, clamp_1, w_ge_n_1, cl_entry_1, count0_1, mip_point_1, kind_1}),
    .q_o ({recip_2, clamp_2, w_ge_n_2, cl_entry_2, count0_2, mip_point_2, kind_2})
  );

  for (genvar l = 0; l < Lanes; l++) begin : g_ch
    logic [1:0] ch;   // the channel of this lane
    assign ch = (Datapath == pst_pkg::DatapathParallel) ? 2'(l) : 2'(step_i);
    // The reads of this channel (before the first register); SAT: csat at the high end
    // (hidx), the low end (lo mod N) and N-1.
    pst_clut_channel #(`PST_CLUT_CHANNEL_PASS, .Regs(Regs)) u_channel (
      .clk_i, .rst_ni, .en_i,
      .a_i           (CB'(lev_a >> (ch * CB))),
      .b_i           (CB'(lev_b >> (ch * CB))),
      .first_i       (CB'(clut_first >> (ch * CB))),
      .last_i        (CB'(clut_last >> (ch * CB))),
      .entry_i       (CB'(clut_e >> (ch * CB))),
      .sh_i          (sat_q[{hidx, ch}]),
      .sl_i          (sat_q[{lm, ch}]),
      .sn_i          (sat_q[{Log2Clut'(N - 1), ch}]),
      .t_1_i         (t_1),
      .nb_1_i        (nb_1),
      .na_1_i        (na_1),
      .clamp_1_i     (clamp_1),
      .mod_wrap_1_i  (mod_wrap_1),
      .lo_neg_1_i    (lo_neg_1),
      .recip_2_i     (recip_2),
      .clamp_2_i     (clamp_2),
      .w_ge_n_2_i    (w_ge_n_2),
      .cl_entry_2_i  (cl_entry_2),
      .count0_2_i    (count0_2),
      .mip_point_2_i (mip_point_2),
      .kind_2_i      (kind_2),
      .ch_o          (lane_out[l*CB +: CB])
    );
  end

  if (Datapath == pst_pkg::DatapathParallel) begin : g_out_par
    assign rgba_o = lane_out;
    logic unused_serial;
    assign unused_serial = ^{step_i, adv_i};
  end else begin : g_out_ser
    // Channels 0..2 stored as they come out (step c + Regs); channel 3 is live at the last step.
    logic [3*CB-1:0] ch_q;
    logic [SB:0]     out_ch;   // the channel at the output: step - Regs (negative: none yet)
    assign out_ch = {1'b0, step_i} - (SB + 1)'(Regs);
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) ch_q <= '0;
      else if (adv_i && !out_ch[SB] && step_i != LastStep) ch_q[2'(out_ch)*CB +: CB] <= lane_out;
    end
    assign rgba_o = {lane_out, ch_q};
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    if (Log2Clut < 1 || Log2Clut > 11) $error("pst_clut_filter: Log2Clut must be 1..11");
    if (ColourBits < 1 || ColourBits > 8) $error("pst_clut_filter: ColourBits must be 1..8");
    if (FilterRecipFrac < 1 || FilterRecipFrac > 40) $error("pst_clut_filter: FilterRecipFrac must be 1..40");
    if (TFrac < 1) $error("pst_clut_filter: Log2Clut - 1 + WidthFrac must be >= 1");
  end
  // The window is never wider than ceil(W) <= 4N entries (the ROM's depth).
  assert property (@(posedge clk_i) (kind_i == KindSat) |-> (count <= CountBits'(4 * N)));
  // The point index is inside the table in clamp mode whatever f is.
  assert property (@(posedge clk_i) (clamp_i && iu < 0) |-> (pidx == '0));
  // In mod mode below W = N the window covers at most N entries.
  assert property (@(posedge clk_i) (kind_i == KindSat && !clamp_i && !w_ge_n) |-> (count <= CountBits'(N)));
`endif

endmodule

`default_nettype wire

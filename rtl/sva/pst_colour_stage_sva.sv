// pst_colour_stage_sva: checker of pst_colour_stage. Assertions: the handshake at the output
// (pst_handshake_sva: RGBA and the side payload held while refused); the control register (kind, wrap) steady while a fragment is in the
// stage. Cover points, per fragment entering the colour-table filter: every filter kind x
// wrap x W case (W < 1, 1 <= W < N, W >= N: 24 points), the summed-area table's cases of
// pst_clut_filter's header (mod: mean, entry, inside, wrap, the whole table; clamp: entry with
// count 0, window past the top, past the bottom, inside, above, below, both), the widest
// window (4N entries), the MIP top level and a blended level; serial: every channel step.
// Bound with pst_clut_filter's decode of the entering fragment (u_clut.*).
`include "sva/pst_assert.svh"
`include "pst_pkg.sv"
`default_nettype none

module pst_colour_stage_sva #(
  parameter int  Log2Clut   = 1,
  parameter int  WidthFrac  = 0,
  parameter int  WW         = 4,
  parameter int  CB4        = 4,
  parameter int  SideW      = 1,
  parameter int  KB         = 2,
  parameter int  SB         = 1,
  parameter bit  Serial     = 1'b0,
  parameter int  ColourRegs = 0
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             clamp_i,
  input logic [KB-1:0]    kind_i,
  input logic             valid_i,
  input logic             ready_o,
  input logic [WW-1:0]    w_i,
  input logic             valid_o,
  input logic             ready_i,
  input logic [CB4-1:0]   rgba_o,
  input logic [SideW-1:0] side_o,
  input logic             busy_o,
  input logic [SB-1:0]    step_q,
  // pst_clut_filter's decode of f_i, w_i (the fragment entering it)
  input logic             cnt0,       // count = 0
  input logic             widest,     // count = 4N
  input logic             w_ge_n,
  input logic             mod_wrap,
  input logic             whole,      // hi = lo mod N
  input logic             hi_neg,     // hi < 0
  input logic             cl_entry,
  input logic             cl_below,
  input logic             cl_above,
  input logic             mip_top,    // floor(lg W) >= Log2Clut
  input logic             mip_t       // blend weight t != 0
);
  localparam int N = 1 << Log2Clut;
  logic take;     // a fragment enters the filter's datapath (its decode is valid)
  logic w_lt_1, w_mid;
  assign take   = valid_i && ready_o;
  assign w_lt_1 = 32'(w_i) < (1 << WidthFrac);
  assign w_mid  = !w_lt_1 && !w_ge_n;

  pst_handshake_sva #(.Width(CB4 + SideW)) u_out (
    .clk_i, .rst_ni, .valid_i (valid_o), .ready_i, .data_i ({rgba_o, side_o}));
  `PST_ASSERT(ControlSteadyInFlight, (valid_i || busy_o) |=> ($stable(kind_i) && $stable(clamp_i)))
  `PST_ASSERT(WGeNMatchesW, w_ge_n == (32'(w_i) >= (N << WidthFrac)))
  `PST_ASSERT_KNOWN(ReadyKnown, ready_o)

  // Filter kind x wrap x W.
  for (genvar k = 0; k < 4; k++) begin : g_kind
    for (genvar c = 0; c < 2; c++) begin : g_wrap
      logic sel;
      assign sel = take && kind_i == KB'(k) && clamp_i == c[0];
      `PST_COVER(WBelowOne, sel && w_lt_1)
      `PST_COVER(WInside, sel && w_mid)
      `PST_COVER(WAtLeastN, sel && w_ge_n)
    end
  end

  // The summed-area table's cases.
  logic sat, sat_mod, sat_cl;
  assign sat     = take && kind_i == KB'(pst_pkg::FilterKindSat);
  assign sat_mod = sat && !clamp_i;
  assign sat_cl  = sat && clamp_i;
  `PST_COVER(SatModMean, sat_mod && w_ge_n)
  `PST_COVER(SatModEntry, sat_mod && !w_ge_n && cnt0)
  `PST_COVER(SatModInside, sat_mod && !w_ge_n && !cnt0 && !mod_wrap)
  `PST_COVER(SatModWrap, sat_mod && !w_ge_n && !cnt0 && mod_wrap && !whole)
  `PST_COVER(SatModWholeTable, sat_mod && !w_ge_n && !cnt0 && whole)
  `PST_COVER(SatClampEntryZero, sat_cl && cnt0)
  `PST_COVER(SatClampPastTop, sat_cl && !cnt0 && cl_entry && !hi_neg)
  `PST_COVER(SatClampPastBottom, sat_cl && !cnt0 && hi_neg)
  `PST_COVER(SatClampInside, sat_cl && !cl_entry && !cl_below && !cl_above)
  `PST_COVER(SatClampAbove, sat_cl && !cl_entry && !cl_below && cl_above)
  `PST_COVER(SatClampBelow, sat_cl && !cl_entry && cl_below && !cl_above)
  `PST_COVER(SatClampBoth, sat_cl && !cl_entry && cl_below && cl_above)
  `PST_COVER(SatWidestWindow, sat && widest)
  // MIP: the top level (a single entry, the table's mean) and a blended level below it.
  logic mip;
  assign mip = take && (kind_i == KB'(pst_pkg::FilterKindMip) ||
                        kind_i == KB'(pst_pkg::FilterKindMipBlended)) && !w_lt_1;
  `PST_COVER(MipTopLevel, mip && mip_top)
  `PST_COVER(MipBlend, mip && kind_i == KB'(pst_pkg::FilterKindMipBlended) && !mip_top && mip_t)

  if (Serial) begin : g_serial
    for (genvar c = 0; c < pst_pkg::ColourSteps + ColourRegs; c++) begin : g_step
      `PST_COVER(ChannelStep, valid_i && step_q == SB'(c))
    end
  end else begin : g_parallel
    logic unused;
    assign unused = ^step_q;
  end
endmodule

bind pst_colour_stage pst_colour_stage_sva #(
  .Log2Clut(Log2Clut), .WidthFrac(WidthFrac), .WW(WW), .CB4(CB4), .SideW(SideW), .KB(KB),
  .SB(SB), .Serial(Serial), .ColourRegs(ColourRegs)
) u_sva (
  .clk_i, .rst_ni, .clamp_i, .kind_i, .valid_i, .ready_o, .w_i, .valid_o, .ready_i, .rgba_o,
  .side_o, .busy_o, .step_q,
  .cnt0     (u_clut.count == '0),
  .widest   (32'(u_clut.count) == 4 * (1 << Log2Clut)),
  .w_ge_n   (u_clut.w_ge_n),
  .mod_wrap (u_clut.mod_wrap),
  .whole    (u_clut.hm == u_clut.lm),
  .hi_neg   (u_clut.hi < 0),
  .cl_entry (u_clut.cl_entry),
  .cl_below (u_clut.cl_below),
  .cl_above (u_clut.cl_above),
  .mip_top  (32'(u_clut.lw) >= Log2Clut),
  .mip_t    (u_clut.t != '0));

`default_nettype wire

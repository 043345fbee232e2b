// pst_clut_filter_sva: checker of pst_clut_filter's table port and decode: one table per
// write, the point index inside the table in clamp mode, the clamp extensions within the
// window, the MIP levels in range. Cover points: a write to each table (colour table, SAT,
// MIP levels) and to the colour table's last entry. These hold for any input, so they are
// checked every cycle (the filter has no valid of its own).
`include "sva/pst_assert.svh"
`include "pst_pkg.sv"
`default_nettype none

module pst_clut_filter_sva #(
  parameter int Log2Clut  = 1,
  parameter int KB        = 2,
  parameter int IUW       = 2,
  parameter int CountBits = 2,
  parameter int LW        = 2
) (
  input logic                            clk_i,
  input logic                            rst_ni,
  input logic                            we_i,
  input logic [Log2Clut-1:0]             addr_lo,   // addr_i's entry bits
  input logic                            clamp_i,
  input logic [KB-1:0]                   kind_i,
  input logic                            sel_clut,
  input logic                            sel_sat,
  input logic                            sel_mip,
  input logic signed [IUW-1:0]           iu,
  input logic [Log2Clut-1:0]             pidx,
  input logic [CountBits-1:0]            count,
  input logic                            w_ge_n,
  input logic                            cl_entry,
  input logic [CountBits-1:0]            nb,
  input logic [CountBits-1:0]            na,
  input logic [LW-1:0]                   lc,
  input logic [LW-1:0]                   lb
);
  localparam int N = 1 << Log2Clut;
  logic sat;
  assign sat = kind_i == KB'(pst_pkg::FilterKindSat);

  `PST_ASSERT(OneTablePerWrite, we_i |-> ($countones({sel_clut, sel_sat, sel_mip}) <= 1))
  `PST_ASSERT(ClampPointLow, (clamp_i && iu < 0) |-> (pidx == '0))
  `PST_ASSERT(ClampPointHigh, (clamp_i && iu > $signed(IUW'(N - 1))) |-> (pidx == Log2Clut'(N - 1)))
  `PST_ASSERT(SatCountInRom, sat |-> (32'(count) <= 4 * N))
  `PST_ASSERT(ModCountAtMostN, (sat && !clamp_i && !w_ge_n) |-> (32'(count) <= N))
  `PST_ASSERT(ClampExtInWindow, (sat && clamp_i && !cl_entry) |-> (nb <= count && na <= count))
  `PST_ASSERT(MipLevels, (32'(lc) <= Log2Clut) && (lb == lc + LW'(1) || 32'(lb) == Log2Clut))

  `PST_COVER(WriteClut, we_i && sel_clut)
  `PST_COVER(WriteSat, we_i && sel_sat)
  `PST_COVER(WriteMip, we_i && sel_mip)
  `PST_COVER(WriteClutLast, we_i && sel_clut && addr_lo == Log2Clut'(N - 1))
endmodule

bind pst_clut_filter pst_clut_filter_sva #(
  .Log2Clut(Log2Clut), .KB(KB), .IUW(IUW), .CountBits(CountBits), .LW(LW)
) u_sva (.*, .addr_lo (addr_i[Log2Clut-1:0]));

`default_nettype wire

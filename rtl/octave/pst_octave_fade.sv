// Octave fade (bandlimited octaves, filter.bandlimit = isotropic; docs/HARDWARE.md unit 4):
// the weight alpha of one octave's term in one pixel. Combinational. Golden model:
// octaveFadeFx in model/golden/arith_fx.cpp (bit for bit); the reference's exact form is
// octaveIsotropic in model/texture.cpp.
//
//   lg nu_x = lgx_i + lgm_i           the footprint's x edge in lattice cells, bounded by
//                                     ||M||_2 |dsdx| (lgm_i = lg ||M||_2, the octave's register;
//                                     lgx_i from pst_fade_lg), FadeLgFrac fraction bits
//   idx_x   = clamp(floor((lg nu_x + FadeLgLo) 4), 0, FadeEntries - 1)   (a quarter octave each)
//   alpha_o = min(floor(h[idx_x] h[idx_y] / 2^FadeFrac), 2^FadeFrac)     (h: the fade table)
// en_i = 0 (the texture's control.bandlimit off): alpha_o = 2^FadeFrac (the term whole).
//
// Parameters:
//   LgW   width of lgx_i, lgy_i (signed; pst_fade_lg's LgW).
`include "pst_pkg.sv"
`default_nettype none

module pst_octave_fade #(
  parameter int LgW = 9,
  localparam int FB  = pst_pkg::FadeBits,
  localparam int FE  = pst_pkg::FadeEntries,
  localparam int LMW = pst_pkg::FadeLgBits,
  localparam int SW  = ((LgW > LMW) ? LgW : LMW) + 2   // lg nu + the table's offset, signed
) (
  input  logic              en_i,
  input  logic [LgW-1:0]    lgx_i,
  input  logic [LgW-1:0]    lgy_i,
  input  logic [LMW-1:0]    lgm_i,
  input  logic [FE*FB-1:0]  table_i,   // entry k at [k*FB +: FB]
  output logic [FB-1:0]     alpha_o
);

  localparam int IB = $clog2(FE);
  localparam logic signed [SW-1:0] Lo = SW'(pst_pkg::FadeLgLo << pst_pkg::FadeLgFrac);

  function automatic logic [IB-1:0] index(input logic [LgW-1:0] lg, input logic [LMW-1:0] lgm);
    logic signed [SW-1:0] t, q;
    t = SW'($signed(lg)) + SW'($signed(lgm)) + Lo;
    q = t >>> (pst_pkg::FadeLgFrac - 2);
    if (q < 0) index = '0;
    else if (q > SW'(FE - 1)) index = IB'(FE - 1);
    else index = q[IB-1:0];
  endfunction

  logic [IB-1:0]   ix, iy;
  logic [FB-1:0]   hx, hy;
  logic [2*FB-1:0] prod;
  logic [2*FB-1:0] a;
  assign ix   = index(lgx_i, lgm_i);
  assign iy   = index(lgy_i, lgm_i);
  assign hx   = table_i[ix*FB +: FB];
  assign hy   = table_i[iy*FB +: FB];
  assign prod = (2*FB)'(hx) * (2*FB)'(hy);
  assign a    = prod >> pst_pkg::FadeFrac;
  assign alpha_o = !en_i ? FB'(1 << pst_pkg::FadeFrac)
                 : (a > (2*FB)'(1 << pst_pkg::FadeFrac)) ? FB'(1 << pst_pkg::FadeFrac) : a[FB-1:0];

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (pst_pkg::FadeLgFrac >= 2) else $error("pst_octave_fade: FadeLgFrac must be >= 2 (quarter octaves)");
    assert (FB == pst_pkg::FadeFrac + 1) else $error("pst_octave_fade: an entry holds 1.0");
  end
`endif

endmodule

`default_nettype wire

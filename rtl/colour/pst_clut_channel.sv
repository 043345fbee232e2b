// pst_clut_channel: one channel of the colour-table filter (part of rtl/colour/pst_clut_filter.sv,
// unit 6 of docs/HARDWARE.md): the MIP blend, the SAT sum and its division, and the output
// select, from the table entries pst_clut_filter read for this channel.
// Golden: model/golden/clut_filter_fx.cpp (the same steps, bit for bit).
//
//   MIP:  channel = (a 2^TFrac + (b - a) t + 2^(TFrac-1)) >> TFrac (round half up of the lerp
//         of level entries a, b by t; it lies between a and b).
//   SAT:  mod   sum = csat[hm] - csat[lm] + (hm <= lm ? csat[N-1] : 0);
//         clamp sum = nb clut[0] + csat[hi] - (lo < 0 ? 0 : csat[lo]) + na clut[N-1];
//         channel = min(2^ColourBits - 1, (sum recip[count] + 2^(RF-1)) >> RF); the mean
//         (csat[N-1] + N/2) >> Log2Clut when W >= N (mod); the entry when the window sees one.
//   The cases and why the widths hold: pst_clut_filter's header.
//
// Pipeline: the reads come before the first register (Regs > 0), the sums and the blend before
// the second (Regs > 1); the shared values arrive already delayed (_1: after the first, _2:
// after the second register), as pst_clut_filter registers them once for every channel.
//
// Parameters (pst_clut_filter's):
//   Log2Clut         N = 2^Log2Clut entries: SAT and count widths, the mean's shift
//   ColourBits       bits of a channel: entry, sum and product widths
//   WidthFrac        fraction bits of W: the blend weight's width (TFrac)
//   FilterRecipFrac  RF: the reciprocal's fraction bits (the division's precision)
//   Regs             pipeline registers (0..2, above)
//
// Ports:
//   a_i, b_i, first_i, last_i, entry_i  this channel of MIP level entries a, b, clut[0],
//                                        clut[N-1] and the point (or SAT end) entry
//   sh_i, sl_i, sn_i                     csat at the high end, the low end and N-1
//   t_1_i, nb_1_i, na_1_i, clamp_1_i, mod_wrap_1_i, lo_neg_1_i   after the first register
//   recip_2_i, clamp_2_i, w_ge_n_2_i, cl_entry_2_i, count0_2_i, mip_point_2_i, kind_2_i
//                                        after the second register
//   ch_o                                 the filtered channel
`include "pst_pkg.sv"
`include "pst_params.svh"
`default_nettype none

module pst_clut_channel #(
  `PST_CLUT_CHANNEL_PARAMS,
  parameter int Regs            = 0,
  localparam int CB        = ColourBits,
  localparam int KB        = pst_pkg::RegControlKindWidth,  // filter kind
  localparam int CountBits = Log2Clut + 3,                  // count <= ceil(W) <= 4N
  localparam int SatBits   = ColourBits + Log2Clut,         // csat[N-1] <= N (2^CB - 1)
  localparam int RecipBits = FilterRecipFrac + 1,           // recip[1] = 2^RF
  localparam int TFrac     = Log2Clut - 1 + WidthFrac       // blend weight
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 en_i,
  input  logic [CB-1:0]        a_i,
  input  logic [CB-1:0]        b_i,
  input  logic [CB-1:0]        first_i,
  input  logic [CB-1:0]        last_i,
  input  logic [CB-1:0]        entry_i,
  input  logic [SatBits-1:0]   sh_i,
  input  logic [SatBits-1:0]   sl_i,
  input  logic [SatBits-1:0]   sn_i,
  input  logic [TFrac-1:0]     t_1_i,
  input  logic [CountBits-1:0] nb_1_i,
  input  logic [CountBits-1:0] na_1_i,
  input  logic                 clamp_1_i,
  input  logic                 mod_wrap_1_i,
  input  logic                 lo_neg_1_i,
  input  logic [RecipBits-1:0] recip_2_i,
  input  logic                 clamp_2_i,
  input  logic                 w_ge_n_2_i,
  input  logic                 cl_entry_2_i,
  input  logic                 count0_2_i,
  input  logic                 mip_point_2_i,
  input  logic [KB-1:0]        kind_2_i,
  output logic [CB-1:0]        ch_o
);

  localparam int N        = 1 << Log2Clut;
  localparam int RF       = FilterRecipFrac;
  localparam int SumBits  = ColourBits + Log2Clut + 2;   // sum <= count (2^CB - 1) < 4N 2^CB
  localparam int ProdBits = SumBits + RecipBits;         // sum * recip, exact
  localparam int QBits    = ProdBits - FilterRecipFrac + 1;  // rounded quotient (+1: carry)
  localparam int AccW     = ColourBits + TFrac + 2;      // a 2^TFrac + (b - a) t, signed
  localparam logic [CB-1:0] MaxC = {CB{1'b1}};
  localparam logic [KB-1:0] KindNone       = KB'(pst_pkg::FilterKindNone);
  localparam logic [KB-1:0] KindMip        = KB'(pst_pkg::FilterKindMip);
  localparam logic [KB-1:0] KindMipBlended = KB'(pst_pkg::FilterKindMipBlended);
  localparam int R0 = (Regs > 0) ? 1 : 0;   // after the table reads
  localparam int R1 = (Regs > 1) ? 1 : 0;   // after the sums and the blend

  logic [CB-1:0]           ca, cb, first, last, entry_1, entry;
  logic [SatBits-1:0]      sh, sl, sn;
  logic signed [CB:0]      d;       // b - a
  logic signed [AccW-1:0]  acc;     // a 2^TFrac + (b - a) t + 2^(TFrac-1)
  logic [CB-1:0]           mip_ch;
  logic [SumBits-1:0]      sum_mod, sum_cl, sum;
  logic [ProdBits-1:0]     prod;
  logic [QBits-1:0]        quo;
  logic [CB-1:0]           mean;    // <= 2^CB - 1: a mean of CB-bit entries
  logic [CB-1:0]           div_ch, sat_ch;

  pst_delay #(.Width(5*CB + 3*SatBits), .Depth(R0)) u_r0 (
    .clk_i, .rst_ni, .en_i, .d_i ({a_i, b_i, first_i, last_i, entry_i, sh_i, sl_i, sn_i}),
    .q_o ({ca, cb, first, last, entry_1, sh, sl, sn})
  );

  // MIP: round half up of lerp(a, b, t); the result lies between a and b.
  assign d      = $signed({1'b0, cb}) - $signed({1'b0, ca});
  assign acc    = ($signed(AccW'(ca)) <<< TFrac) + AccW'(d) * $signed(AccW'(t_1_i)) +
                  $signed(AccW'(1) <<< (TFrac - 1));

  // SAT sums (all terms non-negative; see pst_clut_filter's header).
  assign sum_mod = SumBits'(sh) + (mod_wrap_1_i ? SumBits'(sn) : '0) - SumBits'(sl);
  assign sum_cl  = SumBits'(nb_1_i) * SumBits'(first) + SumBits'(sh) -
                   (lo_neg_1_i ? '0 : SumBits'(sl)) + SumBits'(na_1_i) * SumBits'(last);
  logic [CB-1:0]      mip_d, mean_d;
  logic [SumBits-1:0] sum_d;
  assign mip_d  = CB'(acc >>> TFrac);
  assign sum_d  = clamp_1_i ? sum_cl : sum_mod;
  assign mean_d = CB'(((SatBits + 1)'(sn) + (SatBits + 1)'(N / 2)) >> Log2Clut);
  pst_delay #(.Width(3*CB + SumBits), .Depth(R1)) u_r1 (
    .clk_i, .rst_ni, .en_i, .d_i ({mip_d, mean_d, entry_1, sum_d}), .q_o ({mip_ch, mean, entry, sum})
  );

  // Division by the window's count: the reciprocal product, rounded, saturated.
  assign prod   = ProdBits'(sum) * ProdBits'(recip_2_i);
  assign quo    = QBits'((prod + (ProdBits'(1) << (RF - 1))) >> RF);
  assign div_ch = (quo > QBits'(MaxC)) ? MaxC : quo[CB-1:0];

  always_comb begin
    if (!clamp_2_i && w_ge_n_2_i) begin
      sat_ch = mean;
    end else if (clamp_2_i ? cl_entry_2_i : count0_2_i) begin
      sat_ch = entry;
    end else begin
      sat_ch = div_ch;
    end
    unique case (kind_2_i)
      KindNone:                ch_o = entry;
      KindMip, KindMipBlended: ch_o = mip_point_2_i ? entry : mip_ch;
      default:                 ch_o = sat_ch;
    endcase
  end

endmodule

`default_nettype wire

// A product for the noise datapath (part of rtl/noise/pst_noise.sv's and rtl/octave/pst_octave_transform.sv's
// arithmetic; docs/HARDWARE.md "Multipliers"): p = a * b mod 2^PW, a signed, b signed or
// unsigned, as a radix-4 Booth product. Combinational, exact.
//
// Yosys 0.23 has no Booth recoding: it builds a * b as an AND array of AW x BW partial-product
// bits summed by a carry-save tree (a signed product over operands sign-extended to the result
// width, more still). Radix-4 Booth recodes b into D = ceil((BW + 1) / 2) digits (unsigned b:
// floor(BW / 2) + 1) in {-2, -1, 0, 1, 2}: D partial products of AW + 1 bits (a mux and an XOR
// per bit), half the rows. Measured alone (OSU018, synth.py's ABC script): signed 17 x unsigned
// 16: 2158 GE (unsigned product and sign correction: 2483); 24 x 16: 2912 (3468); 24 x 32:
// 5744 (6957).
//
// Digit i of b (b_{-1} = 0, b extended by its sign or by zeros): d_i = b_{2i-1} + b_{2i} -
// 2 b_{2i+1}. Row i = d_i a as (AW+1)-bit two's complement: magnitude a or 2a, inverted when
// negative, the +1 of the negation added at bit 2i (the `neg` vector). Sign extension without
// sign copies: a row's signed value r = u - 2^AW with u = r with its sign bit inverted
// (unsigned), so sum_i r_i 4^i = sum_i u_i 4^i - 2^AW sum_i 4^i: the rows unsigned plus one
// constant K. Everything modulo 2^PW (rows and bits at or above PW are not built).
//
// Parameters:
//   AW        width of a (signed)
//   BW        width of b
//   BSigned   1: b signed, 0: b unsigned
//   PW        product bits kept (the exact product has AW + BW bits; fewer: modulo 2^PW)
//
// Ports:
//   a_i [AW-1:0]  signed
//   b_i [BW-1:0]  signed (BSigned) or unsigned
//   p_o [PW-1:0]  a b mod 2^PW
//
// Two forms of the same function, chosen by a define:
//   (default)              the synthesis form above, what Yosys and every gate figure see;
//   PST_MUL_BEHAVIOURAL    the simulation form, one `*` (Verilator evaluates it as one machine
//                          multiply instead of D rows of muxes and adds).
// scripts/mul_proof.py proves the two equal for every (AW, BW, BSigned, PW) the profiles
// instantiate (ctest mul_proof): the synthesis form equals the digit form
// sim/formal/pst_mul_digits.sv bit for bit (ABC's combinational equivalence check), and the
// digit form equals a b as polynomials in a and the bits of b (Z3's sum-of-monomials normal
// form: sum_i d_i a 4^i with d_i = b_{2i-1} + b_{2i} - 2 b_{2i+1}).
`include "pst_pkg.sv"
`default_nettype none

module pst_mul_booth #(
  parameter int AW = 16,
  parameter int BW = 16,
  parameter bit BSigned = 1'b1,
  parameter int PW = AW + BW
) (
  input  logic [AW-1:0] a_i,
  input  logic [BW-1:0] b_i,
  output logic [PW-1:0] p_o
);

`ifdef PST_MUL_BEHAVIOURAL
  // Simulation form: a and b extended to PW bits (a by its sign, b by its sign or by zeros).
  localparam int XA = PW > AW ? PW : AW;
  localparam int XB = PW > BW ? PW : BW;
  logic [XA-1:0] ax;
  logic [XB-1:0] bxw;
  assign ax = XA'($signed(a_i));
  if (BSigned) begin : g_bs_sim
    assign bxw = XB'($signed(b_i));
  end else begin : g_bu_sim
    assign bxw = XB'(b_i);
  end
  assign p_o = PW'(ax * bxw);
`else
  // Digits of b: signed b needs ceil(BW / 2) digits, unsigned b one more bit (a zero sign).
  localparam int EW = BSigned ? BW : BW + 1;   // b as a signed number
  localparam int D = (EW + 1) / 2;
  localparam int XW = 2 * D + 1;               // {b sign-extended to 2D bits, b_{-1} = 0}
  // Wide enough for every row before the modulo.
  localparam int TW = PW + AW + 2 * D + 4;

  function automatic logic [PW-1:0] k_const();
    logic [TW-1:0] k;
    k = '0;
    for (int i = 0; i < D; i++) k = k + (TW'(1) << (AW + 2 * i));
    k_const = PW'(-k);
  endfunction
  localparam logic [PW-1:0] K = k_const();

  logic [XW-1:0] bx;
  if (XW == BW + 1) begin : g_bx_exact   // signed b of even width: no extension
    assign bx = {b_i, 1'b0};
  end else if (BSigned) begin : g_bs
    assign bx = {{(XW-BW-1){b_i[BW-1]}}, b_i, 1'b0};
  end else begin : g_bu
    assign bx = {{(XW-BW-1){1'b0}}, b_i, 1'b0};
  end

  logic [D*PW-1:0] rows;   // row i (unsigned, sign bit inverted) shifted by 2i, mod 2^PW
  logic [D-1:0]    neg;
  for (genvar i = 0; i < D; i++) begin : g_row
    logic [2:0]  sel;
    logic        one, two;
    logic [AW:0] mag, r;
    assign sel = bx[2*i +: 3];
    assign one = sel[0] ^ sel[1];                       // |d| = 1
    assign two = (sel == 3'b011) || (sel == 3'b100);    // |d| = 2
    assign neg[i] = sel[2] && !(sel[1] && sel[0]);      // d < 0 (-0 is +0)
    assign mag = one ? {a_i[AW-1], a_i} : two ? {a_i, 1'b0} : '0;
    assign r = neg[i] ? ~mag : mag;
    assign rows[i*PW +: PW] = PW'({{TW{1'b0}}, ~r[AW], r[AW-1:0]} << (2 * i));
  end

  logic [PW-1:0] negs;     // the +1 of each negated row at bit 2i
  always_comb begin
    negs = '0;
    for (int i = 0; i < D; i++) begin
      if (2 * i < PW) negs[2 * i] = neg[i];
    end
  end

  always_comb begin
    p_o = K + negs;
    for (int i = 0; i < D; i++) p_o = p_o + rows[i*PW +: PW];
  end
`endif

endmodule

`default_nettype wire

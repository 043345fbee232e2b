// The digit form of pst_mul_booth (rtl/common/pst_mul_booth.sv): the middle of the proof that
// its synthesis form (radix-4 Booth rows) and its simulation form (one `*`) are the same
// function (scripts/mul_proof.py). Not part of the design.
//
// Each Booth row is written as the arithmetic it stands for: with digit d_i = b_{2i-1} + b_{2i}
// - 2 b_{2i+1} (b_{-1} = 0, b extended by its sign or by zeros) and neg_i the row's "negated"
// flag, row i holds u_i = d_i a - neg_i + 2^AW (an (AW+1)-bit unsigned number: the two's
// complement row with its sign bit inverted, one's complement where negative), weighted by
// 4^i; p = K + sum_i neg_i 4^i + sum_i u_i 4^i mod 2^PW with K = -sum_i 2^AW 4^i.
//   - Bit for bit it has the synthesis form's rows and sum, so ABC proves the two equal.
//   - As arithmetic it is a polynomial in a and the bits of b (products and sums only, every
//     weight a multiplication by a constant), so Z3 normalizes it to sum_i d_i a 4^i = a b.
//
// Parameters and ports: those of pst_mul_booth.
`default_nettype none

module pst_mul_digits #(
  parameter int AW = 16,
  parameter int BW = 16,
  parameter bit BSigned = 1'b1,
  parameter int PW = AW + BW
) (
  input  logic [AW-1:0] a_i,
  input  logic [BW-1:0] b_i,
  output logic [PW-1:0] p_o
);

  localparam int EW = BSigned ? BW : BW + 1;
  localparam int D = (EW + 1) / 2;
  localparam int XW = 2 * D + 1;
  localparam int TW = PW + AW + 2 * D + 4;   // K's width before the modulo

  function automatic logic [PW-1:0] k_const();
    logic [TW-1:0] k;
    k = '0;
    for (int i = 0; i < D; i++) k = k + (TW'(1) << (AW + 2 * i));
    k_const = PW'(-k);
  endfunction
  localparam logic [PW-1:0] K = k_const();

  // b's bits b_{-1} .. b_{2D-1}, each a bit of b_i (or 0)
  logic [XW-1:0] bx;
  for (genvar k = 0; k < XW; k++) begin : g_bx
    if (k == 0) begin : g_zero
      assign bx[k] = 1'b0;
    end else if (k - 1 < BW) begin : g_bit
      assign bx[k] = b_i[k-1];
    end else begin : g_ext
      assign bx[k] = BSigned ? b_i[BW-1] : 1'b0;
    end
  end

  // Everything modulo 2^PW (as the synthesis form): a sign-extended (or cut) to PW bits.
  logic [PW-1:0] as;
  assign as = PW'($signed(a_i));

  logic [D*PW-1:0] rows;   // u_i 4^i
  logic [D*PW-1:0] negs;   // neg_i 4^i
  for (genvar i = 0; i < D; i++) begin : g_row
    logic [PW-1:0] neg, u;
    // d_i a = a b_{2i-1} + a b_{2i} - 2 a b_{2i+1}, each product of a with one bit
    assign neg = PW'(bx[2*i+2] & ~(bx[2*i+1] & bx[2*i]));
    assign u = as * PW'(bx[2*i]) + as * PW'(bx[2*i+1]) - as * PW'(bx[2*i+2]) * PW'(2) - neg
               + (PW'(1) << AW);
    assign rows[i*PW +: PW] = u * (PW'(1) << (2 * i));
    assign negs[i*PW +: PW] = neg * (PW'(1) << (2 * i));
  end

  // The synthesis form's order: K, the negations' +1s, then the rows.
  always_comb begin
    p_o = K;
    for (int i = 0; i < D; i++) p_o = p_o + negs[i*PW +: PW];
    for (int i = 0; i < D; i++) p_o = p_o + rows[i*PW +: PW];
  end

endmodule

`default_nettype wire

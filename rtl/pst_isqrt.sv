// Integer square root: y_o = floor(sqrt(x_i)), combinational. The digit-by-digit (restoring)
// method, two input bits per step from the top: one compare-subtract of OutWidth + 2 bits per
// result bit. Used by pst_filter_width for the euclidean |grad_x f|. Golden model: isqrtFx in
// model/golden/arith_fx.cpp (same steps).
//
//   rem = 0, root = 0; for i = OutWidth-1 .. 0:
//     rem  = 4 rem + x[2i+1:2i];  trial = 4 root + 1
//     rem >= trial ? (rem -= trial, root = 2 root + 1) : (root = 2 root)
//   Invariant after each step: root^2 + rem = the leading bits of x consumed so far and
//   rem <= 2 root, so rem fits OutWidth + 2 bits.
//
// Parameters:
//   InWidth   bits of the unsigned input x_i; the result has ceil(InWidth / 2) bits.
`default_nettype none

module pst_isqrt #(
  parameter int InWidth = 32,
  // Derived width (not a profile key): floor(sqrt(x)) < 2^ceil(InWidth / 2).
  localparam int OutWidth = (InWidth + 1) / 2
) (
  input  logic [InWidth-1:0]  x_i,
  output logic [OutWidth-1:0] y_o
);

  localparam int PW = 2 * OutWidth;   // x padded to an even number of bits
  localparam int RW = OutWidth + 2;   // remainder and trial width

  always_comb begin
    logic [PW-1:0]       xp;
    logic [RW-1:0]       rem, trial;
    logic [OutWidth-1:0] root;
    xp   = PW'(x_i);
    rem  = '0;
    root = '0;
    for (int i = OutWidth - 1; i >= 0; i--) begin
      rem   = {rem[RW-3:0], xp[2*i +: 2]};
      trial = {root, 2'b01};
      if (rem >= trial) begin
        rem  = rem - trial;
        root = (root << 1) | OutWidth'(1);
      end else begin
        root = root << 1;
      end
    end
    y_o = root;
  end

  // Assertions
`ifndef SYNTHESIS
  // y_o = floor(sqrt(x_i)): y^2 <= x < (y + 1)^2.
  always_comb begin
    assert ((2*RW)'(y_o) * (2*RW)'(y_o) <= (2*RW)'(x_i) &&
            ((2*RW)'(y_o) + 1) * ((2*RW)'(y_o) + 1) > (2*RW)'(x_i))
      else $error("pst_isqrt: y_o is not floor(sqrt(x_i))");
  end
`endif

endmodule

`default_nettype wire

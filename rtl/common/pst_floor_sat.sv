// pst_floor_sat: a wide exact signed value brought to a narrower fixed-point format, as every
// unit does with its results: floor to OutFrac fraction bits (an arithmetic shift right; a
// left shift, exact, when the output has more fraction bits), then saturate to OutWidth
// signed bits. Combinational. Golden model: shiftSatSigned (model/golden/arith_fx.cpp),
// shiftSatSigned(x, InFrac - OutFrac, OutWidth); unit test: sim/unit/arith_unit_test.cpp.
//
//   y_o = sat_OutWidth(floor(x_i 2^(OutFrac - InFrac)))
//   sat: in range iff the bits above OutWidth - 1 all equal the sign; else the maximum
//        (positive x) or the minimum (negative x) of OutWidth signed bits.
//
// Parameters:
//   InWidth, InFrac     x_i: signed, InFrac fraction bits.
//   OutWidth, OutFrac   y_o: signed, OutFrac fraction bits.
`default_nettype none

module pst_floor_sat #(
  parameter int InWidth  = 32,
  parameter int InFrac   = 16,
  parameter int OutWidth = 16,
  parameter int OutFrac  = 8,
  localparam int Sh  = InFrac - OutFrac,       // > 0: right shift (floor); < 0: left shift
  localparam int ShR = (Sh > 0) ? Sh : 0,
  localparam int ShL = (Sh < 0) ? -Sh : 0,
  // Shifted width: room for the left shift and for the output's sign check.
  localparam int SW  = (InWidth + ShL > OutWidth) ? InWidth + ShL : OutWidth + 1
) (
  input  logic [InWidth-1:0]  x_i,
  output logic [OutWidth-1:0] y_o
);

  logic signed [SW-1:0] xs;
  assign xs = (SW'($signed(x_i)) <<< ShL) >>> ShR;

  always_comb begin
    if (xs[SW-1:OutWidth-1] == '0 || xs[SW-1:OutWidth-1] == '1) y_o = xs[OutWidth-1:0];
    else y_o = {xs[SW-1], {(OutWidth-1){~xs[SW-1]}}};
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (InWidth >= 1 && OutWidth >= 2) else $error("pst_floor_sat: widths too small");
  end
`endif

endmodule

`default_nettype wire

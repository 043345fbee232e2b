// pst_floor_sat_sva: checker of every pst_floor_sat instance (each unit's saturation point):
// in range the value passes unchanged, out of range the output is the extreme of the input's
// sign. Cover points per instance: saturated high and saturated low (combinational, so
// reached by the unit's inputs whether or not they belong to a valid fragment).
`include "sva/pst_assert.svh"
`default_nettype none

module pst_floor_sat_sva #(
  parameter int SW       = 2,
  parameter int OutWidth = 2
) (
  input logic signed [SW-1:0]       xs,
  input logic        [OutWidth-1:0] y_o
);
  logic sat;
  assign sat = !(xs[SW-1:OutWidth-1] == '0 || xs[SW-1:OutWidth-1] == '1);
  always_comb begin
    `PST_ASSERT_I(PassOrExtreme, sat ? (y_o == {xs[SW-1], {(OutWidth-1){~xs[SW-1]}}})
                                     : (SW'($signed(y_o)) == xs))
    `PST_COVER_I(SatHigh, sat && !xs[SW-1])
    `PST_COVER_I(SatLow, sat && xs[SW-1])
  end
endmodule

bind pst_floor_sat pst_floor_sat_sva #(.SW(SW), .OutWidth(OutWidth)) u_sva (.*);

`default_nettype wire

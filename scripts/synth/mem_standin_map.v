// Yosys techmap: every memory ($mem_v2 after `memory -nomap`) becomes timing stand-ins, so
// OpenSTA sees a path through it (scripts/synth.py; DESIGN: asynchronous reads need an
// address-to-data arc). Each data bit of each read port is one PST_MEMRD cell (address on
// A0..A15, unused pins tied low); scripts/synth.py renames it PST_MEMRD_<k> after the memory
// it stands for, whose delay the stand-in liberty gives. Each write-port bit (data, enable,
// address) ends at a PST_MEMWR capture cell clocked by the write clock. The cells have no
// area: memories are costed apart.
module \$mem_v2 (RD_CLK, RD_EN, RD_ARST, RD_SRST, RD_ADDR, RD_DATA, WR_CLK, WR_EN, WR_ADDR, WR_DATA);
  parameter MEMID = "";
  parameter SIZE = 0;
  parameter OFFSET = 0;
  parameter ABITS = 0;
  parameter WIDTH = 0;
  parameter INIT = 0;
  parameter RD_PORTS = 0;
  parameter RD_WIDE_CONTINUATION = 0;
  parameter RD_CLK_ENABLE = 0;
  parameter RD_CLK_POLARITY = 0;
  parameter RD_TRANSPARENCY_MASK = 0;
  parameter RD_COLLISION_X_MASK = 0;
  parameter RD_CE_OVER_SRST = 0;
  parameter RD_ARST_VALUE = 0;
  parameter RD_SRST_VALUE = 0;
  parameter RD_INIT_VALUE = 0;
  parameter WR_PORTS = 0;
  parameter WR_WIDE_CONTINUATION = 0;
  parameter WR_CLK_ENABLE = 0;
  parameter WR_CLK_POLARITY = 0;
  parameter WR_PRIORITY_MASK = 0;

  input [RD_PORTS-1:0] RD_CLK, RD_EN, RD_ARST, RD_SRST;
  input [RD_PORTS*ABITS-1:0] RD_ADDR;
  output [RD_PORTS*WIDTH-1:0] RD_DATA;
  input [WR_PORTS-1:0] WR_CLK;
  input [WR_PORTS*WIDTH-1:0] WR_EN;
  input [WR_PORTS*ABITS-1:0] WR_ADDR;
  input [WR_PORTS*WIDTH-1:0] WR_DATA;

  // Synchronous read ports are not used by this design; refuse them rather than time them wrong.
  wire _TECHMAP_FAIL_ = RD_CLK_ENABLE != 0 || ABITS > 16;

  genvar p, b;
  generate
    for (p = 0; p < RD_PORTS; p = p + 1) begin : rd
      wire [15:0] a = RD_ADDR[p*ABITS +: ABITS];
      for (b = 0; b < WIDTH; b = b + 1) begin : bit
        (* keep *)
        PST_MEMRD cell (.A0(a[0]), .A1(a[1]), .A2(a[2]), .A3(a[3]), .A4(a[4]), .A5(a[5]),
                        .A6(a[6]), .A7(a[7]), .A8(a[8]), .A9(a[9]), .A10(a[10]), .A11(a[11]),
                        .A12(a[12]), .A13(a[13]), .A14(a[14]), .A15(a[15]),
                        .Y(RD_DATA[p*WIDTH+b]));
      end
    end
    for (p = 0; p < WR_PORTS; p = p + 1) begin : wr
      for (b = 0; b < WIDTH; b = b + 1) begin : dbit
        (* keep *) PST_MEMWR wd (.CK(WR_CLK[p]), .D(WR_DATA[p*WIDTH+b]));
        (* keep *) PST_MEMWR we (.CK(WR_CLK[p]), .D(WR_EN[p*WIDTH+b]));
      end
      for (b = 0; b < ABITS; b = b + 1) begin : abit
        (* keep *) PST_MEMWR wa (.CK(WR_CLK[p]), .D(WR_ADDR[p*ABITS+b]));
      end
    end
  endgenerate
endmodule

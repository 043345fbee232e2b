// pst_noise_value_rom: the noise unit's value table R (pst_noise step 3; Rayshade's 267
// 16-bit entries) in four banks by address mod 4 (bank b's entry j = R[4 j + b]): a corner's
// four consecutive entries R[m .. m + 3] are one read of each bank, rotated by m mod 4 (8 read
// ports per 67-entry bank in the parallel unit instead of 32 on the whole table).
//
// Parameters:
//   Corners  read ports, one per corner (m_i and r_o slot i).
//   Reads    entries per corner: 4 (R[m .. m + 3], value-gradient corners) or 1 (R[m], value
//            corners: one bank read).
//   Bits     the top Bits bits of each 16-bit entry are read (Q1.VF: Bits = VF + 1).
`include "pst_pkg.sv"
`include "noise/pst_rom_dir.svh"
`default_nettype none

module pst_noise_value_rom #(
  parameter int Corners = 8,
  parameter int Reads   = 4,
  parameter int Bits    = 16
) (
  input  logic [Corners*8-1:0]         m_i,   // corner i's m = h3 & 0xff at [i*8 +: 8]
  output logic [Corners*Reads*Bits-1:0] r_o   // corner i's R[m + k] at [(Reads i + k)*Bits +: Bits]
);

  localparam int VD = 67;   // bank depth: R[0..266] (bank 3's entry 66 is padding)
  logic [15:0] value_b0 [VD];
  logic [15:0] value_b1 [VD];
  logic [15:0] value_b2 [VD];
  logic [15:0] value_b3 [VD];
  initial $readmemh({`PST_ROM_DIR, "/value16_b0.memh"}, value_b0);
  initial $readmemh({`PST_ROM_DIR, "/value16_b1.memh"}, value_b1);
  initial $readmemh({`PST_ROM_DIR, "/value16_b2.memh"}, value_b2);
  initial $readmemh({`PST_ROM_DIR, "/value16_b3.memh"}, value_b3);

  for (genvar i = 0; i < Corners; i++) begin : g_corner
    logic [7:0]      m;
    logic [4*16-1:0] bank;   // bank b's entry: R[m + ((b - m) mod 4)] at [b*16 +: 16]
    assign m = m_i[i*8 +: 8];
    for (genvar b = 0; b < 4; b++) begin : g_bank
      logic [8:0] e;   // the entry of bank b among R[m .. m + 3]
      logic [6:0] j;
      logic [1:0] off;
      assign off = 2'(b) - m[1:0];
      assign e   = {1'b0, m} + {7'b0, off};
      assign j   = e[8:2];
      if (b == 0) begin : g_b0
        assign bank[b*16 +: 16] = value_b0[j];
      end else if (b == 1) begin : g_b1
        assign bank[b*16 +: 16] = value_b1[j];
      end else if (b == 2) begin : g_b2
        assign bank[b*16 +: 16] = value_b2[j];
      end else begin : g_b3
        assign bank[b*16 +: 16] = value_b3[j];
      end
      logic unused_e;
      assign unused_e = ^e[1:0];
    end
    for (genvar k = 0; k < Reads; k++) begin : g_r
      logic [15:0] r16;
      assign r16 = bank[2'(m[1:0] + 2'(k))*16 +: 16];
      assign r_o[(Reads*i + k)*Bits +: Bits] = r16[15 -: Bits];
      if (Bits < 16) begin : g_unused_low
        logic unused_low;
        assign unused_low = ^r16[15-Bits:0];
      end
    end
  end

endmodule

`default_nettype wire

// pst_noise_hash_rom: the noise unit's hash table T (pst_noise step 2) in two banks, T[2a] in
// bank E at a and T[2a + 1] in bank O at a, with combinational read ports of two kinds:
//   pair    the two lookups of a corner pair, addresses a0 and a1 that differ in bit 0 (X and
//           X + 1, or h ^ Y and h ^ (Y + 1)): one read of each bank gives T[a0] and T[a1];
//   single  one lookup: both banks read at a >> 1, picked by a[0].
// Each port is one read port of each bank (the memory figures count them).
//
// Parameters:
//   NoiseHash  rayshade: Rayshade's 4096 x 12 table; perm256 / perlin256: a 256 x 8
//              permutation (ROM images in `PST_ROM_DIR, written by sim/tools/pst_roms).
//   Pairs      pair read ports (0: none).
//   Singles    single read ports (0: none).
`include "pst_pkg.sv"
`include "pst_params.svh"
`include "noise/pst_rom_dir.svh"
`default_nettype none

module pst_noise_hash_rom #(
  `PST_HASH_ROM_PARAMS,
  parameter int Pairs     = 1,
  parameter int Singles   = 0,
  localparam int HW = (NoiseHash == pst_pkg::NoiseHashRayshade) ? pst_pkg::LatticeBits : 8,
  localparam int PW = (Pairs > 0) ? Pairs : 1,     // port vectors keep one slot when unused
  localparam int SW = (Singles > 0) ? Singles : 1
) (
  input  logic [PW*HW-1:0] pair_a0_i,   // port p at [p*HW +: HW], likewise below
  input  logic [PW*HW-1:0] pair_a1_i,   // a0 with bit 0 inverted (only its upper bits are read)
  output logic [PW*HW-1:0] pair_h0_o,   // T[a0]
  output logic [PW*HW-1:0] pair_h1_o,   // T[a1]
  input  logic [SW*HW-1:0] single_a_i,
  output logic [SW*HW-1:0] single_h_o   // T[a]
);

  localparam int HD = (1 << HW) / 2;   // bank depth
  logic [HW-1:0] rom_e [HD];
  logic [HW-1:0] rom_o [HD];
  if (NoiseHash == pst_pkg::NoiseHashRayshade) begin : g_rayshade
    initial $readmemh({`PST_ROM_DIR, "/hash4096_even.memh"}, rom_e);
    initial $readmemh({`PST_ROM_DIR, "/hash4096_odd.memh"}, rom_o);
  end else if (NoiseHash == pst_pkg::NoiseHashPerm256) begin : g_perm256
    initial $readmemh({`PST_ROM_DIR, "/perm256_even.memh"}, rom_e);
    initial $readmemh({`PST_ROM_DIR, "/perm256_odd.memh"}, rom_o);
  end else begin : g_perlin256
    initial $readmemh({`PST_ROM_DIR, "/perlin256_even.memh"}, rom_e);
    initial $readmemh({`PST_ROM_DIR, "/perlin256_odd.memh"}, rom_o);
  end

  for (genvar p = 0; p < Pairs; p++) begin : g_pair
    logic [HW-1:0] a0, a1, de, dd;
    assign a0 = pair_a0_i[p*HW +: HW];
    assign a1 = pair_a1_i[p*HW +: HW];
    assign de = rom_e[a0[0] ? a1[HW-1:1] : a0[HW-1:1]];
    assign dd = rom_o[a0[0] ? a0[HW-1:1] : a1[HW-1:1]];
    assign pair_h0_o[p*HW +: HW] = a0[0] ? dd : de;
    assign pair_h1_o[p*HW +: HW] = a0[0] ? de : dd;
    logic unused_a1;   // bit 0 of the partner is ~a0[0]
    assign unused_a1 = a1[0];
  end
  for (genvar p = 0; p < Singles; p++) begin : g_single
    logic [HW-1:0] a;
    assign a = single_a_i[p*HW +: HW];
    assign single_h_o[p*HW +: HW] = a[0] ? rom_o[a[HW-1:1]] : rom_e[a[HW-1:1]];
  end
  if (Pairs == 0) begin : g_no_pairs
    assign pair_h0_o = '0;
    assign pair_h1_o = '0;
    logic unused_pair;
    assign unused_pair = ^{pair_a0_i, pair_a1_i};
  end
  if (Singles == 0) begin : g_no_singles
    assign single_h_o = '0;
    logic unused_single;
    assign unused_single = ^single_a_i;
  end

endmodule

`default_nettype wire

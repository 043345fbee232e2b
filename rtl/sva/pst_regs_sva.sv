// pst_regs_sva: checker of pst_regs (the register file): the active octave count stays in
// 0..Octaves and is only written in range; cover points for a write of every register class
// (control, active count, quadric, each octave field, the last octave, the fade table and
// the octaves' lg ||M|| and term means of the bandlimit profiles, the worley coefficients) and the active
// count's extremes.
`include "sva/pst_assert.svh"
`include "pst_pkg.sv"
`default_nettype none

module pst_regs_sva #(
  parameter int Octaves = 1,
  parameter int OctBits = 1
) (
  input logic                            clk_i,
  input logic                            rst_ni,
  input logic                            we_i,
  input logic [pst_pkg::RegAddrBits-1:0] addr_i,
  input logic [pst_pkg::RegDataBits-1:0] wdata_i,
  input logic [OctBits-1:0]              active_o
);
  localparam int AB = pst_pkg::RegAddrBits;
  localparam int DB = pst_pkg::RegDataBits;
  // The octave block a write addresses, and the field's offset inside it.
  logic [AB-1:0] oct_off;
  logic          oct_sel;
  assign oct_off = (addr_i - pst_pkg::RegOctave) % AB'(pst_pkg::RegOctaveStride);
  assign oct_sel = addr_i >= pst_pkg::RegOctave &&
                   32'(addr_i) < 32'(pst_pkg::RegOctave) + pst_pkg::RegOctaveStride * Octaves;
  logic w_active;
  assign w_active = we_i && addr_i == pst_pkg::RegActive;

  `PST_ASSERT(ActiveWrittenInRange, w_active |-> (wdata_i <= DB'(Octaves)))
  `PST_ASSERT(ActiveInRange, 32'(active_o) <= Octaves)
  `PST_ASSERT_KNOWN(WriteKnown, we_i)
  `PST_ASSERT(WriteAddrKnown, we_i |-> !$isunknown({addr_i, wdata_i}))

  `PST_COVER(WriteControl, we_i && addr_i == pst_pkg::RegControl)
  `PST_COVER(WriteActive, w_active)
  `PST_COVER(ActiveZero, w_active && wdata_i == '0)
  `PST_COVER(ActiveAll, w_active && wdata_i == DB'(Octaves))
  `PST_COVER(WriteQuadric, we_i && addr_i >= pst_pkg::RegQuadric &&
                           32'(addr_i) < 32'(pst_pkg::RegQuadric) + pst_pkg::RegQuadricCount)
  `PST_COVER(WriteOctaveM, we_i && oct_sel && 32'(oct_off) >= pst_pkg::RegOctaveM &&
                           32'(oct_off) < pst_pkg::RegOctaveM + pst_pkg::RegOctaveMCount)
  `PST_COVER(WriteOctaveO, we_i && oct_sel && 32'(oct_off) >= pst_pkg::RegOctaveO &&
                           32'(oct_off) < pst_pkg::RegOctaveO + pst_pkg::RegOctaveOCount)
  `PST_COVER(WriteOctaveA, we_i && oct_sel && 32'(oct_off) == pst_pkg::RegOctaveA)
  `PST_COVER(WriteOctaveGm, we_i && oct_sel && 32'(oct_off) >= pst_pkg::RegOctaveGm &&
                            32'(oct_off) < pst_pkg::RegOctaveGm + pst_pkg::RegOctaveGmCount)
  `PST_COVER(WriteLastOctave, we_i && 32'(addr_i) == 32'(pst_pkg::RegOctave) +
                              pst_pkg::RegOctaveStride * (Octaves - 1) + pst_pkg::RegOctaveA)
  `PST_COVER(WriteOctaveLgm, we_i && oct_sel && 32'(oct_off) == pst_pkg::RegOctaveLgm)
  `PST_COVER(WriteOctaveFm, we_i && oct_sel && 32'(oct_off) == pst_pkg::RegOctaveFm)
  `PST_COVER(WriteBandlimitOn, we_i && addr_i == pst_pkg::RegControl && wdata_i[pst_pkg::RegControlBandlimitLsb])
  `PST_COVER(WriteFade, we_i && addr_i >= pst_pkg::RegFade &&
                        32'(addr_i) < 32'(pst_pkg::RegFade) + pst_pkg::RegFadeCount)
  `PST_COVER(WriteFadeLast, we_i && 32'(addr_i) == 32'(pst_pkg::RegFade) + pst_pkg::RegFadeCount - 1)
  `PST_COVER(WriteWorley, we_i && addr_i >= pst_pkg::RegWorley &&
                          32'(addr_i) < 32'(pst_pkg::RegWorley) + pst_pkg::RegWorleyCount)
endmodule

bind pst_regs pst_regs_sva #(.Octaves(Octaves), .OctBits(OctBits)) u_sva (.*);

`default_nettype wire

// pst_rom_dir: where the noise units' ROM images are read from, `PST_ROM_DIR (the folder of the
// *.memh files sim/tools/pst_roms writes), "rom" unless the build defines it (Verilator
// +define+PST_ROM_DIR=..., Yosys -D PST_ROM_DIR=...). Included by every module with an
// initial $readmemh: pst_noise_hash_rom, pst_noise_value_rom, pst_subband, pst_worley.
`ifndef PST_ROM_DIR
`define PST_ROM_DIR "rom"
`endif

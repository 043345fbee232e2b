# Timing constraints of pst_top (OpenSTA 2.0.17, OSU 0.18 um typical: 1.8 V, 25 C), read by
# scripts/synth.py. Fmax is derived from the worst slack at this target: 1 / (period - WNS).
#   clock: 10 ns target (100 MHz, a 1999 consumer chip), ideal (no clock tree, no uncertainty)
#   inputs: arrive 2 ns after the edge (20 % of the cycle spent in the driving block), driven
#           by a BUFX2
#   outputs: required 2 ns before the next edge (20 % for the receiving block), each loaded
#           with 0.05 pF (about four NAND2X1 inputs plus a short wire)
create_clock -name clk -period 10.0 [get_ports clk_i]
set_input_delay 2.0 -clock clk [delete_from_list [all_inputs] [get_ports clk_i]]
set_output_delay 2.0 -clock clk [all_outputs]
set_driving_cell -lib_cell BUFX2 [delete_from_list [all_inputs] [get_ports clk_i]]
set_load 0.05 [all_outputs]
# The reset is asynchronous in the RTL (flip-flops with an asynchronous clear); Yosys turns it
# into logic in front of D (async2sync, a DFFPOSX1 has no clear), which is not a path of the
# chip: a synchronized, buffered reset tree is timed by recovery/removal checks, not setup.
set_false_path -from [get_ports rst_ni]

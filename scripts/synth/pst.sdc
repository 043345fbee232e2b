# Timing constraints of pst_top (OpenSTA 2.0.17, OSU 0.18 um typical: 1.8 V, 25 C), read by
# scripts/synth.py. Fmax is derived from the worst setup slack at this target:
# 1 / (period - WNS), a pre-layout figure (typical corner, no wire load: the liberty has none).
#   clock: 10 ns target (100 MHz, a 1999 consumer chip); the clock network stays ideal (no
#           clock-tree synthesis in the flow, nor in qflow's back end), so what a buffered
#           clock net adds is modelled by the uncertainty and transition below
#   inputs: arrive 2 ns after the edge (20 % of the cycle spent in the driving block), driven
#           by a BUFX2
#   outputs: required 2 ns before the next edge (20 % for the receiving block), each loaded
#           with 0.05 pF (about four NAND2X1 inputs plus a short wire)
create_clock -name clk -period 10.0 [get_ports clk_i]
set_input_delay 2.0 -clock clk [delete_from_list [all_inputs] [get_ports clk_i]]
set_output_delay 2.0 -clock clk [all_outputs]
set_load 0.05 [all_outputs]

# Clock uncertainty. qflow has no clock-tree synthesis: its clock is a buffered fanout tree
# (blifFanout), whose skew is 0.2-0.5 ns at this size (/work/shared/DESIGN.md section 9).
#   setup: 0.3 ns skew (the middle of that range, between any two flip-flops of the chip)
#          + 0.1 ns cycle-to-cycle jitter (1 % of the period, a PLL of the time) = 0.4 ns
#   hold:  0.1 ns: a hold path is a short path between neighbouring flip-flops, which hang on
#          one leaf buffer or on sibling leaves (local skew); jitter does not apply (the same
#          edge launches and captures)
set_clock_uncertainty -setup 0.4 [get_clocks clk]
set_clock_uncertainty -hold 0.1 [get_clocks clk]

# Clock transition at the flip-flops' CLK pins: a CLKBUF1 leaf buffer driving 16 DFFPOSX1
# clock pins (16 x 0.028 pF) and about 0.1 pF of wire (16 x 50 um x 0.13 fF/um), 0.55 pF:
# its rise transition is 0.316 ns at 0.5 pF and 0.745 ns at 1.2 pF (liberty table), about
# 0.35 ns at 0.55 pF (fall 0.26-0.30 ns).
set_clock_transition 0.35 [get_clocks clk]

# Data inputs: a BUFX2 whose own input switches with 0.2 ns, the rise transition of a BUFX2
# at 0.15 pF in the liberty's table (0.193-0.205 ns over its input slews): a like gate of the
# driving block.
set_driving_cell -lib_cell BUFX2 -input_transition_rise 0.2 -input_transition_fall 0.2 \
    [delete_from_list [all_inputs] [get_ports clk_i]]

# Design rules. The liberty has no default_max_transition; its delay and transition tables
# end at an input transition of 1.2 ns (most cells; 1.8 ns for the rest): beyond it every
# delay is extrapolated, so 1.2 ns is the limit on every pin. The maximum capacitance is per
# output pin in the liberty (max_capacitance, 0.47-3.94 pF); OpenSTA 2.0.17 has no check of
# it (report_check_types knows -max_transition only), so scripts/pstlib/synth/sta.py checks
# every driver's net against its pin's liberty limit.
set_max_transition 1.2 [current_design]

# The reset is asynchronous in the RTL (flip-flops with an asynchronous clear); Yosys turns it
# into logic in front of D (async2sync, a DFFPOSX1 has no clear), which is not a path of the
# chip: a synchronized, buffered reset tree is timed by recovery/removal checks, not setup.
set_false_path -from [get_ports rst_ni]

// Black boxes of the memory timing stand-ins (scripts/synth/mem_standin_map.v); their timing
// is in the stand-in liberty scripts/synth.py writes beside the netlist.
(* blackbox *)
module PST_MEMRD (input A0, A1, A2, A3, A4, A5, A6, A7, A8, A9, A10, A11, A12, A13, A14, A15,
                  output Y);
endmodule

(* blackbox *)
module PST_MEMWR (input CK, input D);
endmodule

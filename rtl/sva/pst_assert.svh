// pst_assert.svh: named assertion and cover macros (after lowRISC's prim_assert.sv) in the
// subset the simulator supports (|->, |=>, $past, $stable, $rose, disable iff; no ## or [*n]).
// Used by the checker modules of rtl/sva/, which `bind` attaches to the RTL modules; synthesis
// never reads rtl/sva/ (scripts/synth.py reads rtl/*.sv only). A failed assertion stops the
// simulation with the checker's path and the assertion's name.
//
//   `PST_ASSERT(Name, prop)          concurrent, @(posedge clk_i) disable iff (!rst_ni)
//   `PST_ASSERT_KNOWN(Name, sig)     no X/Z on sig after reset (4-state simulators only: a
//                                    2-state simulator always sees $isunknown = 0)
//   `PST_COVER(Name, prop)           concurrent cover point (a user point of the coverage
//                                    build, scripts/coverage.sh; ignored otherwise)
//   `PST_ASSERT_I(Name, expr)        immediate, inside always_comb (combinational modules)
//   `PST_COVER_I(Name, expr)         immediate cover point inside always_comb (counted per
//                                    evaluation: it says "reached", not how often)
`ifndef PST_ASSERT_SVH
`define PST_ASSERT_SVH

`define PST_ASSERT(__name, __prop) \
  __name: assert property (@(posedge clk_i) disable iff (!rst_ni) (__prop)) \
    else $error("%m: assertion %s failed", `"__name`");

`define PST_ASSERT_KNOWN(__name, __sig) \
  `PST_ASSERT(__name, !$isunknown(__sig))

`define PST_COVER(__name, __prop) \
  __name: cover property (@(posedge clk_i) disable iff (!rst_ni) (__prop));

`define PST_ASSERT_I(__name, __expr) \
  __name: assert (__expr) else $error("%m: assertion %s failed", `"__name`");

`define PST_COVER_I(__name, __expr) \
  __name: cover (__expr);

`endif

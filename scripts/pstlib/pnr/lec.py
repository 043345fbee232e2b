"""A routed block proven equal to the block the synthesis cut (issue 43 part 2): the netlist qflow
placed and routed (its buffer and clock trees from blifFanout, flip-flops reassigned to clock
buffers by the placer, filler cells dropped: the `sta.v` OpenSTA times) against the block's
netlist before qflow (WORK/blocks/blk_NAME.blif, written as Verilog by pstlib/pnr/blif.py as the
routed one is, so that both name their ports alike), both OSU018 cells read as their liberty
functions.

`miter -equiv -flatten` compares every output bit of the two; flip-flops start at zero on both
sides (`write_aiger -zinit`) and ABC's `dprove` decides the sequential miter (pstlib/lec/prove.py):
the cell names differ between the two netlists (qflow renames every instance), so registers are
matched by ABC's signal correspondence, not by name. A mutant (one two-input cell of the routed
netlist swapped for its dual, pstlib/lec/miter.py `mutate`) must come out "differs".
"""
import pathlib
import time

from ..lec import miter, prove
from ..synth.tools import run_yosys

GOLD = "pst_lec_gold"
GATE = "pst_lec_gate"


def script(lib, gold, gate, module: str, aig) -> str:
    """Yosys: the two netlists of MODULE (GOLD: before qflow, GATE: routed) as one miter in AIG."""
    return "\n".join([
        f"read_liberty {lib}", f"read_verilog {gold}", f"hierarchy -top {module}", "flatten", f"rename {module} {GOLD}",
        "design -stash pst_g",
        f"read_liberty {lib}", f"read_verilog {gate}", f"hierarchy -top {module}", "flatten", f"rename {module} {GATE}",
        "design -stash pst_t",
        "design -reset",
        f"design -copy-from pst_g -as {GOLD} {GOLD}",
        f"design -copy-from pst_t -as {GATE} {GATE}",
        f"miter -equiv -flatten {GOLD} {GATE} pst_lec_miter",
        "hierarchy -top pst_lec_miter", "flatten", "techmap", "opt -fast", "dffunmap", "aigmap",
        "setundef -zero -init", f"write_aiger -zinit {aig}", ""])


def check(lib, gold: pathlib.Path, gate: pathlib.Path, module: str, work: pathlib.Path,
          timeout: float = 1800.0, mutate: bool = False) -> dict:
    """{"result": proven | differs | undecided | timeout, "seconds", "abc", "mutation"} for the
    routed netlist GATE against GOLD (with MUTATE: GATE with one cell swapped, which must differ)."""
    work.mkdir(parents=True, exist_ok=True)
    mutation = None
    if mutate:
        text, mutation = miter.mutate(gate.read_text(), module)
        gate = work / "routed_mutant.v"
        gate.write_text(text)
    aig = work / ("routed_mutant.aig" if mutate else "routed.aig")
    t0 = time.time()
    run_yosys(script(lib, gold, gate, module, aig), work, "lec_mutant" if mutate else "lec")
    verdict, secs, last = prove.prove(aig, True, timeout)
    return {"result": verdict, "seconds": round(time.time() - t0, 1), "abc_seconds": round(secs, 1), "abc": last,
            "mutation": mutation}

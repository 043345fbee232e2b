"""Running Yosys and OpenSTA, and the pieces of the Yosys scripts every synthesis here shares:
reading the RTL with a profile's parameters, and the one mapping to the cell library."""
import json
import pathlib
import re
import subprocess
import time

from .. import contract, procs
from ..paths import ROOT, rtl_sources

SYNTH_DIR = ROOT / "scripts" / "synth"
OLD_LIB = SYNTH_DIR / "cells.lib"
SDC = SYNTH_DIR / "pst.sdc"
STANDIN_MAP = SYNTH_DIR / "mem_standin_map.v"
STANDIN_CELLS = SYNTH_DIR / "mem_standin_cells.v"
# ABC: area mapping, then fanout buffering and sizing against the delay target (ps).
ABC_SCRIPT = "+strash;dretime;map,-a;topo;buffer,-p;upsize,{D};dnsize,{D}"
ABC_DELAY_PS = 10000
ABC_CONSTR = "set_driving_cell BUFX2\nset_load 0.02\n"
YOSYS_ERRORS = "implicitly declared|has no driver"     # warnings that fail the run (a silent mis-build)


def base_name(module: str) -> str:
    """The source module of a Yosys module name ($paramod$<hash>\\pst_noise -> pst_noise)."""
    m = re.search(r"(pst_[A-Za-z0-9_]+)", module)
    return m.group(1) if m else module.lstrip("\\")


def tool_version(cmd: list) -> str:
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, input="exit\n", timeout=60)
        return (r.stdout or r.stderr).strip().splitlines()[0]
    except (OSError, IndexError, subprocess.SubprocessError):
        return "unknown"


def abc_line(lib: pathlib.Path, constr: pathlib.Path) -> str:
    return f"abc -liberty {lib} -constr {constr} -D {ABC_DELAY_PS} -script {ABC_SCRIPT}"


def chparams(doc: dict) -> list:
    """The profile's RTL parameters as Yosys chparam lines on pst_top."""
    return [f"chparam -set {n} {v} pst_top" for n, v in contract.parameters(doc)]


def read_lines(doc: dict, rom_dir, lib=None) -> list:
    """Read the cell library (port directions), the memory stand-ins and the RTL with the
    profile's parameters (debug probes off); `include`s (pst_pkg.sv, *.svh) come from rtl/."""
    sources = " ".join(str(p) for p in rtl_sources())
    return [*([f"read_liberty -lib {lib}"] if lib else []),   # none: elaboration only
            f"read_verilog -lib {STANDIN_CELLS}",
            f'read_verilog -sv -I {ROOT / "rtl"} -D SYNTHESIS -D PST_ROM_DIR="{rom_dir}" {sources}',
            *chparams(doc),
            "chparam -set DebugProbes 0 pst_top"]


def cell_lines(lib, tmp: pathlib.Path, save_generic: bool = False, before_ffs=()) -> list:
    """Generic logic -> the library: every flop a positive-edge DFF, ABC maps for area and sizes,
    then the library's flops; the statistics into TMP/stat.json. SAVE_GENERIC keeps the generic
    design as `generic` before ABC; BEFORE_FFS runs between ABC and the flop mapping."""
    return ["dfflegalize -cell $_DFF_P_ 01",
            *(["design -save generic"] if save_generic else []),
            abc_line(lib, tmp / "abc.constr"),
            "opt_clean -purge",
            *before_ffs,
            f"dfflibmap -liberty {lib}",
            "opt_clean -purge",
            f"tee -q -o {tmp}/stat.json stat -json"]


def map_lines(lib, tmp: pathlib.Path, save_generic: bool = False, before_ffs=()) -> list:
    """A coarse design -> the library: memories become timing stand-ins, asynchronous resets
    logic, then cell_lines."""
    return [f"techmap -map {STANDIN_MAP} t:$mem_v2",
            "techmap",
            "opt -fast",
            "async2sync",
            *cell_lines(lib, tmp, save_generic, before_ffs)]


def parse_stat_json(text: str) -> dict:
    """Yosys 0.23's `stat -json` prints the hierarchy as plain text inside its "design"
    section when the design has sub-modules; only the "modules" section is used here, so the
    text is cut after it."""
    end = text.find("\n   },\n")
    return json.loads(text if end < 0 else text[:end] + "\n   }\n}\n")


def hierarchy_of(stat: dict) -> dict:
    """Derived module -> {sub-module: instances} of a design's `stat -json`."""
    mods = stat["modules"]
    return {m: {c: n for c, n in v.get("num_cells_by_type", {}).items() if c in mods} for m, v in mods.items()}


def run_yosys(script: str, tmp: pathlib.Path, tag: str, yosys: str = "yosys") -> float:
    """Runs a Yosys script (TMP/TAG.ys, log TMP/TAG.log); seconds, RuntimeError with the log's tail."""
    path = tmp / f"{tag}.ys"
    path.write_text(script)
    t0 = time.time()
    rc, _, err = procs.run([yosys, "-q", "-e", YOSYS_ERRORS, "-l", tmp / f"{tag}.log", "-s", path], cwd=None)
    if rc != 0:
        log = tmp / f"{tag}.log"
        tail = "\n".join(log.read_text().splitlines()[-30:]) if log.exists() else ""
        raise RuntimeError(f"yosys ({tag}) failed:\n{tail}\n{err}")
    return time.time() - t0


def run_sta(script: str, tmp: pathlib.Path, tag: str, sta_bin: str = "sta") -> tuple:
    """Runs an OpenSTA Tcl script; (seconds, stdout), RuntimeError on an error."""
    path = tmp / f"{tag}.tcl"
    path.write_text(script)
    t0 = time.time()
    rc, out, err = procs.run([sta_bin, "-no_init", "-no_splash", "-exit", path], cwd=None)
    if rc != 0 or "Error" in out or "Error" in err:
        raise RuntimeError(f"OpenSTA ({tag}) failed:\n{out[-3000:]}\n{err[-3000:]}")
    return time.time() - t0, out

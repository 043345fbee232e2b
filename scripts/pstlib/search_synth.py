"""Logic area of a profile from a per-module synthesis cache (issue 13: a search point that
changes one format re-synthesizes only the modules that format reaches).

scripts/synth.py synthesizes pst_top hierarchically: every module once per parameter set. The
same flow here is split in two Yosys runs:
1. elaboration only (`hierarchy` after the profile's chparam; seconds): the derived modules,
   each named by Yosys from its parameter values ($paramod$<sha1 of the parameters>\\NAME, or
   the values spelled out), and which module instantiates which, how often;
2. synthesis of the derived modules not in the cache (the others are turned into black boxes
   first, so their instances stay cells and cost nothing), with synth.py's own mapping (its
   ABC script, constraints, flip-flop legalization, memory stand-ins): stat per module.
A module's cache key is its derived name (its parameter values), the text of its source file,
rtl/pst_pkg.sv and rtl/*.svh, and the flow (synth.py's ABC line and scripts/synth/ files):
a change elsewhere in rtl/ keeps it. Area = sum over derived modules of instances x own cells'
area, as synth.py counts it (memories outside: stand-ins without area). Fmax is not part of
this (it needs the whole netlist): scripts/synth.py gives it for the points that need it.
"""
import hashlib
import json
import pathlib
import subprocess
import tempfile
import time

from . import atomic, liberty
from .paths import PY, ROOT



def _synth_module():
    """scripts/synth.py imported as a module (its flow constants and script pieces)."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("pst_synth_script", ROOT / "scripts" / "synth.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


_SYN = None


def syn():
    global _SYN
    if _SYN is None:
        _SYN = _synth_module()
    return _SYN


def _sha(*parts) -> str:
    h = hashlib.sha256()
    for p in parts:
        h.update(p if isinstance(p, bytes) else str(p).encode())
        h.update(b"\0")
    return h.hexdigest()[:20]


def flow_salt(lib: pathlib.Path) -> str:
    """What every module's gates depend on besides its source: the mapping and the cell library."""
    s = syn()
    files = [ROOT / "scripts" / "synth.py", lib, *sorted((ROOT / "scripts" / "synth").glob("*.v"))]
    return _sha(s.ABC_SCRIPT, s.ABC_DELAY_PS, s.ABC_CONSTR, "module-flow-1", *[f.read_bytes() for f in files])


def source_of(base: str) -> pathlib.Path:
    return ROOT / "rtl" / f"{base}.sv"


def module_key(derived: str, salt: str) -> str:
    base = syn().base_name(derived)
    shared = [ROOT / "rtl" / "pst_pkg.sv", *sorted((ROOT / "rtl").glob("*.svh"))]
    src = source_of(base)
    texts = [p.read_bytes() for p in ([src] if src.exists() else []) + shared]
    return _sha(derived, salt, *texts)


def _chparams(profile: pathlib.Path) -> list:
    out = subprocess.run([PY, str(ROOT / "scripts" / "profile.py"), str(profile), "--yosys"],
                         check=True, capture_output=True, text=True).stdout.splitlines()
    return [f"{line} pst_top" for line in out if line.strip()]


def _read_lines(profile, rom_dir, lib) -> list:
    sources = " ".join(str(p) for p in sorted((ROOT / "rtl").glob("*.sv")))
    s = syn()
    return [f"read_liberty -lib {lib}", f"read_verilog -lib {s.STANDIN_CELLS}",
            f'read_verilog -sv -D SYNTHESIS -D PST_ROM_DIR="{rom_dir}" {sources}',
            *_chparams(profile), "chparam -set DebugProbes 0 pst_top"]


def _yosys(script: str, tmp: pathlib.Path, tag: str, yosys="yosys") -> float:
    path = tmp / f"{tag}.ys"
    path.write_text(script)
    t0 = time.time()
    r = subprocess.run([yosys, "-q", "-e", "implicitly declared|has no driver", "-l", str(tmp / f"{tag}.log"),
                        "-s", str(path)], capture_output=True, text=True)
    if r.returncode != 0:
        log = tmp / f"{tag}.log"
        tail = "\n".join(log.read_text().splitlines()[-30:]) if log.exists() else ""
        raise RuntimeError(f"yosys ({tag}) failed:\n{tail}\n{r.stderr}")
    return time.time() - t0


def hierarchy_of(stat: dict) -> dict:
    """Derived module -> {sub-module: instances} from an elaborated design's `stat -json`."""
    mods = stat["modules"]
    return {m: {c: n for c, n in v.get("num_cells_by_type", {}).items() if c in mods} for m, v in mods.items()}


def instance_counts(subs: dict, top: str) -> dict:
    count = {}

    def walk(name, k):
        count[name] = count.get(name, 0) + k
        for sub, n in subs[name].items():
            walk(sub, k * n)
    walk(top, 1)
    return count


def block_counts(subs: dict, top: str) -> dict:
    """(derived module, block) -> instances, as synth.py counts blocks (synth.block_instances)."""
    count = {}
    for (name, b, _), k in syn().block_instances(subs, top).items():
        count[(name, b)] = count.get((name, b), 0) + k
    return count


def elaborate(profile: pathlib.Path, rom_dir: pathlib.Path, lib: pathlib.Path, tmp: pathlib.Path) -> dict:
    """Derived modules of the profile's pst_top and their instance counts (Yosys `hierarchy`)."""
    script = "\n".join(_read_lines(profile, rom_dir, lib) + [
        "hierarchy -check -top pst_top", f"tee -q -o {tmp}/hier.json stat -json"]) + "\n"
    _yosys(script, tmp, "elab")
    subs = hierarchy_of(syn().parse_stat_json((tmp / "hier.json").read_text()))
    top = next(m for m in subs if syn().base_name(m) == "pst_top")
    return {"subs": subs, "top": top, "count": instance_counts(subs, top)}


def synthesize_modules(profile, rom_dir, lib, tmp: pathlib.Path, keep: set, all_mods: list) -> dict:
    """Synthesizes every derived module except KEEP (black boxes): name -> {area, ffs, cells}."""
    s = syn()
    (tmp / "abc.constr").write_text(s.ABC_CONSTR)
    lines = _read_lines(profile, rom_dir, lib) + ["hierarchy -check -top pst_top"]
    bb = [m for m in all_mods if m in keep]
    if bb:
        lines.append("blackbox " + " ".join(_yname(m) for m in bb))
    lines += [
        "synth -top pst_top -run :fine",
        "opt -fast -full",
        f"techmap -map {s.STANDIN_MAP} t:$mem_v2",
        "techmap", "opt -fast", "async2sync", "dfflegalize -cell $_DFF_P_ 01",
        s.abc_line(lib, tmp / "abc.constr"),
        "opt_clean -purge",
        f"dfflibmap -liberty {lib}",
        "opt_clean -purge",
        f"tee -q -o {tmp}/stat.json stat -json",
    ]
    secs = _yosys("\n".join(lines) + "\n", tmp, "synth")
    lib_text = lib.read_text()
    areas = liberty.cell_areas(lib_text)
    ffc = liberty.flip_flop_cells(lib_text)
    stat = s.parse_stat_json((tmp / "stat.json").read_text())
    out = {}
    for name, m in stat["modules"].items():
        if name in keep or name.lstrip("\\") in {k.lstrip("\\") for k in keep}:
            continue
        cells = m.get("num_cells_by_type", {})
        out[name] = {"area_um2": sum(n * areas[c] for c, n in cells.items() if c in areas),
                     "flip_flops": sum(n for c, n in cells.items() if c in ffc),
                     "cells": sum(n for c, n in cells.items() if c in areas)}
    return {"modules": out, "seconds": secs}


def _yname(m: str) -> str:
    """A module name as a Yosys command argument (derived names hold '$' and '\\')."""
    return m if m.startswith("\\") or m.startswith("$") else "\\" + m


class ModuleCache:
    """Per-module synthesis results in DIR/<key>.json (atomic writes; safe across threads and
    processes: two writers of one key write the same content)."""

    def __init__(self, directory: pathlib.Path, lib: pathlib.Path, rom_dir: pathlib.Path):
        self.dir = pathlib.Path(directory)
        self.lib = lib
        self.rom_dir = rom_dir
        self.salt = flow_salt(lib)
        self.ge_um2 = liberty.ge_unit(liberty.cell_areas(lib.read_text()))

    def get(self, key):
        try:
            return json.loads((self.dir / f"{key}.json").read_text())
        except (OSError, ValueError):
            return None

    def put(self, key, rec):
        atomic.write_text(self.dir / f"{key}.json", json.dumps(rec, indent=1) + "\n")

    def area(self, profile: pathlib.Path) -> dict:
        """Logic GE of the profile (blocks, per module) and how many modules were synthesized now."""
        t0 = time.time()
        with tempfile.TemporaryDirectory(prefix="pst_modsyn_") as t:
            tmp = pathlib.Path(t)
            h = elaborate(profile, self.rom_dir, self.lib, tmp)
            keys = {m: module_key(m, self.salt) for m in h["count"]}
            have = {m: self.get(k) for m, k in keys.items()}
            missing = {m for m, r in have.items() if r is None}
            # A missing module's ancestors are synthesized too (a black box hides its children).
            parents = {}
            for p, subs in h["subs"].items():
                for c in subs:
                    parents.setdefault(c, set()).add(p)
            todo, stack = set(missing), list(missing)
            while stack:
                for p in parents.get(stack.pop(), ()):
                    if p not in todo and p in h["count"]:
                        todo.add(p)
                        stack.append(p)
            secs = 0.0
            if todo:
                keep = set(h["count"]) - todo
                r = synthesize_modules(profile, self.rom_dir, self.lib, tmp, keep, list(h["count"]))
                secs = r["seconds"]
                got = {k.lstrip("\\"): v for k, v in r["modules"].items()}
                for m in todo:
                    rec = got.get(m.lstrip("\\"))
                    if rec is None:
                        raise RuntimeError(f"module {m}: not in the synthesized design's stat")
                    rec = dict(rec, module=m, base=syn().base_name(m))
                    self.put(keys[m], rec)
                    have[m] = rec
        blocks = {}
        modules = {}
        total = 0.0
        for (m, b), n in block_counts(h["subs"], h["top"]).items():
            blocks[b] = blocks.get(b, 0.0) + n * have[m]["area_um2"]
        for m, n in h["count"].items():
            rec = have[m]
            a = n * rec["area_um2"]
            total += a
            base = syn().base_name(m)
            e = modules.setdefault(base, {"instances": 0, "ge": 0.0})
            e["instances"] += n
            e["ge"] += a / self.ge_um2
        return {"logic_ge": round(total / self.ge_um2),
                "blocks": {b: round(v / self.ge_um2) for b, v in blocks.items()},
                "modules": {k: {"instances": v["instances"], "ge": round(v["ge"])} for k, v in sorted(modules.items())},
                "flip_flops": sum(n * have[m]["flip_flops"] for m, n in h["count"].items()),
                "modules_synthesized": len(todo), "modules_total": len(h["count"]),
                "yosys_seconds": round(secs, 1), "seconds": round(time.time() - t0, 1)}

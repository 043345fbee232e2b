"""Logic area of a profile from a per-module synthesis cache: a profile that changes one format
re-synthesizes only the modules that format reaches (what the design-space search uses).

The flow of pstlib.synth.flow split in two Yosys runs:
1. elaboration only (`hierarchy` after the profile's chparam; seconds): the derived modules,
   each named by Yosys from its parameter values ($paramod$<sha1 of the parameters>\\NAME, or
   the values spelled out), and which module instantiates which, how often;
2. synthesis of the derived modules not in the cache (the others are turned into black boxes
   first, so their instances stay cells and cost nothing), with the flow's own mapping
   (pstlib.synth.tools.map_lines): stat per module.
A module's cache key is its derived name (its parameter values), the text of its source file,
rtl/pst_pkg.sv and rtl/*.svh, and the flow (flow_salt: the ABC line, every input of
pstlib.synth.inputs but the other RTL sources, the tool versions): a change elsewhere in rtl/
keeps it. Area = sum over derived modules of
instances x own cells' area, as the flow counts it (memories outside: stand-ins without area).
Fmax is not part of this (it needs the whole netlist): pstlib.synth.flow gives it.
"""
import hashlib
import json
import pathlib
import tempfile
import time

from .. import atomic
from ..paths import ROOT, rtl_source
from . import blocks, inputs, liberty
from .tools import (ABC_CONSTR, ABC_DELAY_PS, ABC_SCRIPT, base_name, hierarchy_of, map_lines,
                    parse_stat_json, read_lines, run_yosys)


def _sha(*parts) -> str:
    h = hashlib.sha256()
    for p in parts:
        h.update(p if isinstance(p, bytes) else str(p).encode())
        h.update(b"\0")
    return h.hexdigest()[:20]


def flow_salt(lib: pathlib.Path, rom_dir: pathlib.Path) -> str:
    """What every module's gates depend on besides its own source and parameters: the mapping,
    every input of pstlib.synth.inputs but the RTL's .sv files (the flow's code, the contract,
    scripts/synth/, the cell library's content, the ROM images) and the tool versions."""
    return inputs.digest(inputs.input_files(lib, rom_dir, rtl_sv=False),
                         (ABC_SCRIPT, ABC_DELAY_PS, ABC_CONSTR, "module-flow-2", *inputs.tool_versions()))


def module_key(derived: str, salt: str) -> str:
    shared = [rtl_source("pst_pkg"), *sorted((ROOT / "rtl").rglob("*.svh"))]
    src = rtl_source(base_name(derived))
    texts = [p.read_bytes() for p in ([src] if src else []) + [p for p in shared if p]]
    return _sha(derived, salt, *texts)


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
    for (name, b, _), k in blocks.block_instances(subs, top).items():
        count[(name, b)] = count.get((name, b), 0) + k
    return count


def elaborate(doc: dict, rom_dir: pathlib.Path, lib: pathlib.Path, tmp: pathlib.Path) -> dict:
    """Derived modules of the profile's pst_top and their instance counts (Yosys `hierarchy`)."""
    script = "\n".join(read_lines(doc, rom_dir, lib) + [
        "hierarchy -check -top pst_top", f"tee -q -o {tmp}/hier.json stat -json"]) + "\n"
    run_yosys(script, tmp, "elab")
    subs = hierarchy_of(parse_stat_json((tmp / "hier.json").read_text()))
    top = next(m for m in subs if base_name(m) == "pst_top")
    return {"subs": subs, "top": top, "count": instance_counts(subs, top)}


def synthesize_modules(doc: dict, rom_dir, lib, tmp: pathlib.Path, keep: set, all_mods: list) -> dict:
    """Synthesizes every derived module except KEEP (black boxes): name -> {area, ffs, cells}."""
    (tmp / "abc.constr").write_text(ABC_CONSTR)
    lines = read_lines(doc, rom_dir, lib) + ["hierarchy -check -top pst_top"]
    bb = [m for m in all_mods if m in keep]
    if bb:
        lines.append("blackbox " + " ".join(_yname(m) for m in bb))
    lines += [
        "synth -top pst_top -run :fine",
        "opt -fast -full",
        *map_lines(lib, tmp),
    ]
    secs = run_yosys("\n".join(lines) + "\n", tmp, "synth")
    lib_text = lib.read_text()
    areas = liberty.cell_areas(lib_text)
    ffc = liberty.flip_flop_cells(lib_text)
    stat = parse_stat_json((tmp / "stat.json").read_text())
    # Sub-modules (the black boxes too) and memory stand-ins have no area of their own here.
    subs = {*stat["modules"], *keep, *(_yname(m) for m in keep), *liberty.STANDIN_TYPES}
    out = {}
    for name, m in stat["modules"].items():
        if name in keep or name.lstrip("\\") in {k.lstrip("\\") for k in keep}:
            continue
        cells = m.get("num_cells_by_type", {})
        area = liberty.cells_area(cells, areas, skip=subs)
        out[name] = {"area_um2": area,
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
        self.salt = flow_salt(lib, rom_dir)
        self.ge_um2 = liberty.ge_unit(liberty.cell_areas(lib.read_text()))

    def get(self, key):
        try:
            return json.loads((self.dir / f"{key}.json").read_text())
        except (OSError, ValueError):
            return None

    def put(self, key, rec):
        atomic.write_text(self.dir / f"{key}.json", json.dumps(rec, indent=1) + "\n")

    def area(self, doc: dict) -> dict:
        """Logic GE of the profile (blocks, per module) and how many modules were synthesized now."""
        t0 = time.time()
        with tempfile.TemporaryDirectory(prefix="pst_modsyn_") as t:
            tmp = pathlib.Path(t)
            h = elaborate(doc, self.rom_dir, self.lib, tmp)
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
                r = synthesize_modules(doc, self.rom_dir, self.lib, tmp, keep, list(h["count"]))
                secs = r["seconds"]
                got = {k.lstrip("\\"): v for k, v in r["modules"].items()}
                for m in todo:
                    rec = got.get(m.lstrip("\\"))
                    if rec is None:
                        raise RuntimeError(f"module {m}: not in the synthesized design's stat")
                    rec = dict(rec, module=m, base=base_name(m))
                    self.put(keys[m], rec)
                    have[m] = rec
        per_block = {}
        modules = {}
        total = 0.0
        for (m, b), n in block_counts(h["subs"], h["top"]).items():
            per_block[b] = per_block.get(b, 0.0) + n * have[m]["area_um2"]
        for m, n in h["count"].items():
            rec = have[m]
            a = n * rec["area_um2"]
            total += a
            base = base_name(m)
            e = modules.setdefault(base, {"instances": 0, "ge": 0.0})
            e["instances"] += n
            e["ge"] += a / self.ge_um2
        return {"logic_ge": round(total / self.ge_um2),
                "blocks": {b: round(v / self.ge_um2) for b, v in per_block.items()},
                "modules": {k: {"instances": v["instances"], "ge": round(v["ge"])} for k, v in sorted(modules.items())},
                "flip_flops": sum(n * have[m]["flip_flops"] for m, n in h["count"].items()),
                "modules_synthesized": len(todo), "modules_total": len(h["count"]),
                "yosys_seconds": round(secs, 1), "seconds": round(time.time() - t0, 1)}

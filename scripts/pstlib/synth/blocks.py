"""The report's blocks, read off the elaborated hierarchy (no hand-written module list).

A block is a module the design holds at depth 1 to 4 (BLOCK_DEPTH: the top's children, the
pipeline's stages; theirs, the octave datapath, the noise units, the filter width, the
colour-table filter; and two levels of units below: quadric, octave lane, transform, term,
fade, noise, worley, the noise unit's weights, corners, lerps and ROMs, ...), named after its module without the `pst_`
prefix; the top's own logic is the block `top`. A building block (a module instantiated by
more than one module: pst_delay, pst_mul_booth, pst_floor_sat, pst_isqrt, pst_pipe_flow, ...)
and anything deeper than BLOCK_DEPTH counts in the block of the instance holding it. Blocks
come in the order of the hierarchy: a module's children in the order its source instantiates
them, the top's own row last.
"""
import re

from ..paths import rtl_source
from . import liberty
from .tools import base_name

BLOCK_DEPTH = 4
TOP_BLOCK = "top"


def block_name(base: str) -> str:
    return base[4:] if base.startswith("pst_") else base


def building_blocks(subs: dict) -> set:
    """Source modules instantiated by more than one source module of the design."""
    parents = {}
    for name, children in subs.items():
        for c in children:
            parents.setdefault(base_name(c), set()).add(base_name(name))
    return {b for b, ps in parents.items() if len(ps) > 1}


def source_position(parent: str, child: str) -> int:
    """Where the source of module PARENT first names module CHILD (for the row order)."""
    src = rtl_source(parent)
    text = src.read_text() if src else ""
    m = re.search(rf"\b{re.escape(child)}\b", text)
    return m.start() if m else len(text)


def block_instances(subs: dict, top: str, position=source_position) -> dict:
    """(derived module, block, holder) -> instances in the flattened design, in the blocks'
    order. holder: the base name of the nearest enclosing module that is not a building block
    (None for the top)."""
    shared = building_blocks(subs)
    count = {}

    def walk(name: str, k: int, depth: int, block: str, holder) -> None:
        own = base_name(name)
        if 0 < depth <= BLOCK_DEPTH and own not in shared:
            block = block_name(own)
        count[(name, block, holder)] = count.get((name, block, holder), 0) + k
        inner = holder if own in shared else own
        for sub, n in sorted(subs[name].items(), key=lambda kv: (position(own, base_name(kv[0])), kv[0])):
            walk(sub, k * n, depth + 1, block, inner)
    walk(top, 1, 0, TOP_BLOCK, None)
    order = list(dict.fromkeys(b for (_, b, _) in count if b != TOP_BLOCK)) + [TOP_BLOCK]
    return {key: count[key] for b in order for key in count if key[1] == b}


def module_label(name: str, holder, shared: set) -> str:
    """A module's row in its block: a building block is listed per module holding it (the
    Booth products of the lerps are the figure a designer acts on)."""
    own = base_name(name)
    return f"{own} in {holder}" if own in shared and holder is not None else own


def analyse(stat: dict, ltp_text: str, areas: dict, ff_cells: set, mems: list) -> dict:
    """Per block: area, flip-flops, cells and the modules in it; per memory its instances."""
    modules = stat["modules"]
    own = {}
    for name, m in modules.items():
        cells = m.get("num_cells_by_type", {})
        try:
            logic = liberty.cells_area(cells, areas, skip=(*modules, *liberty.STANDIN_TYPES))
        except RuntimeError as e:
            raise RuntimeError(f"module {name}: {e}") from None
        own[name] = {"logic": logic,
                     "ffs": sum(n for c, n in cells.items() if c in ff_cells),
                     "subs": {c: n for c, n in cells.items() if c in modules},
                     "cells": sum(n for c, n in cells.items() if c in areas)}
    depth = {m.group(1): int(m.group(2))
             for m in re.finditer(r"Longest topological path in (\S+) \(length=(\d+)\)", ltp_text)}
    subs = {name: v["subs"] for name, v in own.items()}
    top = next(n for n in modules if base_name(n) == "pst_top")
    held = block_instances(subs, top)
    shared = building_blocks(subs)
    blocks = {}
    for (name, b, holder), k in held.items():
        v = blocks.setdefault(b, {"area": 0.0, "ffs": 0, "cells": 0, "modules": {}})
        v["area"] += k * own[name]["logic"]
        v["ffs"] += k * own[name]["ffs"]
        v["cells"] += k * own[name]["cells"]
        entry = v["modules"].setdefault(module_label(name, holder, shared), {"instances": 0, "area": 0.0, "depth": 0})
        entry["instances"] += k
        entry["area"] += k * own[name]["logic"]
        entry["depth"] = max(entry["depth"], depth.get(name.lstrip("\\"), depth.get(name, 0)))
    inst = {}
    for m in mems:
        inst[(m["module"], m["memory"])] = sum(k for (name, _, _), k in held.items()
                                               if name.lstrip("\\") == m["module"].lstrip("\\"))
    return {"blocks": blocks, "depth": depth, "held": held, "mem_instances": inst, "top": top}

"""The profile's flattened netlist cut into blocks small enough for qflow's placer and router.

A block is every cell whose flattened name starts with an instance path (`u_width.`), less
the blocks nested inside it; what no block claims is the block `top` (the top's glue, pipeline
registers and small units). Memory stand-ins belong to no block: they are the macros, and the
nets into and out of them become block pins.

The cut is chosen from the cell counts alone (`choose`): a top-level instance is a block; one
larger than LIMIT cells gives up its largest sub-instances (each cut again the same way) until
what it keeps is at most LIMIT (a module with more cells of its own stays whole); instances under MIN_CELLS stay in `top`. graywolf and qrouter
take about 10 + 4 minutes for 20k cells here (../shared/DESIGN.md section 9), so LIMIT is 25k.
"""
import collections
import re

LIMIT = 25000
MIN_CELLS = 2000
TOP = "pst_top"
ASSEMBLY_BLIF = "assembly.blif"


def parent(path: str) -> str:
    """The instance path holding a flattened name ('u_a.u_b._12_' -> 'u_a.u_b'; '' at the top).
    Generate scopes (`g_lane[0]`) are part of the path like instances."""
    return path.rsplit(".", 1)[0] if "." in path else ""


def subtree_counts(cells: list) -> collections.Counter:
    """Instance path -> number of cells at or below it ('' is the whole design)."""
    n = collections.Counter()
    for c in cells:
        p = parent(c)
        while True:
            n[p] += 1
            if not p:
                break
            p = parent(p)
    return n


def children(counts: dict, path: str) -> list:
    """Direct sub-paths of PATH, largest first."""
    pre = path + "." if path else ""
    kids = [p for p in counts if p.startswith(pre) and p != path and "." not in p[len(pre):]]
    return sorted(kids, key=lambda p: (-counts[p], p))


def _cut(counts: dict, path: str, limit: int) -> list:
    """PATH and the sub-paths pulled out of it so that none keeps more than LIMIT cells."""
    out = [path]
    keep = counts[path]
    for kid in children(counts, path):
        if keep <= limit:
            break
        out += _cut(counts, kid, limit)
        keep -= counts[kid]
    return out


def choose(cells: list, limit: int = LIMIT, min_cells: int = MIN_CELLS) -> list:
    """Block instance paths (largest cut first) for flattened cell names CELLS (no module
    prefix, memory stand-ins left out)."""
    counts = subtree_counts(cells)
    blocks = []
    for kid in children(counts, ""):
        if counts[kid] >= min_cells:
            blocks += _cut(counts, kid, limit)
    # A path that keeps no cell of its own (a generate scope around one instance) is no block.
    kept = assign(cells, blocks)
    return [b for b in blocks if block_name(b) in kept]


def block_name(path: str) -> str:
    """A file-safe name for a block's instance path ('u_octave.g_noise[0]' -> 'u_octave_g_noise_0')."""
    return re.sub(r"_+", "_", re.sub(r"[^A-Za-z0-9_]", "_", path)).strip("_") or "top"


def assign(cells: list, blocks: list) -> dict:
    """Block name -> its cells: each cell to the longest block path it lies under, else `top`."""
    by_len = sorted(blocks, key=len, reverse=True)
    out = collections.defaultdict(list)
    for c in cells:
        b = next((p for p in by_len if c.startswith(p + ".")), None)
        out[block_name(b) if b else "top"].append(c)
    return dict(out)


def parse_group(spec: str) -> tuple:
    """'NAME=PATH[+PATH...]' (scripts/pnr.py --group) -> (NAME, [PATH, ...]); ValueError when malformed."""
    name, sep, rest = spec.partition("=")
    paths = [p.strip() for p in rest.split("+") if p.strip()]
    if not sep or not paths or not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name) or name == "top":
        raise ValueError(f"--group {spec!r}: expected NAME=PATH[+PATH...] with NAME a file-safe name other than top")
    return name, paths


def claim(cells: list, groups: dict) -> tuple:
    """(name -> its cells, the cells left) for named blocks GROUPS (name -> instance paths): a
    block of several instances, so that a critical path from one instance's registers into
    another's lies inside one block (a path crossing a block's edge is timed on the SDC's pin
    budgets instead). A cell goes to the first group with a path it lies under; ValueError for a
    path with no cell."""
    out = {name: [] for name in groups}
    left = []
    flat = [(name, p) for name, paths in groups.items() for p in paths]
    used = set()
    for c in cells:
        hit = next(((name, p) for name, p in flat if c.startswith(p + ".")), None)
        if hit:
            out[hit[0]].append(c)
            used.add(hit)
        else:
            left.append(c)
    empty = [p for name, p in flat if (name, p) not in used]
    if empty:
        raise ValueError(f"--group: no cell under {empty[0]!r}")
    return out, left


def list_script(libs: list, netlist, top: str, out) -> str:
    """Yosys: the design flattened, its cell names (`top/name` lines) into OUT."""
    return "\n".join([*(f"read_liberty -lib {lib}" for lib in libs), f"read_verilog {netlist}",
                      f"hierarchy -top {top}", "flatten", f"tee -q -o {out} select -list t:*", ""])


def split_script(libs: list, netlist, top: str, selections: dict, outdir, keep_types: str,
                 assembly: bool = True) -> str:
    """Yosys: the flattened design's blocks (name -> a `select -read` file of `top/cell` lines)
    each moved into a module blk_NAME (`submod`: nets crossing its edge become ports) and
    written alone to OUTDIR/blk_NAME.v (and .blif, its pre-layout netlist for the assembled
    timing when it has no layout), and the top level that connects them to
    OUTDIR/ASSEMBLY_BLIF. Cells of type KEEP_TYPES (the memory stand-ins) stay
    outside every block."""
    lines = [*(f"read_liberty -lib {lib}" for lib in libs), f"read_verilog {netlist}",
             f"hierarchy -top {top}", "flatten"]
    for name, sel in selections.items():
        lines += [f"select -read {sel}", f"select -set s_{name} % t:{keep_types} %d", "select -clear"]
    lines += [f"submod -name blk_{name} @s_{name}" for name in selections]
    if not assembly:
        # A few blocks of a large design: only their modules kept (the whole flattened design
        # saved and loaded per block, as below, needs over 22 GB for full).
        lines += [f"design -copy-to pst_blocks {' '.join(f'blk_{n}' for n in selections)}"]
        for name in selections:
            lines += ["design -reset", *(f"read_liberty -lib {lib}" for lib in libs),
                      f"design -copy-from pst_blocks -as blk_{name} blk_{name}", f"hierarchy -top blk_{name}",
                      f"write_verilog -noattr {outdir}/blk_{name}.v",
                      f"write_blif -buf BUFX2 A Y -gates {outdir}/blk_{name}.blif"]
        return "\n".join(lines) + "\n"
    lines += ["design -save split"]
    for name in selections:
        lines += ["design -load split", f"hierarchy -top blk_{name}",
                  f"write_verilog -noattr {outdir}/blk_{name}.v",
                  f"write_blif -buf BUFX2 A Y -gates {outdir}/blk_{name}.blif"]
    # The top level alone (blocks as black boxes, memory stand-ins, net aliases as .conn):
    # what connects the blocks (pstlib/pnr/assembly.py).
    lines += ["design -load split", f"hierarchy -top {top}", "blackbox blk_*",
              f"write_blif -conn -gates {outdir}/{ASSEMBLY_BLIF}"]
    return "\n".join(lines) + "\n"

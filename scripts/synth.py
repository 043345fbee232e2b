#!/usr/bin/python3
"""Gate count of one hardware profile: Yosys 0.23 synthesis of pst_top to the small generic
cell library scripts/synth/cells.lib, reported in NAND2 gate equivalents (GE).

    scripts/synth.py PROFILE [--out DIR] [--rom-dir DIR] [--yosys yosys]

PROFILE is a name (rtl/configs/NAME.toml) or a profile file. Writes DIR/NAME.json and
DIR/NAME.md (default DIR: out/synth) and prints the Markdown table.

Method (docs/HARDWARE.md has the blocks):
- Hierarchical synthesis: every module is synthesized once per parameter set and counted
  once per instance, so the eight identical noise units of `full` cost one synthesis.
- Memories stay memories (`memory -nomap`): the hash and value ROMs and the colour-table
  RAMs are reported as ROM/RAM bits (depth x width, once per memory instance, whatever its
  number of read ports), outside the logic count, as designers report them. Constant
  tables written as logic (the SAT reciprocal table) are logic.
- Flip-flops: async resets are turned into logic (`async2sync`) and every flop is the one
  DFF cell (4.33 GE); the flop count is reported on its own too.
- Logic depth: `ltp -noff` per module (cells on the longest combinational path; a
  sub-module instance counts as one cell there, so a stage's depth is the sum of the
  modules chained in it; see the `stages` table).
- Yosys runs with -e "implicitly declared|has no driver" so a silent mis-build fails.
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
LIB = ROOT / "scripts" / "synth" / "cells.lib"

# Module (base name) -> block of the report.
BLOCKS = {
    "pst_quadric": "quadric",
    "pst_quadric_serial": "quadric",
    "pst_octave_transform": "noise",
    "pst_noise": "noise",
    "pst_noise_weight": "noise",
    "pst_noise_corner": "noise",
    "pst_noise_lerp": "noise",
    "pst_octave_term": "octave accumulation",
    "pst_filter_width": "gradient and filter width",
    "pst_isqrt": "gradient and filter width",
    "pst_clut_filter": "colour-table filter",
    "pst_pipe_reg": "control",
    "pst_top": "control",
}
BLOCK_ORDER = ["quadric", "noise", "octave accumulation", "gradient and filter width",
               "colour-table filter", "control"]
# Pipeline stages and the modules chained in each (for the depth table).
STAGES = [
    ("octave stage ([A] -> [B])", ["pst_octave_transform", "pst_noise", "pst_octave_term", "pst_top"]),
    ("quadric (parallel to the octaves)", ["pst_quadric", "pst_quadric_serial"]),
    ("filter width ([B] -> [C])", ["pst_filter_width"]),
    ("colour-table filter ([C] -> [D])", ["pst_clut_filter"]),
]


def cell_areas(lib: pathlib.Path) -> dict:
    """Cell name -> area, read from the liberty file (the one place the areas live)."""
    text = lib.read_text()
    return {m.group(1): float(m.group(2))
            for m in re.finditer(r"cell\((\w+)\)\s*\{\s*area\s*:\s*([0-9.]+)", text)}


def profile_path(name: str) -> pathlib.Path:
    p = pathlib.Path(name)
    if p.suffix == ".toml" or "/" in name:
        return p
    return ROOT / "rtl" / "configs" / f"{name}.toml"


def base_name(module: str) -> str:
    m = re.search(r"(pst_[A-Za-z0-9_]+)", module)
    return m.group(1) if m else module.lstrip("\\")


def yosys_script(profile: pathlib.Path, rom_dir: pathlib.Path, stat_json: str, ltp_txt: str, mem_txt: str) -> str:
    params = subprocess.run(["/usr/bin/python3", str(ROOT / "scripts" / "profile.py"), str(profile), "--yosys"],
                            check=True, capture_output=True, text=True).stdout.split("\n")
    chparams = [f"{line} pst_top" for line in params if line.strip()]
    sources = " ".join(str(p) for p in sorted((ROOT / "rtl").glob("*.sv")))
    lines = [
        f"read_liberty -lib {LIB}",  # cell port directions, for ltp
        f'read_verilog -sv -D SYNTHESIS -D PST_ROM_DIR="{rom_dir}" {sources}',
        *chparams,
        "chparam -set DebugProbes 0 pst_top",
        "hierarchy -check -top pst_top",
        # Coarse synthesis with memories kept as $mem cells.
        "synth -top pst_top -run :fine",
        # The memories' shapes (SIZE, WIDTH, read ports) for the memory-bit table.
        f"tee -q -o {mem_txt} select -list t:$mem_v2",
        f"tee -q -a {mem_txt} dump t:$mem_v2",
        "opt -fast -full",
        "techmap",
        "opt -fast",
        "async2sync",
        "dfflegalize -cell $_DFF_P_ 01",
        f"abc -fast -liberty {LIB}",  # the default script takes minutes per multiplier-heavy module
        "opt_clean -purge",
        # Depth before the flops become library cells: ltp -noff skips the internal $_DFF_P_
        # cells, so a path ends at a register (a library DFF would be walked through).
        f"tee -q -o {ltp_txt} ltp -noff",
        f"dfflibmap -liberty {LIB}",
        "opt_clean -purge",
        f"tee -q -o {stat_json} stat -json",
    ]
    return "\n".join(lines) + "\n"


def parse_stat_json(text: str) -> dict:
    """Yosys 0.23's `stat -json` prints the hierarchy as plain text inside its "design"
    section when the design has sub-modules; only the "modules" section is used here, so the
    text is cut after it."""
    end = text.find("\n   },\n")
    stat = json.loads(text if end < 0 else text[:end] + "\n   }\n}\n")
    return stat


def parse_memories(text: str) -> list:
    """(module, memory, size, width, read ports, write ports) of every $mem_v2 cell; the
    `select -list` lines and the `dump` blocks come in the same order."""
    names = [line.strip() for line in text.splitlines() if "/" in line and not line.startswith(" ")
             and not line.startswith("attribute")]
    blocks = re.split(r"\n\s*cell \$mem_v2 ", text)[1:]
    mems = []
    for name, block in zip(names, blocks):
        param = lambda key: int(re.search(rf"parameter \\{key} (\d+)", block).group(1))
        module, memory = name.split("/", 1)
        mems.append({"module": module, "memory": memory, "size": param("SIZE"), "width": param("WIDTH"),
                     "read_ports": param("RD_PORTS"), "write_ports": param("WR_PORTS")})
    if len(names) != len(blocks):
        raise RuntimeError(f"memory listing mismatch: {len(names)} names, {len(blocks)} cells")
    return mems


def analyse(stat: dict, ltp_text: str, areas: dict, mems: list) -> dict:
    modules = stat["modules"]
    own = {}
    for name, m in modules.items():
        cells = m.get("num_cells_by_type", {})
        logic = sum(n * areas[c] for c, n in cells.items() if c in areas)
        ffs = cells.get("DFF", 0)
        subs = {c: n for c, n in cells.items() if c in modules}
        own[name] = {"logic": logic, "ffs": ffs, "subs": subs}
    depth = {}
    for m in re.finditer(r"Longest topological path in (\S+) \(length=(\d+)\)", ltp_text):
        depth[m.group(1)] = int(m.group(2))

    # Instance counts of every module under the top (hierarchy walk).
    count = {}

    def walk(name: str, k: int) -> None:
        count[name] = count.get(name, 0) + k
        for sub, n in own[name]["subs"].items():
            walk(sub, k * n)

    top = next(n for n in modules if base_name(n) == "pst_top")
    walk(top, 1)
    blocks = {b: {"logic_ge": 0.0, "ffs": 0, "modules": {}} for b in BLOCK_ORDER}
    for name, k in count.items():
        b = BLOCKS.get(base_name(name), "control")
        blocks[b]["logic_ge"] += k * own[name]["logic"]
        blocks[b]["ffs"] += k * own[name]["ffs"]
        entry = blocks[b]["modules"].setdefault(base_name(name), {"instances": 0, "logic_ge_each": 0.0, "depth": 0})
        entry["instances"] += k
        entry["logic_ge_each"] = max(entry["logic_ge_each"], own[name]["logic"])
        entry["depth"] = max(entry["depth"], depth.get(name.lstrip("\\"), depth.get(name, 0)))
    # Memories: depth x width bits per instance; a memory with several read ports is one
    # multi-ported array (or that many single-ported copies: bits x read ports).
    memories = []
    for m in mems:
        k = next((n for name, n in count.items() if name.lstrip("\\") == m["module"].lstrip("\\")), 0)
        if k == 0:
            continue
        memories.append({"module": base_name(m["module"]), "memory": m["memory"].lstrip("\\"),
                         "kind": "RAM" if m["write_ports"] else "ROM", "instances": k,
                         "size": m["size"], "width": m["width"], "read_ports": m["read_ports"],
                         "bits_each": m["size"] * m["width"]})
    return {"blocks": blocks, "memories": memories, "depth": depth, "count": count}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profile")
    ap.add_argument("--out", default=str(ROOT / "out" / "synth"))
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    ap.add_argument("--yosys", default="yosys")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args()

    profile = profile_path(args.profile)
    if not profile.exists():
        print(f"error: {profile}: no such profile", file=sys.stderr)
        return 2
    rom_dir = pathlib.Path(args.rom_dir)
    if not (rom_dir / "hash4096.memh").exists():
        print(f"error: {rom_dir}: no ROM images (build first: cmake --build build --target pst_rom_images)",
              file=sys.stderr)
        return 2
    name = profile.stem
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    areas = cell_areas(LIB)

    with tempfile.TemporaryDirectory(prefix=f"pst_synth_{name}_") as tmp:
        stat_json = f"{tmp}/stat.json"
        ltp_txt = f"{tmp}/ltp.txt"
        mem_txt = f"{tmp}/mem.txt"
        script = pathlib.Path(tmp) / "synth.ys"
        script.write_text(yosys_script(profile, rom_dir, stat_json, ltp_txt, mem_txt))
        t0 = time.time()
        run = subprocess.run([args.yosys, "-q", "-e", "implicitly declared|has no driver", "-l", f"{tmp}/yosys.log",
                              "-s", str(script)], capture_output=True, text=True)
        seconds = time.time() - t0
        if run.returncode != 0:
            log = pathlib.Path(f"{tmp}/yosys.log")
            tail = "\n".join(log.read_text().splitlines()[-30:]) if log.exists() else run.stderr
            print(f"error: yosys failed on {profile}:\n{tail}\n{run.stderr}", file=sys.stderr)
            return 1
        raw = pathlib.Path(stat_json).read_text()
        (out / f"{name}.stat.json").write_text(raw)
        stat = parse_stat_json(raw)
        ltp_text = pathlib.Path(ltp_txt).read_text()
        mem_raw = pathlib.Path(mem_txt).read_text()
        (out / f"{name}.ltp.txt").write_text(ltp_text)
        (out / f"{name}.mem.txt").write_text(mem_raw)
        mems = parse_memories(mem_raw)

    a = analyse(stat, ltp_text, areas, mems)
    total = sum(b["logic_ge"] for b in a["blocks"].values())
    ffs = sum(b["ffs"] for b in a["blocks"].values())
    result = {
        "profile": name,
        "profile_file": str(profile),
        "yosys_seconds": round(seconds, 1),
        "logic_ge": round(total),
        "flip_flops": ffs,
        "blocks": {b: {"logic_ge": round(v["logic_ge"]), "flip_flops": v["ffs"], "modules": v["modules"]}
                   for b, v in a["blocks"].items()},
        "memories": a["memories"],
        "rom_bits": sum(m["instances"] * m["bits_each"] for m in a["memories"] if m["kind"] == "ROM"),
        "ram_bits": sum(m["instances"] * m["bits_each"] for m in a["memories"] if m["kind"] == "RAM"),
    }
    md = [f"## Gates: profile `{name}`\n",
          f"Yosys 0.23, hierarchical, {seconds:.0f} s. Logic in NAND2 gate equivalents (cells.lib); "
          "memories outside the logic count.\n",
          "| block | logic GE | flip-flops | modules (instances x GE each, depth in cells) |",
          "|---|---:|---:|---|"]
    for b in BLOCK_ORDER:
        v = result["blocks"][b]
        mods = ", ".join(f"{m} {e['instances']} x {e['logic_ge_each']:.0f} (depth {e['depth']})"
                         for m, e in sorted(v["modules"].items()))
        md.append(f"| {b} | {v['logic_ge']:,} | {v['flip_flops']:,} | {mods} |")
    md.append(f"| **total** | **{result['logic_ge']:,}** | **{ffs:,}** | |")
    md.append("")
    md.append("| memory | kind | instances | words x bits | read ports | bits |")
    md.append("|---|---|---:|---|---:|---:|")
    for m in result["memories"]:
        md.append(f"| {m['module']}.{m['memory']} | {m['kind']} | {m['instances']} | {m['size']} x {m['width']} | "
                  f"{m['read_ports']} | {m['instances'] * m['bits_each']:,} |")
    md.append(f"| **total** | | | | | **ROM {result['rom_bits']:,}, RAM {result['ram_bits']:,}** |")
    md.append("")
    depth = {base_name(k): v for k, v in a["depth"].items()}
    md.append("The sum of the chained modules' depths bounds the stage's longest path from above; "
              "with the serial datapath the transform, noise and term are separated by registers, so "
              "the octave stage's real path is the longest single module plus the accumulation "
              "(each module's own depth is in the table above).\n")
    md.append("| pipeline stage | modules chained | logic depth (cells, sum of module depths) |")
    md.append("|---|---|---:|")
    result["stages"] = []
    for stage, mods in STAGES:
        d = sum(depth.get(m, 0) for m in mods)
        result["stages"].append({"stage": stage, "modules": mods, "depth": d})
        present = [m for m in mods if m in depth] or mods
        md.append(f"| {stage} | {' -> '.join(present)} | {d} |")
    text = "\n".join(md) + "\n"
    (out / f"{name}.json").write_text(json.dumps(result, indent=2) + "\n")
    (out / f"{name}.md").write_text(text)
    if not args.quiet:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Build-time verilation (rtl/CMakeLists.txt pst_verilate()): runs Verilator for one top and
profile, then spreads its generated C++ over a fixed set of unity files that CMake knows at
configure time, so that Ninja verilates several profiles at once and compiles their C++ in
parallel with the rest of the build.

    verilate.py --mdir DIR --prefix P --slots N --depfile F -- verilator_bin ARGS...

Writes DIR/P_fast_<i>.cpp and DIR/P_slow_<i>.cpp, i < N: each #includes a share of
Verilator's fast-path files (compiled with OPT_FAST) or of its run-once files (*__Slow.cpp,
the constant pool, the symbol table: OPT_SLOW). The files are balanced by size; a slot gets
at least --min-bytes of C++ unless every slot is in use, so a small model fills one or two
slots and leaves the rest empty (they compile in a fraction of a second). Every unity file is
rewritten on each run (so that Ninja, which stats Verilator's files only once, recompiles it). F is a Ninja depfile naming every file Verilator read
(from its P__ver.d), so that an `include`d file re-verilates too.
"""
import argparse
import os
import re
import resource
import subprocess
import sys
from pathlib import Path


def cmake_list(text: str, var: str) -> list:
    m = re.search(r"^set\(" + re.escape(var) + r"\s*(.*)\)\s*$", text, re.M)
    if not m:
        return []
    return re.findall(r'"([^"]*)"', m.group(1))


def spread(files: list, slots: int, min_bytes: int) -> list:
    """Files into `slots` lists balanced by size (largest first onto the lightest list), using
    no more lists than needed to keep each at or above min_bytes."""
    sizes = {f: os.path.getsize(f) for f in files}
    total = sum(sizes.values())
    used = max(1, min(slots, total // max(min_bytes, 1)))
    out = [[] for _ in range(slots)]
    load = [0] * used
    for f in sorted(files, key=lambda f: (-sizes[f], f)):
        i = min(range(used), key=lambda k: (load[k], k))
        out[i].append(f)
        load[i] += sizes[f]
    return [sorted(x) for x in out]


def write(path: Path, text: str) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mdir", required=True, type=Path)
    ap.add_argument("--prefix", required=True)
    ap.add_argument("--slots", type=int, default=1)
    ap.add_argument("--min-bytes", type=int, default=4_000_000)
    ap.add_argument("--depfile", type=Path)
    ap.add_argument("cmd", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.cmd[1:] if a.cmd and a.cmd[0] == "--" else a.cmd
    mdir, p = a.mdir.resolve(), a.prefix
    mdir.mkdir(parents=True, exist_ok=True)
    # Verilator's own outputs of an earlier run (the DepSet files carry hashes in their
    # names: a stale one would otherwise linger); the unity files stay.
    for f in mdir.iterdir():
        if f.name.startswith(p) and not re.fullmatch(re.escape(p) + r"_(fast|slow)_\d+\.cpp", f.name):
            f.unlink()
    r = subprocess.run(cmd + ["--cc", "--make", "cmake", "--prefix", p, "--Mdir", str(mdir)])
    if r.returncode != 0:
        return r.returncode
    if os.environ.get("PST_VERILATE_LOG"):  # CPU-seconds of each verilation (build measurements)
        ru = resource.getrusage(resource.RUSAGE_CHILDREN)
        with open(os.environ["PST_VERILATE_LOG"], "a") as log:
            log.write(f"{ru.ru_utime:.2f} {ru.ru_stime:.2f} {ru.ru_maxrss} {p}\n")
    text = (mdir / f"{p}.cmake").read_text()
    fast = cmake_list(text, f"{p}_CLASSES_FAST") + cmake_list(text, f"{p}_SUPPORT_FAST")
    slow = cmake_list(text, f"{p}_CLASSES_SLOW") + cmake_list(text, f"{p}_SUPPORT_SLOW")
    for kind, files in (("fast", fast), ("slow", slow)):
        for i, group in enumerate(spread(files, a.slots, a.min_bytes)):
            body = "".join(f'#include "{Path(f).name}"\n' for f in group)
            write(mdir / f"{p}_{kind}_{i}.cpp",
                             f"// {kind} slot {i} of {p} (sim/tools/verilate.py)\n{body}")
    if a.depfile:
        # P__ver.d: "outputs... : inputs..." (one logical line); Ninja wants one target.
        ver = (mdir / f"{p}__ver.d").read_text().replace("\\\n", " ")
        inputs = ver.split(":", 1)[1].split() if ":" in ver else []
        target = mdir / f"{p}_fast_0.cpp"
        esc = lambda s: s.replace(" ", "\\ ")
        a.depfile.write_text(esc(str(target)) + ": " + " ".join(esc(i) for i in inputs) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Proves pst_mul_booth's simulation form (one `*`, what the verilated regression models use)
equal to its synthesis form (radix-4 Booth rows, what Yosys and the gate figures see) for every
width the profiles instantiate (scripts/pstlib/mulproof.py says how: ABC and Z3 through the
digit form sim/formal/pst_mul_digits.sv).

    scripts/mul_proof.py [PROFILE ...] [--width AW,BW,BSIGNED,PW] [--jobs N] [--out DIR]

Default: every named profile (rtl/configs/) and test profile (sim/test_profiles/), the ones the
harness verilates with the simulation form. Writes DIR/mul_proof.json; exit 1 when a width is
not proven, 2 on bad input.

The proof takes minutes (ctest -L formal runs it whole). Its record, sim/formal/mul_proof.record.json,
keeps the widths proven and digests of what the proof was made from (scripts/pstlib/mulproof.py:
PROOF_INPUTS, ELABORATION_INPUTS, the tool versions):

    scripts/mul_proof.py --record     # prove every width, then write the record (with --cached:
                                      # the widths the record still stands for are not proven again)
    scripts/mul_proof.py --cached     # the default test suite's check: widths from the record while
                                      # the RTL and profiles are unchanged (else Yosys elaborates
                                      # them again); a width is taken as proven from the record only
                                      # while the proof's inputs and tools are unchanged, and every
                                      # other width is proven now"""
import argparse
import concurrent.futures
import json
import pathlib
import sys
import tempfile

from .. import atomic, mulproof
from ..paths import CONFIGS, ROOT, profile_path


def parse_width(text: str) -> mulproof.Width:
    try:
        aw, bw, bs, pw = (int(x) for x in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}': want AW,BW,BSIGNED,PW (integers)") from None
    if not (1 <= aw <= 64 and 1 <= bw <= 64 and bs in (0, 1) and 1 <= pw <= 128):
        raise argparse.ArgumentTypeError(f"'{text}': AW, BW in 1..64, BSIGNED 0 or 1, PW in 1..128")
    return mulproof.Width(aw, bw, bs, pw)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profiles", nargs="*", help="profiles (names or files; default every named and test profile)")
    ap.add_argument("--width", action="append", type=parse_width, default=[],
                    help="prove this width only (repeatable), no profile elaborated")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    ap.add_argument("--out", default=str(ROOT / "out" / "mul_proof"))
    ap.add_argument("--record", action="store_true", help=f"write {mulproof.RECORD.name} once every width is proven")
    ap.add_argument("--cached", action="store_true", help="take what the record still stands for, prove the rest")
    a = ap.parse_args(argv)
    if a.jobs < 1:
        print("error: --jobs: must be >= 1", file=sys.stderr)
        return 2
    if (a.record or a.cached) and (a.width or a.profiles):
        print("error: --record and --cached take every profile: no PROFILE or --width", file=sys.stderr)
        return 2
    widths = {w: [] for w in a.width}
    recorded = {}
    if a.cached:
        try:
            rec = mulproof.read_record()
        except ValueError as e:
            print(f"error: {e}", file=sys.stderr)
            return 2
        elab_why, proof_why = mulproof.record_status(rec)
        if not elab_why:
            widths = {w: list(p) for w, p in mulproof.record_widths(rec).items()}
            print(f"widths: from the record ({len(widths)}; RTL and profiles unchanged)")
        else:
            print(f"widths: elaborated again ({'; '.join(elab_why[:5])}{' ...' if len(elab_why) > 5 else ''})")
        if not proof_why:
            recorded = mulproof.record_widths(rec)
        else:
            print(f"proofs: the record does not stand ({'; '.join(proof_why[:5])}): every width proven now")
    if not a.width and not widths:
        files = [profile_path(p) for p in a.profiles] or (sorted(CONFIGS.glob("*.toml"))
                                                          + sorted((ROOT / "sim" / "test_profiles").glob("*.toml")))
        for f in files:
            if not f.is_file():
                print(f"error: {f}: no such profile", file=sys.stderr)
                return 2
        with tempfile.TemporaryDirectory(prefix="mulproof-") as tmp, \
                concurrent.futures.ProcessPoolExecutor(a.jobs) as pool:
            found = {f: pool.submit(mulproof.instantiated, f, a.rom_dir, pathlib.Path(tmp) / f.stem) for f in files}
            for f, fut in found.items():
                for w in fut.result():
                    widths.setdefault(w, []).append(f.stem)
    todo = sorted(w for w in widths if w not in recorded)
    with tempfile.TemporaryDirectory(prefix="mulproof-") as tmp:
        with concurrent.futures.ProcessPoolExecutor(a.jobs) as pool:   # Z3 keeps one context per process
            futs = {w: pool.submit(mulproof.prove, w, pathlib.Path(tmp) / f"w{i}") for i, w in enumerate(todo)}
            results = {w: f.result() for w, f in futs.items()}
    for w in sorted(widths):
        if w not in results:   # the record stands for this width: its inputs and tools are unchanged
            results[w] = {"Q0": True, "Q1": True, "Q2": True, "Q3": True, "abc": "record", "seconds": 0.0,
                          "proven": True, "from_record": True}
    results = dict(sorted(results.items()))
    rows = [{"aw": w.aw, "bw": w.bw, "bsigned": w.bsigned, "pw": w.pw, "profiles": sorted(set(widths[w])), **r}
            for w, r in results.items()]
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    atomic.write_text(out / "mul_proof.json", json.dumps({"widths": rows}, indent=1) + "\n")
    print("| AW x BW -> PW | Q1 Booth = digits (ABC) | Q2 digits = a b (Z3) | Q3 | Q0 sim = a b | s | profiles |")
    print("|---|---|---|---|---|---:|---|")
    for w, r in results.items():
        yes = {True: "by the record", False: "NOT proven"} if r.get("from_record") else \
            {True: "proven", False: "NOT proven"}
        print(f"| {w} | {yes[r['Q1']]} | {yes[r['Q2']]} | {yes[r['Q3']]} | {yes[r['Q0']]} | {r['seconds']} | "
              f"{', '.join(sorted(set(widths[w])))} |")
    bad = [str(w) for w, r in results.items() if not r["proven"]]
    n_rec = sum(1 for r in results.values() if r.get("from_record"))
    print(f"{len(results) - len(bad)} of {len(results)} widths proven" +
          (f" ({n_rec} by the record {mulproof.RECORD.relative_to(ROOT)}; prove all: ctest -L formal)" if n_rec else "")
          + (f"; NOT: {', '.join(bad)}" if bad else ""))
    if a.record and not bad:
        atomic.write_text(mulproof.RECORD, json.dumps(mulproof.make_record(widths), indent=1) + "\n")
        print(f"record: {mulproof.RECORD.relative_to(ROOT)}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

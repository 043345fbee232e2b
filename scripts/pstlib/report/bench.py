"""The simulation benchmark (scripts/bench.py): per verilated profile, the RTL's cycles/s and
pixels/s beside the golden model's pixels/s of the same run, on a fixed scene and a fixed
random stream, read from `pst regress -o` JSON (the scene run's `seconds`, the random run's
`rtl_seconds` and `golden_seconds`: each model's own share of the wall clock)."""
import pathlib


def _rate(n, seconds):
    return n / seconds if seconds and seconds > 0 else 0.0


def scene_row(run: dict) -> dict:
    """One `pst regress SCENE -o` record -> the benchmark's numbers."""
    sec = run["seconds"]
    px = run["fragments"]
    rtl, golden = _rate(px, sec["rtl"]), _rate(px, sec["golden"])
    return {"profile": run["profile"], "input": f"{pathlib.Path(run['scene']).stem} {run['width']}x{run['height']}",
            "pixels": px, "cycles": run["cycles"], "rtl_cycles_per_s": _rate(run["cycles"], sec["rtl"]),
            "rtl_pixels_per_s": rtl, "golden_pixels_per_s": golden,
            "rtl_over_golden": rtl / golden if golden else 0.0,
            "assertions": run.get("assertions_verilated")}


def random_row(run: dict) -> dict:
    """One `pst regress --random N -o` record -> the benchmark's numbers."""
    px = run["fragments"]
    rtl, golden = _rate(px, run["rtl_seconds"]), _rate(px, run["golden_seconds"])
    return {"profile": run["profile"], "input": f"random {px} seed {run['seed']}", "pixels": px,
            "cycles": run["cycles"], "rtl_cycles_per_s": _rate(run["cycles"], run["rtl_seconds"]),
            "rtl_pixels_per_s": rtl, "golden_pixels_per_s": golden,
            "rtl_over_golden": rtl / golden if golden else 0.0,
            "assertions": run.get("assertions_verilated")}


def table(rows: list) -> str:
    """Markdown table of the rows (ratio as 1/x of the golden model)."""
    out = ["| profile | assertions | input | RTL cycles/s | RTL pixels/s | golden pixels/s | RTL / golden |",
           "|---|---|---|---:|---:|---:|---:|"]
    for r in rows:
        ratio = f"1/{1 / r['rtl_over_golden']:.1f}" if r["rtl_over_golden"] > 0 else "-"
        flavour = {True: "yes", False: "no"}.get(r.get("assertions"), "?")
        out.append(f"| {r['profile']} | {flavour} | {r['input']} | {r['rtl_cycles_per_s']:,.0f} | {r['rtl_pixels_per_s']:,.0f} | "
                   f"{r['golden_pixels_per_s']:,.0f} | {ratio} |")
    return "\n".join(out) + "\n"


def verilated_profiles(list_output: str) -> list:
    """The profiles of `pst regress --random 1 --list` ('profile NAME' lines)."""
    return [line.split()[1] for line in list_output.splitlines() if line.startswith("profile ")]

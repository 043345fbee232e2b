"""Silicon and quality baselines (scripts/synth/baseline.json, checked by
scripts/check_baseline.py in the main job): the figures a change must not move by more than
the tolerance (2 %) without the file being updated in the same commit."""
import math

TOLERANCE = 0.02
# Figures kept for the docs (scripts/gen_docs.py: the critical path per stage of
# docs/HARDWARE.md), not checked: Fmax already checks the worst path.
UNCHECKED = ("stage_path_ns",)


def collect(synth: dict, regress: list, power: dict = None) -> dict:
    """Figures of the named profiles: synth maps a profile name to scripts/synth.py's JSON,
    regress is `pst regress` JSON output (a list of runs), power maps a profile name to
    scripts/power.py's summary (energy per pixel, mean over its workloads)."""
    out = {}
    for name, s in sorted(synth.items()):
        p = {
            "logic_ge": s["logic_ge"],
            "block_ge": {b: v["logic_ge"] for b, v in s["blocks"].items()},
            "flip_flops": s["flip_flops"],
            "memory_ge": s["memory_ge"],
            "total_ge": s["total_ge"],
            "rom_bits": s["rom_bits"],
            "ram_bits": s["ram_bits"],
            "clocks_per_pixel": s["clocks_per_pixel"],
        }
        if s.get("timing"):
            p["fmax_mhz"] = s["timing"]["fmax_mhz"]
            # Which constraints the Fmax was timed with (an entry without it predates the
            # sign-off SDC: ideal clock, no uncertainty).
            c = s["timing"].get("constraints") or {}
            if c.get("setup_uncertainty_ns") is not None:
                p["fmax_setup_uncertainty_ns"] = c["setup_uncertainty_ns"]
            if s.get("critical_path_ns"):
                p["stage_path_ns"] = dict(s["critical_path_ns"])
        s_power = (power or {}).get(name)
        if s_power:
            p["energy_pj_per_pixel"] = round(s_power["pj_per_pixel"], 1)
        out[name] = p
    for r in regress:
        name = r.get("profile")
        if name not in out:
            continue
        scene = r["scene"].rsplit("/", 1)[-1].removesuffix(".toml")
        out[name].setdefault("psnr_db", {})[scene] = round(r["vs_reference"]["psnr"], 3)
        out[name].setdefault("regress_size", r.get("width", r.get("size")))
    return out


def _flatten(d: dict, prefix: str = "") -> dict:
    out = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, key + "."))
        else:
            out[key] = v
    return out


def compare(baseline: dict, current: dict, tolerance: float = TOLERANCE) -> list:
    """Figures that moved: (key, baseline value, current value, relative change or None) for
    every number that differs by more than `tolerance` (relative), every figure present on
    one side only, and every non-number that differs. Empty when the baseline holds."""
    def checked(d: dict) -> dict:       # "profile.figure[.sub]" keys but the UNCHECKED figures
        return {k: v for k, v in _flatten(d).items() if (k.split(".") + [""])[1] not in UNCHECKED}
    b, c = checked(baseline), checked(current)
    out = []
    for key in sorted(set(b) | set(c)):
        if key not in b or key not in c:
            out.append((key, b.get(key), c.get(key), None))
            continue
        x, y = b[key], c[key]
        if isinstance(x, bool) or isinstance(y, bool) or not isinstance(x, (int, float)) \
                or not isinstance(y, (int, float)):
            if x != y:
                out.append((key, x, y, None))
            continue
        if math.isinf(x) or math.isinf(y) or math.isnan(x) or math.isnan(y):
            if not (x == y):
                out.append((key, x, y, None))
            continue
        if x == y:
            continue
        rel = abs(y - x) / max(abs(x), 1e-12)
        if rel > tolerance:
            out.append((key, x, y, rel))
    return out


def tool_mismatches(base_tools: dict, synth: dict) -> list:
    """Profiles synthesized with other tools than the baseline's: (profile, its tools). Figures
    of another Yosys or OpenSTA are not comparable with the baseline's (ABC's mapping and the
    timer's interpolation change with the version)."""
    return [(n, s.get("tools")) for n, s in sorted(synth.items()) if s.get("tools") != base_tools]

"""The noise units' table (docs/HARDWARE.md section noise-units): silicon and quality of each
noise unit on the reduced pipeline, from scripts/synth/noise_units.json (see its "doc")."""
import json
from pathlib import Path

SOURCE = Path("scripts/synth/noise_units.json")
FIELDS = ("unit", "profile", "unit_logic_ge", "unit_rom_ge", "unit_rom_bits", "logic_ge", "memory_ge",
          "fmax_mhz", "clocks_per_pixel", "scene", "still_rms_hw", "still_rms_unfiltered", "flicker_rtl",
          "flicker_best_hw", "flicker_best_hw_option")


def load(root: Path) -> list:
    """The units, each with every field (ValueError naming the file and the field otherwise)."""
    path = root / SOURCE
    units = json.loads(path.read_text())["units"]
    for i, u in enumerate(units):
        for f in FIELDS:
            if f not in u:
                raise ValueError(f"{SOURCE}: units[{i}].{f}: missing")
    return units


def _flicker(u) -> str:
    if u["flicker_rtl"] is None:
        return "- (no fly-in of this basis)"
    best = "" if u["flicker_best_hw"] == u["flicker_rtl"] else \
        f"; best in hardware {u['flicker_best_hw']:.2f}x ({u['flicker_best_hw_option']})"
    return f"{u['flicker_rtl']:.2f}x{best}"


def markdown(units: list) -> str:
    L = ["| unit (profile) | unit logic GE | unit ROM GE (bits) | pipeline logic / memory GE | Fmax pre-layout | "
         "clocks / pixel | still RMS vs truth: the unit's image / unfiltered (scene) | fly-in flicker, unfiltered / RTL |",
         "|---|---:|---:|---:|---:|---:|---|---|"]
    for u in units:
        L.append(f"| {u['unit']} (`{u['profile']}`) | {u['unit_logic_ge']:,} | {u['unit_rom_ge']:,} "
                 f"({u['unit_rom_bits']:,}) | {u['logic_ge']:,} / {u['memory_ge']:,} | {u['fmax_mhz']:.1f} MHz | "
                 f"{u['clocks_per_pixel']} | {u['still_rms_hw']:.4f} / {u['still_rms_unfiltered']:.4f} "
                 f"({u['scene']}) | {_flicker(u)} |")
    return "\n".join(L) + "\n"

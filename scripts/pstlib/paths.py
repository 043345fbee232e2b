"""Where the project is, and the one lookup of a profile by name or file."""
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
PY = "/usr/bin/python3"
CONFIGS = ROOT / "rtl" / "configs"


def profile_path(name) -> pathlib.Path:
    """A profile given as a name (rtl/configs/NAME.toml) or as a file (a path or a .toml name)."""
    s = str(name)
    if s.endswith(".toml") or "/" in s:
        return pathlib.Path(s)
    return CONFIGS / f"{s}.toml"


def rtl_sources() -> list:
    """The synthesizable SystemVerilog sources (rtl/, without the assertion binds of rtl/sva/)."""
    return sorted(p for p in (ROOT / "rtl").rglob("*.sv") if "sva" not in p.relative_to(ROOT / "rtl").parts)


def rtl_source(base: str):
    """The file that defines module BASE (rtl/**/BASE.sv), None when there is none."""
    return next((p for p in rtl_sources() if p.stem == base), None)

"""Everything a synthesis result depends on besides the profile's values, for the keys of the
caches that reuse results (the sweep's out/synth/NAME.json sidecar, the search's per-module
cache, the stand-alone memory cache): the RTL, the flow's code (scripts/synth.py,
pstlib/synth/*.py with fanout.py, pstlib/contract.py and paths.py that turn a profile into
parameters and sources, scripts/profile.py), the contract (rtl/contract.toml), the files in
scripts/synth/ (cell libraries, memory stand-ins, the SDC), the OSU018 liberty's content, the
ROM images and the Yosys and OpenSTA versions."""
import functools
import hashlib
import pathlib

from ..paths import ROOT, rtl_sources
from .tools import tool_version


def code_files(rtl_sv: bool = True) -> list:
    """The flow's own files in the repository (tests left out): contract, scripts and the RTL
    (its .sv files only with RTL_SV: the per-module cache keys each module by its own source)."""
    flow = ROOT / "scripts" / "pstlib" / "synth"
    synth = ROOT / "scripts" / "synth"
    rtl = ROOT / "rtl"
    return [ROOT / "scripts" / "synth.py", ROOT / "scripts" / "profile.py",
            ROOT / "scripts" / "pstlib" / "contract.py", ROOT / "scripts" / "pstlib" / "paths.py",
            *sorted(p for p in flow.glob("*.py") if not p.name.startswith("test_")),
            *sorted(p for p in synth.glob("*") if p.suffix in (".lib", ".v", ".sdc")),
            rtl / "contract.toml", *(rtl_sources() if rtl_sv else []),
            *sorted(p for p in rtl.rglob("*.svh") if "sva" not in p.relative_to(rtl).parts)]


def input_files(lib, rom_dir: pathlib.Path, rtl_sv: bool = True) -> list:
    """code_files, the cell library (LIB; None when it is not installed: the flow then refuses
    to run) and the ROM images (ROM_DIR/*.memh)."""
    return [*code_files(rtl_sv), *([pathlib.Path(lib)] if lib else []), *sorted(pathlib.Path(rom_dir).glob("*.memh"))]


@functools.lru_cache(maxsize=None)
def tool_versions(yosys: str = "yosys", sta: str = "sta") -> tuple:
    """(Yosys version line, OpenSTA version line) of the tools on PATH."""
    return tool_version([yosys, "-V"]), tool_version([sta, "-version"])


def digest(files: list, extra=()) -> str:
    """Content hash of FILES (by name relative to their folder and content, in order) and the
    strings EXTRA (tool versions, flow constants). A missing file is an error."""
    h = hashlib.sha256()
    for f in files:
        f = pathlib.Path(f)
        h.update(f.name.encode() + b"\0" + f.read_bytes() + b"\0")
    for e in extra:
        h.update(str(e).encode() + b"\0")
    return h.hexdigest()[:20]

"""Liberty files: the cell areas synthesis reports in, and the stand-in cells through which
OpenSTA times a memory read (scripts/synth.py).

The OSU 0.18 um library (Debian's qflow-tech-osu018) is found by `osu018_lib()`:
$PST_OSU018_LIB, the installed package, or the copy scripts/setup.sh unpacks into
~/.cache/pst/osu018 (apt-get download + dpkg-deb -x, without the rest of qflow).
"""
import os
import pathlib
import re

OSU018_REL = "usr/share/qflow/tech/osu018/osu018_stdcells.lib"
REFERENCE_CELL = "NAND2X1"   # GE = area / area(NAND2X1)


def osu018_candidates() -> list:
    home = pathlib.Path(os.environ.get("XDG_CACHE_HOME", pathlib.Path.home() / ".cache"))
    out = []
    if os.environ.get("PST_OSU018_LIB"):
        out.append(pathlib.Path(os.environ["PST_OSU018_LIB"]))
    out += [pathlib.Path("/") / OSU018_REL, home / "pst" / "osu018" / OSU018_REL]
    return out


def osu018_lib():
    """The OSU018 liberty file, or None when scripts/setup.sh has not fetched it."""
    return next((p for p in osu018_candidates() if p.is_file()), None)


def _strip_comments(text: str) -> str:
    return re.sub(r"/\*.*?\*/", "", text, flags=re.S)


def cell_areas(text: str) -> dict:
    """Cell name -> area from a liberty file's text (the first `area` inside each cell group)."""
    areas = {}
    for name, body in _cell_bodies(text):
        m = re.search(r"\barea\s*:\s*([0-9.eE+-]+)\s*;", body)
        if m:
            areas[name] = float(m.group(1))
    return areas


def _cell_bodies(text: str) -> list:
    """(cell name, text of its group) of a liberty file's text, comments removed."""
    text = _strip_comments(text)
    starts = [(m.start(), m.group(1)) for m in re.finditer(r"\bcell\s*\(\s*\"?([\w$]+)\"?\s*\)\s*\{", text)]
    return [(name, text[pos:starts[i + 1][0] if i + 1 < len(starts) else len(text)])
            for i, (pos, name) in enumerate(starts)]


def max_capacitance(text: str) -> dict:
    """"CELL/PIN" -> the pin's max_capacitance (pF) of every output pin that has one."""
    out = {}
    for cell, body in _cell_bodies(text):
        pins = [(m.start(), m.group(1)) for m in re.finditer(r"\bpin\s*\(\s*\"?(\w+)\"?\s*\)\s*\{", body)]
        for i, (pos, pin) in enumerate(pins):
            group = body[pos:pins[i + 1][0] if i + 1 < len(pins) else len(body)]
            m = re.search(r"\bmax_capacitance\s*:\s*([0-9.eE+-]+)\s*;", group)
            if m:
                out[f"{cell}/{pin}"] = float(m.group(1))
    return out


def cells_area(cells: dict, areas: dict, skip=()) -> float:
    """Area of a module's own cells (cell type -> count). Every type must have an area in the
    liberty unless it is in SKIP (sub-modules, memory stand-ins costed apart): a type without
    one is an error, not a silent zero."""
    missing = sorted(c for c in cells if c not in areas and c not in skip)
    if missing:
        raise RuntimeError(f"cell types without an area in the liberty: {', '.join(missing)}")
    return sum(n * areas[c] for c, n in cells.items() if c in areas)


def library_name(text: str) -> str:
    m = re.search(r"\blibrary\s*\(\s*\"?([\w.-]+)\"?\s*\)", _strip_comments(text))
    return m.group(1) if m else ""


def ge_unit(areas: dict) -> float:
    """Area of one gate equivalent (the library's NAND2X1)."""
    if REFERENCE_CELL not in areas:
        raise ValueError(f"liberty has no {REFERENCE_CELL}: no gate-equivalent unit")
    return areas[REFERENCE_CELL]


def flip_flop_cells(text: str) -> set:
    """Cells with an ff or latch group (sequential cells)."""
    return {name for name, body in _cell_bodies(text) if re.search(r"\b(ff|latch)\s*\(", body)}


# ---- stand-in cells for memories ----------------------------------------------------------
# A memory stays a memory in the netlist; for timing, every data bit of every read port
# becomes a PST_MEMRD_<k> cell (address pins A0..A15, output Y) whose address-to-data delay is
# memory k's own, measured by OpenSTA on that memory synthesized alone to OSU018 cells; every
# write-port bit (data, enable, address) ends at a PST_MEMWR cell with a setup check against
# the write clock. Read data launched by a write (clock to read data) is not modelled: the
# RAMs are written only through the register interface while the pipeline is idle.
ADDR_PINS = 16
STANDIN_TYPES = ("PST_MEMRD", "PST_MEMWR")   # the cell types memories map to before renaming


def standin_cell_name(k: int) -> str:
    return f"PST_MEMRD_{k}"


def standin_liberty(delays: dict, setup_ns: float, addr_cap_pf: float, slew_ns: float = 0.2) -> str:
    """A liberty library with one read stand-in cell per memory (k -> address-to-data delay in
    ns) and the write-port capture cell PST_MEMWR. Areas are 0: memory area is costed
    apart (scripts/pstlib/memarea.py)."""
    pins = " ".join(f"A{i}" for i in range(ADDR_PINS))
    out = ["library(pst_mem_standin) {",
           "  delay_model : table_lookup;",
           '  time_unit : "1ns";', '  voltage_unit : "1V";', '  current_unit : "1uA";',
           '  pulling_resistance_unit : "1kohm";', '  leakage_power_unit : "1nW";',
           "  capacitive_load_unit (1,pf);",
           "  slew_upper_threshold_pct_rise : 80;", "  slew_lower_threshold_pct_rise : 20;",
           "  slew_upper_threshold_pct_fall : 80;", "  slew_lower_threshold_pct_fall : 20;",
           "  input_threshold_pct_rise : 50;", "  input_threshold_pct_fall : 50;",
           "  output_threshold_pct_rise : 50;", "  output_threshold_pct_fall : 50;",
           "  nom_process : 1;", "  nom_voltage : 1.8;", "  nom_temperature : 25;"]

    def scalar(kind: str, v: float) -> list:
        return [f"      {kind}(scalar) {{ values(\"{v:.4f}\"); }}"]

    names = ["PST_MEMRD"] + [standin_cell_name(k) for k in sorted(delays)]
    for name in names:
        d = delays.get(int(name.rsplit("_", 1)[1]), 0.0) if name != "PST_MEMRD" else 0.0
        out += [f"  cell({name}) {{", "    area : 0;", "    dont_use : true;"]
        for i in range(ADDR_PINS):
            out += [f"    pin(A{i}) {{ direction : input; capacitance : {addr_cap_pf:.4f}; }}"]
        out += ["    pin(Y) {", "      direction : output;", "      timing() {",
                f'        related_pin : "{pins}";', "        timing_sense : non_unate;"]
        for kind in ("cell_rise", "cell_fall"):
            out += ["  " + s for s in scalar(kind, d)]
        for kind in ("rise_transition", "fall_transition"):
            out += ["  " + s for s in scalar(kind, slew_ns)]
        out += ["      }", "    }", "  }"]
    out += ["  cell(PST_MEMWR) {", "    area : 0;", "    dont_use : true;",
            "    pin(CK) { direction : input; clock : true; capacitance : 0.01; }",
            "    pin(D) {", "      direction : input;", f"      capacitance : {addr_cap_pf:.4f};",
            "      timing() {", '        related_pin : "CK";', "        timing_type : setup_rising;"]
    for kind in ("rise_constraint", "fall_constraint"):
        out += [f"        {kind}(scalar) {{ values(\"{setup_ns:.4f}\"); }}"]
    out += ["      }", "    }", "  }", "}"]
    return "\n".join(out) + "\n"

"""One block through Debian's qflow (1.3.17, OSU 0.18 µm): its own project folder, the
step scripts of /usr/lib/qflow/scripts run in order, each timed, each checked by the file it
must leave.

The block arrives as a mapped OSU018 netlist (the profile's own synthesis), so qflow's
synthesis step only reads it (a Yosys script given as yosys_options) and then does what
qflow adds: ypostproc, blifFanout (buffer trees sized from the liberty's limits), the
Verilog and SPICE views. Then graywolf places (initial density DENSITY), qrouter routes
(stages 1 and 2; the stage-3 cleanup is skipped: it takes longer than the routing and every
net is routed without it), magic reads the routed DEF (migrate), netgen compares layout and
netlist (LVS), after magic has written the GDS and checked the design rules (DRC).
"""
import dataclasses
import json
import pathlib
import re
import shutil
import time

from .. import procs
from . import blif, islands, pins

SCRIPTS = pathlib.Path("/usr/lib/qflow/scripts")
TECH = "osu018"
TECH_DIR = pathlib.Path("/usr/share/qflow/tech/osu018")
LEF = TECH_DIR / "osu018_stdcells.lef"
DENSITY = 0.7     # graywolf's initial density (decongest): 66-70 % utilization in the trial
DENSITY_STEP = 0.1    # a block qrouter cannot finish is placed again this much less dense,
DENSITY_MIN = 0.4     # down to this
STEP_TIMEOUT = 3 * 3600


class FlowError(RuntimeError):
    """A qflow step failed (its log named)."""


class Unrouted(FlowError):
    """qrouter finished with nets it could not route (the placement is too dense)."""


@dataclasses.dataclass
class Project:
    path: pathlib.Path
    name: str            # the block's module name (blk_NAME)

    @property
    def synthesis(self) -> pathlib.Path:
        return self.path / "synthesis"

    @property
    def layout(self) -> pathlib.Path:
        return self.path / "layout"

    @property
    def log(self) -> pathlib.Path:
        return self.path / "log"


def available() -> bool:
    """qflow, its step scripts and the OSU018 technology are installed (scripts/setup.sh --pnr)."""
    return bool(shutil.which("qflow")) and (SCRIPTS / "router.sh").exists() and LEF.exists()


def setup(path: pathlib.Path, name: str, netlist: pathlib.Path, lib: pathlib.Path, resume: bool = False) -> Project:
    """A fresh qflow project for block NAME whose mapped netlist is NETLIST (RESUME: the one
    already there, when its netlist is the same)."""
    if resume and (path / "source" / f"{name}.v").exists() and \
            (path / "source" / f"{name}.v").read_bytes() == pathlib.Path(netlist).read_bytes():
        return Project(path, name)
    if path.exists():
        shutil.rmtree(path)
    for d in ("source", "synthesis", "layout", "log"):
        (path / d).mkdir(parents=True)
    p = Project(path, name)
    shutil.copy(netlist, path / "source" / f"{name}.v")
    rc, out, err = procs.run(["qflow", "-T", TECH, name], cwd=path, timeout=120)
    if rc != 0 or not (path / "project_vars.sh").exists():
        raise FlowError(f"qflow -T {TECH} {name} in {path} failed:\n{out}\n{err}")
    read = p.synthesis / "read_netlist.ys"
    read.write_text(f"read_liberty -lib {lib}\nread_verilog {path / 'source' / (name + '.v')}\n"
                    f"hierarchy -top {name}\nwrite_blif -buf BUFX2 A Y {name}_mapped.blif\n")
    v = (path / "project_vars.sh").read_text()
    v = re.sub(r"^# set yosys_options =.*$", f'set yosys_options = "-s {read}"', v, flags=re.M)
    v = re.sub(r"^# set initial_density =.*$", f"set initial_density = {DENSITY}", v, flags=re.M)
    (path / "project_vars.sh").write_text(v)
    return p


def _run(p: Project, script: str, args: list, must: list, log: str, ok=lambda rc, out: rc == 0) -> float:
    t0 = time.time()
    rc, out, err = procs.run(["tcsh", "-f", SCRIPTS / script, *args], cwd=p.path, timeout=STEP_TIMEOUT)
    (p.log / f"{script}.out").write_text(out + "\n" + err)
    missing = [str(m) for m in must if not pathlib.Path(m).exists()]
    if not ok(rc, out) or missing:
        tail = "\n".join((out + err).splitlines()[-20:])
        raise FlowError(f"{script} for {p.name} failed (exit {rc}; missing {missing}); "
                        f"log {p.log / log}:\n{tail}")
    return time.time() - t0


def synthesize(p: Project) -> float:
    return _run(p, "synthesize.sh", [p.path, p.name, p.path / "source" / f"{p.name}.v"],
                [p.synthesis / f"{p.name}.blif", p.synthesis / f"{p.name}.rtlnopwr.v"], "synth.log")


def place(p: Project) -> float:
    s = _run(p, "placement.sh", ["-d", p.path, p.name], [p.layout / f"{p.name}.def"], "place.log")
    cel2 = p.layout / f"{p.name}.cel2"
    if not cel2.exists() and pins.far((p.layout / f"{p.name}.def").read_text()):
        # graywolf put the pins far from their cells (or ringed them outside the cells: too
        # many for its pin spacing): such a placement routes for half an hour or more and fails
        # (u_regs, u_octave_g_serial of reduced), so place again at once with the pins from the
        # cells.
        hint_pins(p)
        s += _run(p, "placement.sh", ["-d", p.path, p.name], [p.layout / f"{p.name}.def"], "place.log")
    if cel2.exists():
        # Pins placed from the cells (a retry, hint_pins): graywolf followed the hints roughly;
        # each pin now moves to the edge by its cells as placed (pins.snap).
        # router.sh routes NAME_unroute.def (copied over NAME.def): both carry the pins.
        placed = p.layout / f"{p.name}.def"
        text, summary = pins.snap(placed.read_text())
        for f in (placed, p.layout / f"{p.name}_unroute.def"):
            f.write_text(text)
        _log_pins(p, summary, new_try=False)
    # Routing without qrouter's stage-3 cleanup (standard_route's third argument).
    cfg = p.layout / f"{p.name}.cfg"
    text = cfg.read_text()
    line = f"qrouter::standard_route {p.name}_route.def false"
    if line not in text:
        raise FlowError(f"{cfg}: no `{line}` line to extend")
    cfg.write_text(text.replace(line, line + " true"))
    return s


def route(p: Project) -> float:
    # router.sh moves qrouter's NAME_route.def and NAME_route.rc back to NAME.def / NAME.rc.
    s = _run(p, "router.sh", [p.path, p.name], [p.layout / f"{p.name}.rc"], "route.log")
    out = (p.log / "router.sh.out").read_text()
    if "Final: No failed routes!" not in out:
        raise Unrouted(f"qrouter left nets unrouted in {p.name} (log {p.log / 'route.log'})")
    return s


# Magic's OSU018 rules (SCN6M_SUBM.10.tech: "Metal2 area < 20", lambda 0.1 um) ask 0.2 um^2
# of every metal island; qflow draws each block pin as a 0.3 x 0.3 um square (0.09 um^2) 1 um
# inside the die edge, so every pin is a DRC error of the block on its own. Each such pin is
# drawn PIN_LENGTH_UM tall about its centre (0.3 x 0.7 um = 0.21 um^2): along its track for
# the bottom and top pins (vertical metal2, 0.8 um pitch), across it for the left and right
# pins (horizontal metal3, whose tracks are 1.0 um apart: 0.5 um left to the next wire).
# Found by DRC on the routed blocks: lengthened along x, a metal3 pin comes within 0.3 um of
# the routing beside it (inwards) or shorts to qrouter's wires along the die edge (outwards).
# The DRC and LVS that follow check the result.
PIN_MIN_AREA_UM2 = 0.2
PIN_LENGTH_UM = 0.7


def widen_pins(def_text: str) -> tuple:
    """The DEF with every block pin under PIN_MIN_AREA_UM2 drawn PIN_LENGTH_UM tall about its
    centre, and how many were."""
    units = float(re.search(r"^UNITS DISTANCE MICRONS (\d+)", def_text, re.M).group(1))
    length = int(round(PIN_LENGTH_UM * units))
    n = 0

    def fix(m):
        nonlocal n
        layer, x1, y1, x2, y2 = m.group(1), *(int(v) for v in m.group(2, 3, 4, 5))
        if (x2 - x1) * (y2 - y1) / units ** 2 >= PIN_MIN_AREA_UM2:
            return m.group(0)
        n += 1
        return f"+ LAYER {layer} ( {x1} {-(length // 2)} ) ( {x2} {length - length // 2} )"
    return re.sub(r"\+ LAYER (metal\d) \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)", fix, def_text), n


def migrate(p: Project) -> float:
    routed = p.layout / f"{p.name}.def"
    text, _ = widen_pins(routed.read_text())
    routed.write_text(text)
    return _run(p, "migrate.sh", [p.path, p.name], [p.layout / f"{p.name}.mag"], "migrate.log")


def spice_ports(spice: bytes, ports: list, vdd: str = "vdd", gnd: str = "gnd") -> bytes:
    """SPICE with its `.subckt` line's ports written from PORTS (the BLIF's inputs and outputs)
    after VDD and GND. qflow's blif2BSpice garbles some long port names of the large blocks
    (bytes that are not text, a name cut in pieces), and netgen then counts each piece as an
    unmatched pin although the circuits match."""
    lines = spice.split(b"\n")
    i = next((k for k, l in enumerate(lines) if l.startswith(b".subckt ")), None)
    if i is None:
        raise FlowError("SPICE netlist without a .subckt line")
    name = lines[i].split()[1]
    lines[i] = b" ".join([b".subckt", name, vdd.encode(), gnd.encode(), *(n.encode() for n in ports)])
    return b"\n".join(lines)


def blif_ports(blif_text: str) -> list:
    ports = []
    for line in blif._logical_lines(blif_text):
        parts = line.split()
        if parts[0] in (".inputs", ".outputs"):
            ports += parts[1:]
    return ports


def lvs(p: Project) -> float:
    # The reference netlist's port list from the placed BLIF (spice_ports).
    spc = p.synthesis / f"{p.name}.spc"
    placed = p.synthesis / f"{p.name}_anno.blif"
    src = placed if placed.exists() else p.synthesis / f"{p.name}.blif"
    if spc.exists() and src.exists():
        spc.write_bytes(spice_ports(spc.read_bytes(), blif_ports(src.read_text())))
    # lvs.sh exits 1 on a mismatch; the count is a result (reported), not a crash.
    return _run(p, "lvs.sh", [p.path, p.name], [p.log / "lvs.log"], "lvs.log",
                ok=lambda rc, out: rc == 0 or re.search(r"Total errors = \d+", out) is not None)


def _clear_later_logs(p: Project, *names) -> None:
    """qflow's gdsii.sh and drc.sh refuse to run when the LVS or DRC log of an earlier run ends
    in an error condition; those steps run after them here and write their logs again."""
    for n in names:
        (p.log / n).unlink(missing_ok=True)


def drc(p: Project) -> float:
    _clear_later_logs(p, "lvs.log")
    # drc.sh exits 1 when magic counts errors; the count is a result (reported), not a crash.
    return _run(p, "drc.sh", [p.path, p.name], [p.log / "drc.log"], "drc.log",
                ok=lambda rc, out: rc == 0 or re.search(r"^drc = \d+", out, re.M) is not None)


def drc_count(p: Project) -> int:
    m = re.search(r"^drc = (\d+)", (p.log / "drc.sh.out").read_text(), re.M)
    if not m:
        raise FlowError(f"{p.log / 'drc.sh.out'}: no DRC count")
    return int(m.group(1))


def find_islands(p: Project) -> list:
    """The minimum-area errors magic finds in the block's layout: (layer, x, y) in DEF units."""
    tcl = p.layout / f"islands_{p.name}.tcl"
    tcl.write_text(islands.ISLANDS_TCL.format(lef=LEF, cell=p.name))
    rc, out, err = procs.run(["magic", "-dnull", "-noconsole", tcl], cwd=p.layout, timeout=STEP_TIMEOUT)
    (p.log / "islands.out").write_text(out + "\n" + err)
    scale = re.search(r"^SCALE ([0-9.]+)", out, re.M)
    if rc != 0 or not scale:
        raise FlowError(f"magic's DRC listing of {p.name} failed (exit {rc}; log {p.log / 'islands.out'})")
    units = float(re.search(r"^UNITS DISTANCE MICRONS (\d+)", (p.layout / f"{p.name}.def").read_text(), re.M).group(1))
    f = float(scale.group(1)) * units
    return [(layer, round(x * f), round(y * f)) for layer, x, y in islands.parse_magic_islands(out)]


def drc_repair(p: Project) -> float:
    """DRC; when magic finds minimum-area islands, the routed DEF repaired (pstlib/pnr/islands.py)
    and the layout read, written and checked again. The repair counts go to log/islands.json."""
    t0 = time.time()
    drc(p)
    counts = {"moved": 0, "removed": 0, "left": 0, "drc_before": drc_count(p)}
    if counts["drc_before"]:
        found = find_islands(p)
        if found:
            routed = p.layout / f"{p.name}.def"
            text, c = islands.repair(routed.read_text(), found, LEF.read_text())
            counts.update(c)
            if c["moved"] or c["removed"]:
                routed.write_text(text)
                migrate(p)
                gds(p)
                drc(p)
    (p.log / "islands.json").write_text(json.dumps(counts) + "\n")
    return time.time() - t0


def gds(p: Project) -> float:
    _clear_later_logs(p, "drc.log", "lvs.log")
    return _run(p, "gdsii.sh", [p.path, p.name], [p.layout / f"{p.name}.gds"], "gdsii.log")


def density(p: Project) -> float:
    m = re.search(r"^set initial_density = ([0-9.]+)", (p.path / "project_vars.sh").read_text(), re.M)
    return float(m.group(1)) if m else DENSITY


def set_density(p: Project, d: float) -> None:
    v = p.path / "project_vars.sh"
    v.write_text(re.sub(r"^set initial_density = [0-9.]+", f"set initial_density = {d:.2f}", v.read_text(), flags=re.M))


def hint_pins(p: Project) -> None:
    """Pin hints (NAME.cel2) written from the block's last placement. The tries go to
    log/pins.json (median pin-to-cell distance of the placement each was made from)."""
    cel2 = p.layout / f"{p.name}.cel2"
    first = not cel2.exists()
    placed = (p.layout / f"{p.name}.def").read_text()
    text, summary = pins.from_def(placed)
    summary["median_pin_to_cell_um_before"] = round(pins.pin_distance_um(placed), 1)
    summary["density"] = density(p)
    cel2.write_text(text)
    # graywolf keeps 1.2 um between pins (osu018.par): with ~2,000 pins they no longer fit
    # around the cells and graywolf rings them 250 um out (u_regs of reduced). The hints
    # space the pins themselves; graywolf may put them a track apart.
    par = p.layout / f"{p.name}.par"
    par.write_text(re.sub(r"^\*minimum_pad_space\s*:.*$", "*minimum_pad_space    : 0", par.read_text(), flags=re.M))
    _log_pins(p, summary, new_try=True, fresh=first)


def _log_pins(p: Project, summary: dict, new_try: bool, fresh: bool = False) -> None:
    """log/pins.json: one entry per try with pins from cells (NEW_TRY), or SUMMARY added to the
    last one; FRESH starts the list (the block's first such try)."""
    log = p.log / "pins.json"
    tries = json.loads(log.read_text()) if log.exists() and not fresh else []
    if new_try:
        tries.append(summary)
    else:
        tries[-1].update(summary)
    log.write_text(json.dumps(tries, indent=1) + "\n")


def run_steps(p: Project, resume: bool = False) -> dict:
    """Every step in order; step -> seconds. RESUME skips the steps a previous run finished
    (log/STEP.done holds their seconds); a step run again makes every later one run again.
    When qrouter leaves nets unrouted, the block is placed again DENSITY_STEP less dense (down
    to DENSITY_MIN) with its pins placed from its cells (pins.py), and routed again; the
    seconds of every try are summed."""
    times = {}
    i = 0
    while i < len(STEPS):
        step, fn = STEPS[i]
        done = p.log / f"{step}.done"
        if resume and done.exists():
            times[step] = float(done.read_text())
            i += 1
            continue
        resume = False
        t0 = time.time()
        try:
            fn(p)
        except Unrouted:
            times[step] = times.get(step, 0.0) + round(time.time() - t0, 1)
            # Less dense, with the pins placed from this placement's cells (pstlib/pnr/pins.py).
            d = round(density(p) - DENSITY_STEP, 2)
            if d < DENSITY_MIN:
                raise
            hint_pins(p)
            set_density(p, d)
            i = [s for s, _ in STEPS].index("place")
            continue
        times[step] = round(times.get(step, 0.0) + time.time() - t0, 1)
        done.write_text(f"{times[step]}\n")
        i += 1
    times["density"] = density(p)
    return times


# The GDS, then DRC, then LVS: gdsii.sh refuses to run after a DRC or LVS log that ends in an
# error, drc.sh after such an LVS log; the counts are reported rather than hidden.
STEPS = [("synthesize", synthesize), ("place", place), ("route", route), ("migrate", migrate),
         ("gds", gds), ("drc", drc_repair), ("lvs", lvs)]


def results(p: Project) -> dict:
    """DRC errors (magic, against the LEF cell views: Debian's OSU018 has no cell GDS) and the
    LVS verdict (netgen: layout extracted by magic against qflow's netlist) of a finished run."""
    lvs_out = (p.log / "lvs.sh.out").read_text()
    e = re.search(r"Total errors = (\d+)", lvs_out)
    if not e:
        raise FlowError(f"{p.log / 'lvs.sh.out'}: no LVS error count")
    fixed = p.log / "islands.json"
    return {"drc_errors": drc_count(p), "lvs_errors": int(e.group(1)),
            "drc_islands_repaired": json.loads(fixed.read_text()) if fixed.exists() else None,
            "lvs_match": "Circuits match uniquely" in lvs_out and int(e.group(1)) == 0}

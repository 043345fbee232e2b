"""A profile's kept synthesis (scripts/synth.py --keep: NAME.work/ with netlist_sta.v and
standin.lib, NAME.json beside it): the netlist the silicon figures count, for the flows that
read it again (power, equivalence)."""
import json
import pathlib

from .paths import profile_path
from .synth import flow as synth_flow

InputError = synth_flow.InputError


def synthesis(profile: str, out: pathlib.Path, work=None) -> tuple:
    """(the kept synthesis folder, the synthesis record) of PROFILE: WORK when given (a
    NAME.work folder whose NAME.json sits beside it), else OUT/synth/NAME.work, synthesized
    there first unless already present."""
    name = profile_path(profile).stem
    if work:
        work = pathlib.Path(work)
        rec = work.parent / f"{name}.json"
        if not (work / "netlist_sta.v").exists() or not rec.exists():
            raise InputError(f"{work}: not a kept synthesis of {name} (netlist_sta.v, ../{name}.json)")
        return work, json.loads(rec.read_text())
    sdir = pathlib.Path(out) / "synth"
    work = sdir / f"{name}.work"
    rec = sdir / f"{name}.json"
    if not ((work / "netlist_sta.v").exists() and rec.exists()):
        synth_flow.synthesize(profile_path(profile), synth_flow.Options(out=sdir, keep=True, reuse=True, old_basis=False))
    return work, json.loads(rec.read_text())

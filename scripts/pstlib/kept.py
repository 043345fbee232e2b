"""A profile's kept synthesis (scripts/synth.py --keep: NAME.work/ with netlist_sta.v and
standin.lib, NAME.json beside it): the netlist the silicon figures count, for the flows that
read it again (power, equivalence)."""
import json
import pathlib
import sys

from .paths import profile_path
from .synth import flow as synth_flow, record

InputError = synth_flow.InputError


def synthesis(profile: str, out: pathlib.Path, work=None, rom_dir=None) -> tuple:
    """(the kept synthesis folder, the synthesis record) of PROFILE: WORK when given (a
    NAME.work folder whose NAME.json sits beside it; InputError when an input of its netlist
    has changed since), else OUT/synth/NAME.work, synthesized there first unless present and
    made from the current tree (pstlib/synth/record.py netlist_stale)."""
    path = profile_path(profile)
    name = path.stem
    rom_dir = pathlib.Path(rom_dir) if rom_dir else synth_flow.Options().rom_dir
    if work:
        work = pathlib.Path(work)
        rec = work.parent / f"{name}.json"
        if not (work / "netlist_sta.v").exists() or not rec.exists():
            raise InputError(f"{work}: not a kept synthesis of {name} (netlist_sta.v, ../{name}.json)")
        changed = record.netlist_stale(work, path, rom_dir)
        if changed == [f"no input digest ({record.NETLIST_DIGEST})"]:
            print(f"warning: {work}: kept before input digests existed; cannot tell whether it is the "
                  "current RTL's netlist", file=sys.stderr)
        elif changed:
            raise InputError(f"{work}: kept synthesis out of date for {name}: " + "; ".join(changed[:5])
                             + ("; ..." if len(changed) > 5 else "") + " (synthesize again: scripts/synth.py "
                             f"{name} --keep, or drop --work)")
        return work, json.loads(rec.read_text())
    sdir = pathlib.Path(out) / "synth"
    work = sdir / f"{name}.work"
    rec = sdir / f"{name}.json"
    if not ((work / "netlist_sta.v").exists() and rec.exists() and not record.netlist_stale(work, path, rom_dir)):
        synth_flow.synthesize(path, synth_flow.Options(out=sdir, keep=True, reuse=True, old_basis=False,
                                                       rom_dir=rom_dir))
    return work, json.loads(rec.read_text())

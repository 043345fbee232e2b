"""The silicon record: the synthesis of every baseline profile as it was last run
(scripts/synth/records/PROFILE.{json,md}, scripts/synth.py's own outputs) and, in
scripts/synth/baseline.json, digests of everything those figures were made from.

The figures are a function of the RTL, the profiles, the ROM images, the synthesis flow and its
constraints, the cell library and the tools' versions (INPUTS below, `tools`). While none of
them changed, the record stands: the main job takes the silicon tables from it (minutes of
Yosys and OpenSTA saved) and says so; `scripts/run.sh --synth` synthesizes again and checks
the figures against the baseline. When an input changed, `scripts/check_baseline.py --stale`
(ctest baseline_stale, in the default suite) fails naming the files, until the profiles are
synthesized again and the baseline rewritten (`--update` or `--add`), which also rewrites the
record."""
import hashlib
import json
import pathlib
import shutil

from .. import digest
from ..paths import ROOT
from .liberty import osu018_lib

RECORDS = ROOT / "scripts" / "synth" / "records"
# Everything a synthesis reads from the tree (scripts/synth.py and pstlib/synth/: the RTL, the
# profiles and the contract they are checked against, the flow, constraints, stand-in cells and
# the post-route derate it applies), tests aside.
INPUTS = ("rtl/**/*.sv", "rtl/**/*.svh", "rtl/contract.toml", "rtl/configs/*.toml",
          "scripts/synth.py", "scripts/pstlib/synth/[!t]*.py", "scripts/pstlib/synth/tools.py",
          "scripts/pstlib/contract.py", "scripts/synth/pst.sdc", "scripts/synth/cells.lib",
          "scripts/synth/mem_standin_*.v", "scripts/synth/layout_derate.json")
# Matched by INPUTS but not read by a synthesis: this file (the record's own bookkeeping).
NOT_INPUTS = ("scripts/pstlib/synth/record.py",)


def inputs(rom_dir=None) -> dict:
    """{path: SHA-256} of INPUTS, the ROM images of ROM_DIR (as rom/NAME) and the cell library
    (as lib/NAME)."""
    out = {k: v for k, v in digest.inputs(INPUTS).items() if k not in NOT_INPUTS}
    if rom_dir is not None:
        for p in sorted(pathlib.Path(rom_dir).glob("*.memh")):
            out[f"rom/{p.name}"] = hashlib.sha256(p.read_bytes()).hexdigest()
    lib = osu018_lib()
    if lib is not None:
        out[f"lib/{pathlib.Path(lib).name}"] = hashlib.sha256(pathlib.Path(lib).read_bytes()).hexdigest()
    return out


# Inputs that change the figures but not the netlist: the derate only scales the reported Fmax,
# report.py only writes the record.
NOT_NETLIST = ("scripts/synth/layout_derate.json", "scripts/pstlib/synth/report.py")
NETLIST_DIGEST = "inputs.json"     # in a kept synthesis folder (scripts/synth.py --keep)


def netlist_inputs(profile, rom_dir) -> dict:
    """{path: SHA-256} of what a kept netlist was made from: INPUTS less NOT_NETLIST, the ROM
    images, the cell library and the profile file itself (a test profile lives outside INPUTS)."""
    out = {k: v for k, v in inputs(rom_dir).items() if k not in NOT_NETLIST}
    prof = pathlib.Path(profile).resolve()
    key = prof.relative_to(ROOT).as_posix() if prof.is_relative_to(ROOT) else str(prof)
    out[f"profile/{key}"] = hashlib.sha256(digest.content(prof)).hexdigest()
    return out


def netlist_stale(work, profile, rom_dir) -> list:
    """Why the kept synthesis folder WORK no longer stands for PROFILE in the current tree (the
    inputs that changed since its netlist was made); ["no input digest"] for a folder kept
    before the digest existed; [] when it stands."""
    f = pathlib.Path(work) / NETLIST_DIGEST
    if not f.exists():
        return [f"no input digest ({NETLIST_DIGEST})"]
    return digest.stale(json.loads(f.read_text()), netlist_inputs(profile, rom_dir))


def stale(base: dict, rom_dir=None) -> list:
    """Why BASE (baseline.json) no longer stands for the tree: the inputs that changed (ROM images
    only compared when ROM_DIR is given). ["no input digest"] for a baseline that has none."""
    recorded = base.get("inputs")
    if not recorded:
        return ["no input digest (rewrite the baseline with scripts/check_baseline.py --update)"]
    now = inputs(rom_dir)
    if rom_dir is None:
        recorded = {k: v for k, v in recorded.items() if not k.startswith("rom/")}
    return digest.stale(recorded, now)


def missing(profiles, records: pathlib.Path = RECORDS) -> list:
    """The profiles whose record files are absent."""
    return [p for p in profiles if not all((records / f"{p}.{s}").exists() for s in ("json", "md"))]


def save(out_synth: pathlib.Path, profiles, records: pathlib.Path = RECORDS) -> None:
    """Copies OUT_SYNTH/PROFILE.{json,md} into the record (with the baseline's update)."""
    records.mkdir(parents=True, exist_ok=True)
    for p in profiles:
        for s in ("json", "md"):
            # paths inside the checkout kept relative to it: the record reads the same in any clone
            text = (out_synth / f"{p}.{s}").read_text().replace(f"{ROOT}/", "")
            (records / f"{p}.{s}").write_text(text)


def restore(out_synth: pathlib.Path, profiles, records: pathlib.Path = RECORDS) -> None:
    """Copies the record's PROFILE.{json,md} into OUT_SYNTH (the main job without --synth)."""
    out_synth.mkdir(parents=True, exist_ok=True)
    for p in profiles:
        for s in ("json", "md"):
            shutil.copyfile(records / f"{p}.{s}", out_synth / f"{p}.{s}")

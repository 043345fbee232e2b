"""A kept synthesis is reused only while its netlist's inputs are unchanged (kept.py,
synth/record.py netlist_stale)."""
import json
import pathlib

import pytest

from pstlib import kept
from pstlib.paths import CONFIGS
from pstlib.synth import record


def _kept(tmp_path: pathlib.Path, profile: pathlib.Path, digest: dict = None) -> pathlib.Path:
    work = tmp_path / f"{profile.stem}.work"
    work.mkdir()
    (work / "netlist_sta.v").write_text("module pst_top; endmodule\n")
    (tmp_path / f"{profile.stem}.json").write_text(json.dumps({"profile": profile.stem}))
    if digest is not None:
        (work / record.NETLIST_DIGEST).write_text(json.dumps(digest))
    return work


def test_current_folder_stands(tmp_path):
    prof = CONFIGS / "reduced.toml"
    roms = tmp_path / "rom"
    roms.mkdir()
    (roms / "hash4096.memh").write_text("00\n")
    work = _kept(tmp_path, prof, record.netlist_inputs(prof, roms))
    assert record.netlist_stale(work, prof, roms) == []
    got, rec = kept.synthesis("reduced", tmp_path, work, rom_dir=roms)
    assert got == work and rec["profile"] == "reduced"


def test_changed_input_is_named_and_refused(tmp_path):
    prof = CONFIGS / "reduced.toml"
    roms = tmp_path / "rom"
    roms.mkdir()
    (roms / "hash4096.memh").write_text("00\n")
    made = record.netlist_inputs(prof, roms)
    rtl = next(k for k in made if k.startswith("rtl/") and k.endswith(".sv"))
    made[rtl] = "0" * 64
    work = _kept(tmp_path, prof, made)
    changed = record.netlist_stale(work, prof, roms)
    assert any(rtl in c for c in changed)
    with pytest.raises(kept.InputError, match=rtl.replace(".", r"\.")):
        kept.synthesis("reduced", tmp_path, work, rom_dir=roms)
    # a changed ROM image voids it too
    (roms / "hash4096.memh").write_text("01\n")
    assert any("rom/hash4096.memh" in c for c in record.netlist_stale(work, prof, roms))


def test_derate_does_not_void_the_netlist(tmp_path):
    prof = CONFIGS / "reduced.toml"
    made = record.netlist_inputs(prof, tmp_path)
    assert "scripts/synth/layout_derate.json" not in made
    assert "profile/rtl/configs/reduced.toml" in made


def test_folder_without_digest_is_flagged(tmp_path):
    prof = CONFIGS / "reduced.toml"
    work = _kept(tmp_path, prof)
    assert record.netlist_stale(work, prof, tmp_path) == [f"no input digest ({record.NETLIST_DIGEST})"]

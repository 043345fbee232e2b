"""Tests of pstlib.docs.noise_units (the noise units' table of docs/HARDWARE.md)."""
import json

import pytest

from pstlib.docs import noise_units
from pstlib.paths import ROOT


def test_the_checked_in_table_renders_every_unit():
    units = noise_units.load(ROOT)
    md = noise_units.markdown(units)
    assert [u["profile"] for u in units] == ["reduced", "reduced_worley", "reduced_subband", "reduced_subband_k8",
                                             "full", "full_subband_k8"]
    assert "| subband (isotropic tile, 128 x 128 x 8) (`reduced_subband`) | 4,078 | 20,140 (131,072) |" in md
    assert "- (no fly-in of this basis)" in md
    assert "1.31x; best in hardware 1.93x (the isotropic fade, reduced_bandlimit's RTL; its still 0.0441)" in md
    assert "| 4.22x |" in md
    assert "(`full_subband_k8`) | 270,730 | 347,632 (3,145,728) | 843,913 / 1,063,526 | 106.5 MHz | 3 |" in md


def test_a_missing_field_names_the_file_and_field(tmp_path):
    (tmp_path / "scripts" / "synth").mkdir(parents=True)
    (tmp_path / noise_units.SOURCE).write_text(json.dumps({"units": [{"unit": "x"}]}))
    with pytest.raises(ValueError, match=r"noise_units.json: units\[0\].profile: missing"):
        noise_units.load(tmp_path)

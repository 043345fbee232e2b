"""Tests of the parameter groups (rtl/contract.toml [rtl_params] -> rtl/pst_params.svh): the
group rule of pstlib.contractgen.sv.param_groups (groups compose and may overlap, each
parameter once) and the generated macros."""
import copy
import re

import pytest

from pstlib import contract
from pstlib.contractgen.sv import param_groups, sv_params
from pstlib.paths import ROOT


def with_groups(groups: dict) -> contract.Contract:
    c = copy.copy(contract.load(ROOT / "rtl" / "contract.toml"))
    c.raw = {**c.raw, "rtl_params": groups}
    return c


def test_groups_compose_and_overlap_each_parameter_once():
    c = with_groups({
        "fmt_f": {"params": ["FInt", "FFrac"]},
        "fmt_g": {"params": ["GradInt", "GradFrac"]},
        "sums": {"groups": ["fmt_f", "fmt_g"]},
        "term": {"groups": ["sums", "fmt_f"], "params": ["NoiseOutFrac"]},   # fmt_f twice: once
    })
    got = {name: params for name, _, params in param_groups(c)}
    assert got["SUMS"] == ["FInt", "FFrac", "GradInt", "GradFrac"]
    assert got["TERM"] == ["FInt", "FFrac", "GradInt", "GradFrac", "NoiseOutFrac"]
    assert got["FMT_F"] == ["FInt", "FFrac"]             # overlapping groups keep their own lists
    assert got["PROFILE"] == c.param_names


@pytest.mark.parametrize("groups, error", [
    ({"a": {"params": ["NoSuchParam"]}}, "NoSuchParam is not a profile parameter"),
    ({"a": {"groups": ["b"]}, "b": {"params": ["FInt"]}}, "group b is not defined above it"),
    ({"a": {"params": ["FInt", "FInt"]}}, "FInt: it is listed twice"),
    ({"a": {"params": ["FInt"]}, "b": {"groups": ["a"], "params": ["FInt"]}}, "FInt: its groups bring it"),
    ({"a": {"doc": "nothing"}}, "names no groups and no params"),
    ({"a": {"param": ["FInt"]}}, "unknown key param"),
])
def test_group_errors(groups, error):
    with pytest.raises(ValueError, match=re.escape(error)):
        param_groups(with_groups(groups))


def test_macros_declare_and_pass_the_union():
    text = sv_params(with_groups({
        "fmt_f": {"params": ["FInt", "FFrac"]},
        "term": {"groups": ["fmt_f"], "params": ["NoiseOutFrac"]},
    }))
    decl = text[text.index("`define PST_TERM_PARAMS"):text.index("`define PST_TERM_PASS")]
    assert re.findall(r"parameter int (\w+) = pst_pkg::(\w+)Default", decl) == [
        ("FInt", "FInt"), ("FFrac", "FFrac"), ("NoiseOutFrac", "NoiseOutFrac")]
    passed = text[text.index("`define PST_TERM_PASS"):].split("\n\n")[0]
    assert re.findall(r"\.(\w+)\((\w+)\)", passed) == [("FInt", "FInt"), ("FFrac", "FFrac"),
                                                       ("NoiseOutFrac", "NoiseOutFrac")]
    assert "`define PST_PROFILE_PASS" not in text


def test_every_module_takes_its_profile_parameters_from_groups():
    """No RTL module spells out a profile default by hand (pst_pkg::<P>Default lives in the
    generated rtl/pst_params.svh only), and every group macro a module names exists."""
    names = {name for name, _, _ in param_groups(contract.load(ROOT / "rtl" / "contract.toml"))}
    for f in sorted((ROOT / "rtl").rglob("*.sv")) + sorted((ROOT / "rtl").rglob("*.svh")):
        if f.name in ("pst_params.svh",):
            continue
        text = f.read_text()
        assert not re.search(r"pst_pkg::\w+Default\b", text), f"{f.relative_to(ROOT)} spells a default by hand"
        for g in re.findall(r"`PST_(\w+)_(?:PARAMS|PASS)\b", text):
            assert g in names, f"{f.relative_to(ROOT)}: `PST_{g}_... is no group of rtl/contract.toml"

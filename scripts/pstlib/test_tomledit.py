import tomllib

import pytest

from pstlib.paths import ROOT
from pstlib import tomledit

PROFILE = """# a profile
[pipeline]
octaves = 4   # per pixel
datapath = "serial"

[formats]
coord      = { int = 12, frac = 20 }   # s, t, r
jacobian   = { int = 8,  frac = 24 }
width_frac = 8
"""


def test_set_top_key_keeps_comment_and_layout():
    new = tomledit.set_values(PROFILE, {("pipeline", "octaves"): 8})
    assert new == PROFILE.replace("octaves = 4   # per pixel", "octaves = 8   # per pixel")


def test_set_inside_inline_table_touches_that_line_only():
    new = tomledit.set_values(PROFILE, {("formats", "coord", "frac"): 8, ("pipeline", "datapath"): "parallel"})
    assert new.splitlines() == [
        "# a profile", "[pipeline]", "octaves = 4   # per pixel", 'datapath = "parallel"', "",
        "[formats]", "coord      = { int = 12, frac = 8 }   # s, t, r", "jacobian   = { int = 8,  frac = 24 }",
        "width_frac = 8"]


def test_missing_key_goes_under_its_table():
    new = tomledit.set_values(PROFILE, {("pipeline", "noise_units"): 2})
    assert new.splitlines()[1:3] == ["[pipeline]", "noise_units = 2"]
    assert tomllib.loads(new)["pipeline"] == {"noise_units": 2, "octaves": 4, "datapath": "serial"}


def test_hash_inside_a_string_is_not_a_comment():
    text = '[t]\nname = "a # b"  # c\n'
    assert tomledit.set_values(text, {("t", "name"): "x"}) == '[t]\nname = "x"  # c\n'


@pytest.mark.parametrize("changes", [
    {("nosuch", "key"): 1},                          # no such table
    {("pipeline", "octaves", "frac"): 1},            # into an integer
])
def test_what_it_cannot_do_raises(changes):
    with pytest.raises(ValueError):
        tomledit.set_values(PROFILE, changes)


def test_value_over_several_lines_raises():
    with pytest.raises(ValueError, match="several lines"):
        tomledit.set_values("[t]\nxs = [\n  1,\n]\n", {("t", "xs"): 2})


def test_subtable_header_is_not_overwritten_by_a_key():
    text = "[textures.a]\nscale = 1\n[textures.a.noise]\nhash = \"rayshade\"\n"
    with pytest.raises(ValueError):
        tomledit.set_values(text, {("textures", "a", "noise"): {"hash": "perm256"}})


def test_value_text():
    assert tomledit.value_text({"int": 3, "frac": 0}) == "{ int = 3, frac = 0 }"
    assert tomledit.value_text('say "hi"') == '"say \\"hi\\""'
    assert tomledit.value_text(True) == "true"
    with pytest.raises(ValueError):
        tomledit.value_text(1.5)


def test_changes_between():
    old = {"a": {"x": 1, "f": {"int": 2, "frac": 3}}, "b": {"s": "p"}}
    new = {"a": {"x": 1, "f": {"int": 2, "frac": 4}}, "b": {"s": "q", "t": 1}}
    assert tomledit.changes_between(old, new) == {("a", "f", "frac"): 4, ("b", "s"): "q", ("b", "t"): 1}
    with pytest.raises(ValueError):
        tomledit.changes_between(new, old)


def test_real_profile_round_trip():
    text = (ROOT / "rtl" / "configs" / "full.toml").read_text()
    doc = tomllib.loads(text)
    new = tomledit.set_values(text, {("formats", "offset", "frac"): 9, ("noise", "lattice_frac"): 9})
    got = tomllib.loads(new)
    assert got["formats"]["offset"] == {"int": doc["formats"]["offset"]["int"], "frac": 9}
    assert got["noise"]["lattice_frac"] == 9
    assert sum(a != b for a, b in zip(text.splitlines(), new.splitlines())) == 2
    assert len(new.splitlines()) == len(text.splitlines())


def test_with_comment():
    assert tomledit.with_comment("a = 1\n", "one\n\ntwo") == "# one\n#\n# two\na = 1\n"


def test_without_leading_comment():
    assert tomledit.without_leading_comment(PROFILE) == PROFILE[len("# a profile\n"):]
    assert tomledit.without_leading_comment("# x\n\n# y\n[t]\n# z\na = 1\n") == "[t]\n# z\na = 1\n"

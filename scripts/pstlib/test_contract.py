"""Tests of pstlib.contract: the profile schema and the generators (run by ctest through pytest)."""
import copy
import re
import tomllib

import pytest

from pstlib import contract, contractgen
from pstlib.contractgen.common import emit_formula
from pstlib.paths import ROOT

PROFILES = sorted((ROOT / "rtl" / "configs").glob("*.toml")) + sorted((ROOT / "sim" / "test_profiles").glob("*.toml"))


def reduced() -> dict:
    with open(ROOT / "rtl" / "configs" / "reduced.toml", "rb") as f:
        return tomllib.load(f)


@pytest.mark.parametrize("path", PROFILES, ids=lambda p: p.stem)
def test_shipped_profiles_are_valid(path):
    assert contract.validate(contract.read_profile(path)) == []


def test_parameter_names_follow_the_rule():
    assert contract.param_name("pipeline", "octaves") == "Octaves"
    assert contract.param_name("noise", "out_frac") == "NoiseOutFrac"
    assert contract.param_name("filter", "norm") == "FilterNorm"
    assert contract.param_name("formats", "grad_matrix", "int") == "GradMatrixInt"
    assert contract.param_name("formats", "width_frac") == "WidthFrac"


def test_parameters_of_reduced():
    p = dict(contract.parameters(reduced()))
    # Values as written in rtl/configs/reduced.toml; enums as their index in the description.
    assert p["Octaves"] == 5 and p["NoiseUnits"] == 1 and p["NoiseSteps"] == 4
    assert p["Datapath"] == 1 and p["NoiseInterp"] == 0 and p["FilterNorm"] == 0 and p["FilterBandlimit"] == 0
    assert (p["CoordInt"], p["CoordFrac"], p["WidthFrac"]) == (10, 12, 4)
    assert (p["NoiseRegs"], p["OctaveRegs"], p["WidthRegs"], p["ColourRegs"]) == (5, 1, 0, 2)
    assert p["NoiseWorleySearch"] == 0 and p["NoiseWorleyPoints"] == 4 and p["NoiseWorleyOrder"] == 2
    assert p["NoiseSubband"] == 0 and p["NoiseSubbandOrientations"] == 0   # no subband unit
    assert p["NoiseGradFrac"] == 10   # out_frac 8 + guard_bits 2: every node bit
    assert p["FilterWidthCap"] == 0   # no width cap
    assert len(p) == 46


def test_enum_tables():
    assert contract.ENUMS[("pipeline", "datapath")] == ["parallel", "serial"]
    assert contract.ENUMS[("filter", "norm")] == ["euclid", "max_half_min", "l1"]
    assert contract.FORMAT_MAX["coord"] == 40 and contract.FORMAT_MAX["quadric"] == 32
    assert contract.RANGES[("pipeline", "noise_steps")] == (1, 2, 4, 8)


@pytest.mark.parametrize("edit, field", [
    (lambda d: d["pipeline"].update(noise_units=3), "pipeline.noise_units"),   # serial: must divide
    (lambda d: d["pipeline"].update(noise_units=16), "pipeline.noise_units"),  # more than octaves
    (lambda d: d["pipeline"].update(noise_steps=2), "pipeline.datapath"),   # serial needs >= 4
    (lambda d: d["pipeline"].update(noise_steps=3), "pipeline.noise_steps"),
    (lambda d: d["noise"].update(grad_frac=0), "noise.grad_frac"),
    (lambda d: d["noise"].update(grad_frac=4, worley_search="octant", hash="perm256"), "noise.grad_frac"),
    (lambda d: d["pipeline"].update(octaves=17), "pipeline.octaves"),
    (lambda d: d["pipeline"].update(octaves=True), "pipeline.octaves"),
    (lambda d: d["pipeline"].update(datapath="fast"), "pipeline.datapath"),
    (lambda d: d["formats"].update(matrix={"int": 7, "frac": 4}, coord={"int": 10, "frac": 2}),
     "noise.lattice_frac"),   # 8 > matrix + coord frac = 6
    (lambda d: d["formats"].update(offset={"int": 13, "frac": 21}), "formats.offset"),
    (lambda d: d["formats"].update(quadric={"int": 20, "frac": 13}), "formats.quadric"),
    (lambda d: d["formats"].update(quadric={"int": 1, "frac": 0}), "formats.quadric"),
    (lambda d: d["formats"].update(coord={"int": 0, "frac": 12}), "formats.coord.int"),
    (lambda d: d["formats"].update(width_frac=-1), "formats.width_frac"),
    (lambda d: d["pipeline"].update(log2_clut=1) or d["formats"].update(width_frac=0), "formats.width_frac"),
    (lambda d: d.pop("filter"), "filter"),
    (lambda d: d["noise"].pop("hash"), "noise.hash"),
])
def test_validate_names_the_field(edit, field):
    d = copy.deepcopy(reduced())
    edit(d)
    bad = contract.validate(d)
    assert bad, "expected an error"
    assert any(b.split(": ", 1)[0] == field for b in bad), bad


def test_stage_cycles():
    # reduced: 5 octaves x 4 steps + 6 serial rows + 5 noise registers + the term register = 32
    # cycles per pixel (`pst regress` measures 32); its serial quadric takes 3 (3 + 1 + 3) + 1
    # steps with its product register, + 1 for its result register, its euclidean filter width
    # 16 (the RTL's, checked by sim/unit/arith_unit_test against the golden model), its colour
    # filter 4 + 2 registers; full_1clk is one pixel per clock whatever its pipeline registers,
    # full_2clk (eight octaves over two passes of four noise units) two, full (three passes of
    # three, the last with an idle lane) three.
    assert contract.stage_cycles(reduced()) == {"octave": 32, "quadric": 23, "width": 16, "colour": 6, "pixel": 32}
    for name, cycles in (("full_1clk", 1), ("full_2clk", 2), ("full", 3)):
        with open(ROOT / "rtl" / "configs" / f"{name}.toml", "rb") as f:
            assert contract.stage_cycles(tomllib.load(f))["pixel"] == cycles, name


def test_constraint_translation():
    e = "Datapath != Datapath.serial || NoiseSteps >= 4"
    assert contract.translate(e, "py") == "v['Datapath'] != 1 or v['NoiseSteps'] >= 4"
    assert contract.translate(e, "cpp") == "v[Datapath] != 1 || v[NoiseSteps] >= 4"
    assert contract.translate(e, "sv") == "Datapath != pst_pkg::DatapathSerial || NoiseSteps >= 4"
    with pytest.raises(ValueError):
        contract.translate("Octaves > Nope", "py")
    with pytest.raises(ValueError):
        contract.translate("Datapath == Datapath.fast", "py")


def test_read_profile_error_has_line(tmp_path):
    text = (ROOT / "rtl" / "configs" / "reduced.toml").read_text().replace("noise_units = 1", "noise_units = 3")
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(contract.ProfileError) as e:
        contract.read_profile(p)
    line = text.splitlines().index("noise_units = 3") + 1
    assert str(e.value) == f"{p}:{line}: pipeline.noise_units: must divide pipeline.octaves on the serial datapath"


def test_read_profile_syntax_and_missing(tmp_path):
    p = tmp_path / "x.toml"
    p.write_text("[pipeline\n")
    with pytest.raises(contract.ProfileError, match="syntax"):
        contract.read_profile(p)
    with pytest.raises(contract.ProfileError, match="file"):
        contract.read_profile(tmp_path / "missing.toml")


def test_generated_files_are_current():
    gen = contractgen.generate(ROOT)
    for rel, text in gen.items():
        assert (ROOT / rel).read_text() == text, f"{rel} is stale: run `cd scripts && /usr/bin/python3 -m pstlib.contractgen --write`"


def test_one_line_edit_changes_generated_files(tmp_path):
    # A register address edited once in the description reaches the package, the header and
    # the docs table.
    src = (ROOT / "rtl" / "contract.toml").read_text()
    assert "addr = 0x1000" in src
    (tmp_path / "rtl").mkdir()
    (tmp_path / "rtl" / "contract.toml").write_text(src.replace("addr = 0x1000", "addr = 0x1800"))
    (tmp_path / "rtl" / "configs").mkdir()
    for f in (ROOT / "rtl" / "configs").glob("*.toml"):
        (tmp_path / "rtl" / "configs" / f.name).write_text(f.read_text())
    c = contract.load(tmp_path / "rtl" / "contract.toml")
    gen = contractgen.generate(tmp_path, c)
    assert "localparam logic [15:0] RegClut = 16'h1800;" in gen["rtl/pst_pkg.sv"]
    assert "kRegClut = 0x1800;" in gen["model/golden/contract.h"]
    assert "| 0x1800 + e |" in contractgen.hardware_md_table(c)     # docs/HARDWARE.md (scripts/gen_docs.py)


def test_profile_key_reference_has_every_key():
    """docs/PROFILES.md's table (scripts/gen_docs.py): every schema key with its type and full's value."""
    c = contract.load()
    text = contractgen.profile_keys_md(c, ROOT)
    for k in c.keys:
        assert f"| `{k.key}` | " in text, k.field
    assert "| `octaves` | `Octaves` | integer, 1 .. 16 | 8 |" in text
    assert "| `datapath` | `Datapath` | string: `parallel`, `serial` | `parallel` |" in text
    assert "| `noise_steps` | `NoiseSteps` | integer: 1, 2, 4, 8 | 1 |" in text
    for con in c.constraints:
        assert con.message.split("|")[0].strip() in text


def test_generated_cpp_enums_follow_the_contract():
    """Every enum key is one `enum class` of contract.h, its enumerators the values in order."""
    import re
    text = (ROOT / "model" / "golden" / "contract.h").read_text()
    found = {m.group(1): [v.strip() for v in m.group(2).split(",")]
             for m in re.finditer(r"^enum class (\w+) : int \{ ([^}]*) \};", text, re.M)}
    c = contract.load()
    for k in c.keys:
        if k.kind == "enum":
            assert found[k.cpp_type] == [contract.camel(v) for v in k.enum], k.field
    assert found["GradNorm"] == ["Euclid", "MaxHalfMin", "L1"]   # filter.norm, cpp = "GradNorm"
    # ... and the hand-written copies are gone from the reference model's headers.
    for header in ("noise.h", "texture.h"):
        body = (ROOT / "model" / header).read_text()
        for name in ("NoiseInterp", "NoiseCorner", "NoiseHash", "GradNorm"):
            assert f"enum class {name}" not in body, (header, name)


def test_formulas_in_three_languages():
    c = contract.load()
    f = {x.name: x for x in c.formulas}
    # The same tree, written per language (operations in parentheses, ?: as Python's if-else).
    t = f["octave_cycles"].tree
    assert "DatapathSerial" in emit_formula(t, "sv", c)
    assert "kSerialOctaveExtraCycles" in emit_formula(t, "cpp", c)
    assert " if (Datapath == 1) else 0" in emit_formula(t, "py", c)
    sv = (ROOT / "rtl" / "pst_pkg.sv").read_text()
    cpp = (ROOT / "model" / "golden" / "contract.h").read_text()
    for name in f:
        assert f"function automatic int {name}(" in sv
        assert f"constexpr int {name}(" in cpp
        assert callable(getattr(contract.formulas, name))
    # Values: W of reduced (log2_clut 8, width_frac 4); the serial units' steps.
    assert contract.formulas.w_width(8, 4) == 14 and contract.formulas.w_int_bits(8) == 10
    assert contract.formulas.quadric_serial_steps(15, 22, 1) == 22
    assert contract.formulas.width_serial_steps(0, 8, 4) == 16 and contract.formulas.width_serial_steps(2, 8, 4) == 6


def test_clog2_builtin_and_the_octave_count_width():
    c = contract.load()
    t = contract.parse_formula("clog2(Octaves + 1)", ["Octaves"], c)
    assert emit_formula(t, "sv", c) == "$clog2((Octaves + 1))"
    assert emit_formula(t, "cpp", c) == "clog2_int((octaves + 1))"
    assert emit_formula(t, "py", c) == "clog2_int((Octaves + 1))"
    assert "constexpr int clog2_int(int a)" in (ROOT / "model" / "golden" / "contract.h").read_text()
    # SystemVerilog's $clog2: the least b with 2^b >= a.
    assert [contract.formulas.clog2_int(a) for a in range(10)] == [0, 0, 1, 2, 2, 3, 3, 3, 3, 4]
    # The active count 0..Octaves: as many bits as Octaves has.
    assert [contract.formulas.octave_count_bits(k) for k in range(1, 17)] == [k.bit_length() for k in range(1, 17)]


@pytest.mark.parametrize("expr, error", [("Octaves + Nope", "unknown name Nope"),
                                         ("Datapath == Datapath.fast", "unknown enum value"),
                                         ("later(Octaves)", "unknown function later"),
                                         ("max(Octaves)", "max takes 2 arguments"),
                                         ("clog2(Octaves, 2)", "clog2 takes 1 arguments"),
                                         ("(Octaves", "expected ')'")])
def test_formula_errors(expr, error):
    with pytest.raises(ValueError, match=re.escape(error)):
        contract.parse_formula(expr, ["Octaves", "Datapath"], contract.load())


def test_formula_precedence_is_c():
    c = contract.load()
    for expr, value in [("1 + 2 * 3", 7), ("Octaves - 1 - 1", 3), ("Octaves >= 5 ? 1 : 0", 1),
                        ("Octaves == 5 && !(Octaves < 2) ? Octaves << 1 : 0", 10), ("7 / 2 + 7 % 2", 4),
                        ("max(Octaves, 9) + min(1, 2)", 10), ("0 ? 1 : 0 ? 2 : 3", 3)]:
        py = emit_formula(contract.parse_formula(expr, ["Octaves"], c), "py", c)
        assert eval(py, {"max": max, "min": min}, {"Octaves": 5}) == value, expr  # noqa: S307

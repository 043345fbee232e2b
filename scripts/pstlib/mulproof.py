"""The proof that pst_mul_booth's two forms are one function, for every width a profile
instantiates (rtl/common/pst_mul_booth.sv: the synthesis form, radix-4 Booth rows, and the
simulation form under PST_MUL_BEHAVIOURAL, one `*`).

A Booth multiplier and `*` are hard for SAT (ABC's &cec: 8 x 8 bits in tens of seconds, 12 x 12
not in minutes). The proof goes through the digit form sim/formal/pst_mul_digits.sv, which
has the Booth rows' bits and sum order and is, as arithmetic, a polynomial:

  Q1  synthesis form == digit form: ABC's &cec on Yosys's miter of the two (fraiging finds the
      rows equal, then the sums are the same adders);
  Q2  digit form == sext(a) * bitsum(b) mod 2^PW: Z3 brings both sides of Yosys's SMT-LIB
      model of the digit form to their sum-of-monomials normal form (polynomials in a and the
      bits of b) and finds the difference 0;
  Q3  bitsum(b) == b extended to PW bits (its sign or zeros): Z3, bit-level;
  Q0  simulation form == sext(a) * ext(b) mod 2^PW: Z3 on Yosys's SMT-LIB model of the
      simulation form.

Q0, Q3 and Q2 make the simulation form equal to the digit form (substituting the equal bitsum
for ext(b)), Q1 the digit form equal to the synthesis form."""
import dataclasses
import json
import pathlib
import subprocess
import time

from . import contract, digest
from .paths import ROOT
from .synth import tools

BOOTH = ROOT / "rtl" / "common" / "pst_mul_booth.sv"
DIGITS = ROOT / "sim" / "formal" / "pst_mul_digits.sv"
PARAMS = ("AW", "BW", "BSigned", "PW")
# The record of the last full proof (scripts/mul_proof.py --record), checked by `--cached`.
RECORD = ROOT / "sim" / "formal" / "mul_proof.record.json"
# What one width's proof depends on: the two forms and this code (the tools' versions beside).
PROOF_INPUTS = ("rtl/common/pst_mul_booth.sv", "sim/formal/pst_mul_digits.sv", "scripts/pstlib/mulproof.py",
                "scripts/pstlib/synth/tools.py")
# What decides which widths the profiles instantiate: the RTL and every profile.
ELABORATION_INPUTS = ("rtl/**/*.sv", "rtl/**/*.svh", "rtl/contract.toml", "rtl/configs/*.toml",
                      "sim/test_profiles/*.toml", "scripts/pstlib/contract.py")


@dataclasses.dataclass(frozen=True, order=True)
class Width:
    aw: int
    bw: int
    bsigned: int
    pw: int

    def chparam(self, module: str) -> str:
        return f"chparam -set AW {self.aw} -set BW {self.bw} -set BSigned {self.bsigned} -set PW {self.pw} {module}"

    def __str__(self) -> str:
        return f"{self.aw} x {self.bw}{'' if self.bsigned else 'u'} -> {self.pw}"


def instantiated(profile: pathlib.Path, rom_dir, tmp: pathlib.Path) -> set:
    """Every (AW, BW, BSigned, PW) of pst_mul_booth in PROFILE's pst_top (Yosys elaborates it)."""
    doc = contract.read_profile(profile)
    tmp.mkdir(parents=True, exist_ok=True)
    out = tmp / "hier.json"
    tools.run_yosys("\n".join(tools.read_lines(doc, rom_dir) + [
        "hierarchy -top pst_top", "proc", f"write_json {out}"]), tmp, "hier")
    mods = json.loads(out.read_text())["modules"]
    return {Width(*(int(m["parameter_default_values"][k], 2) for k in PARAMS))
            for name, m in mods.items() if tools.base_name(name) == "pst_mul_booth"
            and "parameter_default_values" in m}


def _abc(aig: pathlib.Path) -> str:
    r = subprocess.run(["yosys-abc", "-c", f"read_aiger {aig}; &get; &cec -m"], capture_output=True, text=True,
                       timeout=3600)
    return r.stdout + r.stderr


def q1(w: Width, tmp: pathlib.Path, booth=BOOTH, digits=DIGITS) -> tuple:
    """(proven, ABC's verdict line): the synthesis form against the digit form."""
    aig = tmp / "miter.aig"
    tools.run_yosys("\n".join([
        f"read_verilog -sv -I {ROOT / 'rtl'} {booth}", f"read_verilog -sv {digits}",
        w.chparam("pst_mul_booth"), w.chparam("pst_mul_digits"), "proc",
        "miter -equiv -flatten pst_mul_booth pst_mul_digits miter", "hierarchy -top miter",
        "flatten", "opt -fast", "techmap", "opt -fast", "aigmap", f"write_aiger -zinit {aig}"]), tmp, "q1")
    out = _abc(aig)
    verdict = next((line.strip() for line in out.splitlines() if "EQUIVALENT" in line.upper()), out.strip()[-200:])
    return "Networks are equivalent" in out, verdict


def _smt2(w: Width, tmp: pathlib.Path, source, top: str, define: str = "") -> str:
    path = tmp / f"{top}.smt2"
    tools.run_yosys("\n".join([
        f"read_verilog -sv {define} -I {ROOT / 'rtl'} {source}", w.chparam(top), f"hierarchy -top {top}", "proc",
        "flatten", f"write_smt2 -wires {path}"]), tmp, f"smt_{top}")
    return path.read_text()


def _terms(z3, text: str, top: str, w: Width) -> tuple:
    """The model's output p_o and its inputs a_i, b_i as Z3 terms of one state."""
    text += (f"(declare-const s |{top}_s|)\n"
             f"(declare-const p (_ BitVec {w.pw}))\n(assert (= p (|{top}_n p_o| s)))\n"
             f"(declare-const a (_ BitVec {w.aw}))\n(assert (= a (|{top}_n a_i| s)))\n"
             f"(declare-const b (_ BitVec {w.bw}))\n(assert (= b (|{top}_n b_i| s)))\n")
    got = {str(f.arg(0)): f.arg(1) for f in z3.parse_smt2_string(text) if z3.is_eq(f)}
    return got["p"], got["a"], got["b"]


def _ext(z3, x, width: int, to: int, signed: bool):
    if to == width:
        return x
    if to < width:
        return z3.Extract(to - 1, 0, x)
    return z3.SignExt(to - width, x) if signed else z3.ZeroExt(to - width, x)


def q023(w: Width, tmp: pathlib.Path, booth=BOOTH, digits=DIGITS) -> dict:
    """Q2, Q3 and Q0 (see the module's text): {name: proven}."""
    import z3   # Debian python3-z3
    pw = w.pw
    p_d, a, b = _terms(z3, _smt2(w, tmp, digits, "pst_mul_digits"), "pst_mul_digits", w)
    sa = _ext(z3, a, w.aw, pw, True)
    bits = [z3.ZeroExt(pw - 1, z3.Extract(j, j, b)) for j in range(w.bw)]
    bitsum = z3.BitVecVal(0, pw)
    for j, e in enumerate(bits):   # b = sum_j b_j 2^j, the sign bit weighing -2^(BW-1) when signed
        weight = -(1 << j) if (w.bsigned and j == w.bw - 1) else (1 << j)
        bitsum = bitsum + e * (weight % (1 << pw))
    diff = z3.simplify(p_d - sa * bitsum, som=True, som_blowup=1 << 30)
    res = {"Q2": z3.is_bv_value(diff) and diff.as_long() == 0}
    ext_b = _ext(z3, b, w.bw, pw, bool(w.bsigned))
    s = z3.Solver()
    s.add(bitsum != ext_b)
    res["Q3"] = s.check() == z3.unsat
    p_s, a_s, b_s = _terms(z3, _smt2(w, tmp, booth, "pst_mul_booth", "-D PST_MUL_BEHAVIOURAL"), "pst_mul_booth", w)
    spec = z3.substitute(sa * ext_b, (a, a_s), (b, b_s))
    d0 = z3.simplify(p_s - spec, som=True, som_blowup=1 << 30)
    res["Q0"] = z3.is_bv_value(d0) and d0.as_long() == 0
    return res


def prove(w: Width, tmp: pathlib.Path, booth=BOOTH, digits=DIGITS) -> dict:
    """Every step for one width: {Q0..Q3: proven, 'abc': ABC's verdict, 'seconds': s, 'proven': all}."""
    tmp.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    ok1, verdict = q1(w, tmp, booth, digits)
    res = {"Q1": ok1, "abc": verdict, **q023(w, tmp, booth, digits)}
    res["proven"] = all(res[k] for k in ("Q0", "Q1", "Q2", "Q3"))
    res["seconds"] = round(time.time() - t0, 1)
    return res


def tool_versions() -> dict:
    """The versions of the tools a proof runs (Yosys with its ABC, Z3)."""
    import z3   # Debian python3-z3
    return {"yosys": tools.tool_version(["yosys", "-V"]), "z3": z3.get_version_string()}


def width_key(w: Width) -> dict:
    return {"aw": w.aw, "bw": w.bw, "bsigned": w.bsigned, "pw": w.pw}


def make_record(widths: dict) -> dict:
    """The record of a full proof: {Width: [profiles]} every one proven, and the digests of the
    inputs it was made from (digest.py)."""
    return {"schema": 1, "made_by": "scripts/mul_proof.py --record", "tools": tool_versions(),
            "proof_inputs": digest.inputs(PROOF_INPUTS), "elaboration_inputs": digest.inputs(ELABORATION_INPUTS),
            "widths": [{**width_key(w), "profiles": sorted(set(p))} for w, p in sorted(widths.items())]}


def read_record(path: pathlib.Path = RECORD) -> dict:
    """The record, or None when there is none. Raises ValueError on a malformed one."""
    if not path.exists():
        return None
    rec = json.loads(path.read_text())
    if rec.get("schema") != 1 or not isinstance(rec.get("widths"), list):
        raise ValueError(f"{path}: not a schema-1 proof record")
    return rec


def record_widths(rec: dict) -> dict:
    """{Width: [profiles]} of a record."""
    return {Width(r["aw"], r["bw"], r["bsigned"], r["pw"]): r["profiles"] for r in rec["widths"]}


def record_status(rec: dict, versions: dict = None) -> tuple:
    """(why the elaboration is stale, why the proofs are stale): each a list of reasons (changed
    files, moved tool versions), empty where the record stands for the tree as it is."""
    if rec is None:
        return ["no record"], ["no record"]
    versions = versions if versions is not None else tool_versions()
    elab = digest.stale(rec["elaboration_inputs"], digest.inputs(ELABORATION_INPUTS))
    proof = digest.stale(rec["proof_inputs"], digest.inputs(PROOF_INPUTS), rec["tools"], versions)
    return elab, proof

"""Switching activity of a simulated run: per-bit toggle rates and duty cycles read from a VCD
(the verilated RTL's FST through gtkwave's fst2vcd), in OpenSTA's units.

OpenSTA's `set_power_activity -activity A -duty D` takes A in transitions per clock period and D
as the fraction of time the signal is 1. Here both are measured over the traced window: A is the
number of value changes of a bit divided by the number of rising clock edges in the window, D
the time the bit spent at 1 divided by the window's length (x and z count as 0).

Every signal is keyed by its hierarchical path below the design's top, scopes joined by "/"
(generate blocks are scopes: u_clut/g_ch[0]/u_channel/q_o), and holds one (activity, duty)
pair per bit, bit index as the signal's declared range numbers it.
"""
import dataclasses
import pathlib
import re
import subprocess


class VcdError(ValueError):
    """A VCD this reader cannot use (no clock, no time, a malformed line)."""


@dataclasses.dataclass
class Signal:
    width: int
    lsb: int                 # the declared range's low index ([7:0] -> 0, [8:1] -> 1)
    msb_first: bool          # [hi:lo] (True) or [lo:hi]


@dataclasses.dataclass
class Activity:
    cycles: int                          # rising clock edges in the window
    window: int                          # time units covered
    rates: dict                          # path -> list of (activity, duty), index = bit - lsb
    lsb: dict                            # path -> the declared range's low index
    changes: dict = dataclasses.field(default_factory=dict)   # path -> value changes in the window

    def bit(self, path: str, index: int):
        """(activity, duty) of bit INDEX of signal PATH, or None when not traced."""
        r = self.rates.get(path)
        if r is None:
            return None
        i = index - self.lsb.get(path, 0)
        return r[i] if 0 <= i < len(r) else None

    def mean(self, prefix: str = ""):
        """Mean activity of every traced bit under PREFIX (None when there is none)."""
        vals = [a for p, r in self.rates.items() if p.startswith(prefix) for a, _ in r]
        return sum(vals) / len(vals) if vals else None


_RANGE = re.compile(r"\[(-?\d+)(?::(-?\d+))?\]$")


def _parse_range(tokens: list) -> tuple:
    """($var ... name [hi:lo]) -> (name, lsb, msb_first); the range may be glued to the name."""
    name = tokens[0]
    rng = tokens[1] if len(tokens) > 1 and tokens[1].startswith("[") else None
    if rng is None:
        m = _RANGE.search(name)
        if m and m.group(2) is not None:
            rng, name = m.group(0), name[:m.start()]
    if rng is None:
        return name, 0, True
    m = _RANGE.match(rng)
    if not m:
        return name, 0, True
    a = int(m.group(1))
    b = int(m.group(2)) if m.group(2) is not None else a
    return name, min(a, b), a >= b


def fst_to_vcd(fst, vcd) -> None:
    """FST (the harness's trace, `pst render --trace`) to VCD with gtkwave's fst2vcd; RuntimeError
    naming fst2vcd's complaint when it fails (the VCD then absent)."""
    vcd = pathlib.Path(vcd)
    with open(vcd, "w") as f:
        r = subprocess.run(["fst2vcd", str(fst)], stdout=f, stderr=subprocess.PIPE, text=True)
    if r.returncode:
        vcd.unlink(missing_ok=True)
        raise RuntimeError(f"fst2vcd: {r.stderr.strip()}")


def read_vcd(path, clock: str = "clk_i", top_scopes: int = 2) -> Activity:
    """Activity of every traced signal of VCD file PATH. CLOCK: the name of the clock at the top;
    TOP_SCOPES: scopes above the design's top (Verilator's trace: TOP's wrapper and the top
    module's own scope, both named pst_top) dropped from the paths."""
    scopes = []
    ids = {}                   # id code -> list of (path, Signal)
    clock_id = None
    with open(path, "r", encoding="ascii", errors="replace") as f:
        for line in f:
            tok = line.split()
            if not tok:
                continue
            if tok[0] == "$scope":
                scopes.append(tok[2])
            elif tok[0] == "$upscope":
                scopes.pop()
            elif tok[0] == "$var":
                # $var TYPE WIDTH ID NAME [RANGE] $end
                kind, width, code = tok[1], int(tok[2]), tok[3]
                if kind == "parameter":
                    continue
                name, lsb, msb_first = _parse_range(tok[4:-1])
                p = "/".join(scopes[top_scopes:] + [name])
                ids.setdefault(code, []).append((p, Signal(width, lsb, msb_first)))
                if name == clock and len(scopes) <= top_scopes and clock_id is None:
                    clock_id = code
            elif tok[0] == "$enddefinitions":
                break
        if clock_id is None:
            raise VcdError(f"{path}: no clock '{clock}' at the top")
        width = {c: v[0][1].width for c, v in ids.items()}
        value = {c: 0 for c in ids}
        since = {c: 0 for c in ids}
        toggles = {c: [0] * width[c] for c in ids}
        changes = {c: 0 for c in ids}
        high = {c: [0] * width[c] for c in ids}
        t = None
        t0 = None
        cycles = 0

        def change(code: str, new: int) -> None:
            nonlocal cycles
            if code not in value:
                return
            old = value[code]
            if t0 is not None and t is not None:
                dt = t - since[code]
                if old and dt:
                    h = high[code]
                    x = old
                    while x:
                        low = x & -x
                        h[low.bit_length() - 1] += dt
                        x ^= low
                diff = old ^ new
                if diff and t > t0:          # the dump's first values are not transitions
                    changes[code] += 1
                    tg = toggles[code]
                    while diff:
                        low = diff & -diff
                        tg[low.bit_length() - 1] += 1
                        diff ^= low
                    if code == clock_id and new == 1:
                        cycles += 1
            value[code] = new
            since[code] = t if t is not None else 0

        for line in f:
            c = line[:1]
            if c == "#":
                try:
                    t = int(line[1:])
                except ValueError:
                    raise VcdError(f"{path}: bad time '{line.strip()}'") from None
                if t0 is None:
                    t0 = t
            elif c in "01xzXZ":
                change(line[1:].strip(), 1 if c == "1" else 0)
            elif c in "bB":
                bits, _, code = line[1:].partition(" ")
                bits = bits.replace("x", "0").replace("z", "0").replace("X", "0").replace("Z", "0")
                try:
                    change(code.strip(), int(bits, 2) if bits else 0)
                except ValueError:
                    raise VcdError(f"{path}: bad vector '{line.strip()}'") from None
            # $dumpvars, $end, real values: nothing to count
    if t is None or t0 is None or t == t0:
        raise VcdError(f"{path}: no time passes in the dump")
    if cycles == 0:
        raise VcdError(f"{path}: the clock '{clock}' never rises")
    span = t - t0
    rates, lsbs, changed = {}, {}, {}
    for code, sigs in ids.items():
        # the time since each bit's last change, at the end of the window
        h = high[code]
        x = value[code]
        while x:
            low = x & -x
            h[low.bit_length() - 1] += t - since[code]
            x ^= low
        r = [(toggles[code][i] / cycles, min(1.0, h[i] / span)) for i in range(width[code])]
        for p, s in sigs:
            rates[p] = r
            lsbs[p] = s.lsb
            changed[p] = changes[code]
    return Activity(cycles=cycles, window=span, rates=rates, lsb=lsbs, changes=changed)

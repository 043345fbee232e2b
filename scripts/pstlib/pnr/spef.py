"""Routed parasitics for OpenSTA: qrouter's RC trees (`write_delays`, the .rc file qflow's
rc2dly reads, and which crashes rc2dly on our blocks) rewritten as SPEF (IEEE 1481).

qrouter writes one line per net (delays.c, write_delays / walk_route_output):

    NET 1 DRIVER/PIN N ( R C [NODE/PIN] [, ] CHILD, CHILD ... )

where every parenthesised record is one routed branch, walked from the driver: its
resistance R (ohm) and capacitance C (pF, from the LEF's per-layer area and edge
capacitance and via resistances), the cell pin it ends at (PIN/name for a block pin), then
the branches that continue from its end. Each branch becomes a SPEF resistor between its two
ends and its capacitance is split half to each end (a pi segment); the pin capacitances come
from the liberty, as in any SPEF flow.

qrouter names instances and nets as the routed DEF does; the timed netlist is qflow's
blif2Verilog output, whose net names are rewritten (`.` and `$` to `_`) but whose instance
names are the DEF's. So a net is named here by the netlist net on its driver's pin (or on a
load's pin), looked up in the netlist: no renaming rule is guessed.
"""
import re

# qrouter counts one edge's fringe capacitance per wire (delays.c: cap = pitch * width * area
# cap + pitch * edge cap); the LEF's EDGECAPACITANCE is per edge and a wire has two (LEF 5.8:
# C = CPERSQDIST * l * w + EDGECAPACITANCE * 2 * (l + w)). Per OSU018 routing layer the ratio
# (w Ca + 2 Ce) / (w Ca + Ce) is 1.875 (metal1) to 1.945 (metal4); the largest scales every
# wire's capacitance. Coupling between neighbouring wires is not modelled (no 3-D extraction).
EDGE_FACTOR = 1.945

_TOKEN = re.compile(r"\(|\)|,|[^\s(),]+")
_INST = re.compile(r"^\s*([A-Za-z_][\w$]*)\s+([^\s(]+)\s*\((.*?)\)\s*;", re.S | re.M)
_PINCONN = re.compile(r"\.(\w+)\(\s*([^()]*?)\s*\)")


def netlist_pins(verilog: str) -> dict:
    """(instance, pin) -> net of a flat structural netlist (qflow's rtlnopwr.v)."""
    out = {}
    body = re.sub(r"//.*", "", verilog)
    for m in _INST.finditer(body):
        if m.group(1) in ("module", "input", "output", "wire", "inout", "assign"):
            continue
        inst = m.group(2).lstrip("\\")
        for pin, net in _PINCONN.findall(m.group(3)):
            out[(inst, pin)] = net.strip().lstrip("\\").strip()
    return out


def port_directions(verilog: str) -> dict:
    """Port name -> 'I' / 'O' of a structural netlist."""
    out = {}
    for kind, names in re.findall(r"^\s*(input|output)\s+(?:\[[^\]]*\]\s*)?([^;]+);", verilog, re.M):
        for n in names.split(","):
            out[n.strip().lstrip("\\")] = "I" if kind == "input" else "O"
    return out


def parse_rc_line(line: str) -> dict:
    """One net of qrouter's .rc file -> {net, driver, tree}; tree is (r, c, node or None,
    [children])."""
    toks = _TOKEN.findall(line)
    if len(toks) < 5 or toks[1] != "1":
        raise ValueError(f"not a qrouter delay record: {line[:80]!r}")
    net, driver = toks[0], toks[2]
    pos = 4

    def record():
        nonlocal pos
        if toks[pos] != "(":
            raise ValueError(f"{net}: expected '(' at token {pos}")
        r, c = float(toks[pos + 1]), float(toks[pos + 2])
        pos += 3
        node = None
        if toks[pos] not in ("(", ")", ","):
            # qrouter writes ERROR for a branch that ends at no pin and goes on nowhere (a
            # dangling stub of the routing): its R and C stay, at an internal node.
            node = None if toks[pos] == "ERROR" else toks[pos]
            pos += 1
        kids = []
        while toks[pos] != ")":
            if toks[pos] == ",":
                pos += 1
                continue
            kids.append(record())
        pos += 1
        return (r, c, node, kids)

    return {"net": net, "driver": driver, "tree": record()}


def _esc(name: str) -> str:
    """A SPEF name: characters other than letters, digits and _ escaped, a bus index kept."""
    m = re.match(r"^(.*?)(\[\d+\])?$", name)
    base = re.sub(r"([^A-Za-z0-9_])", r"\\\1", m.group(1))
    return base + (m.group(2) or "")


def _pin_ref(node: str):
    """qrouter's INST/PIN or PIN/port -> ('I', inst, pin) or ('P', port, None)."""
    inst, pin = node.rsplit("/", 1)
    if inst == "PIN":
        return ("P", pin, None)
    return ("I", inst, pin)


def to_spef(rc_text: str, pins: dict, design: str, directions: dict, cap_factor: float = 1.0) -> tuple:
    """SPEF text for every net of the .rc file, and the names of the nets that could not be
    matched to the netlist (none expected). PINS: (instance, pin) -> netlist net;
    DIRECTIONS: block port -> 'I' or 'O' (its *CONN entry); CAP_FACTOR scales every wire
    capacitance (EDGE_FACTOR: both edges' fringe)."""
    out = ["*SPEF \"IEEE 1481-1998\"", f"*DESIGN \"{design}\"", "*DATE \"\"", "*VENDOR \"pst\"",
           "*PROGRAM \"scripts/pnr.py (qrouter write_delays)\"", "*VERSION \"1\"",
           "*DESIGN_FLOW \"PIN_CAP NONE\"", "*DIVIDER /", "*DELIMITER :", "*BUS_DELIMITER [ ]",
           "*T_UNIT 1 NS", "*C_UNIT 1 PF", "*R_UNIT 1 OHM", "*L_UNIT 1 HENRY", ""]
    unmatched = []
    for line in rc_text.splitlines():
        if not line.strip():
            continue
        rec = parse_rc_line(line)
        ends = [rec["driver"]]

        def collect(t):
            if t[2]:
                ends.append(t[2])
            for k in t[3]:
                collect(k)
        collect(rec["tree"])
        vnet = None
        for e in ends:
            kind, a, b = _pin_ref(e)
            if kind == "I" and (a, b) in pins:
                vnet = pins[(a, b)]
                break
        if vnet is None:
            port = next((_pin_ref(e)[1] for e in ends if _pin_ref(e)[0] == "P"), None)
            if port is None:
                unmatched.append(rec["net"])
                continue
            vnet = port
        def node_name(ref):
            kind, a, b = _pin_ref(ref)
            return _esc(vnet) if kind == "P" else f"{_esc(a)}:{b}"

        caps = {}
        res = []
        counter = [0]

        def walk(t, up):
            r, c, node, kids = t
            c *= cap_factor
            if node:
                down = node_name(node)
            else:
                counter[0] += 1
                down = f"{_esc(vnet)}:{counter[0]}"
            caps[up] = caps.get(up, 0.0) + c / 2
            caps[down] = caps.get(down, 0.0) + c / 2
            res.append((up, down, r))
            for k in kids:
                walk(k, down)

        root = node_name(rec["driver"])
        walk(rec["tree"], root)
        total = sum(caps.values())
        out.append(f"*D_NET {_esc(vnet)} {total:.6g}")
        out.append("*CONN")
        seen = set()
        for e in ends:
            if e in seen:
                continue
            seen.add(e)
            kind, a, b = _pin_ref(e)
            if kind == "P":
                # The block pin is the netlist net itself (blif2Verilog names a port's net
                # after the port).
                out.append(f"*P {_esc(vnet)} {directions.get(vnet.split('[')[0], 'I')}")
            else:
                out.append(f"*I {_esc(a)}:{b} {'O' if e == rec['driver'] else 'I'}")
        out.append("*CAP")
        for i, (n, c) in enumerate(caps.items(), 1):
            out.append(f"{i} {n} {c:.6g}")
        out.append("*RES")
        for i, (a, b, r) in enumerate(res, 1):
            out.append(f"{i} {a} {b} {max(r, 1e-3):.6g}")
        out.append("*END")
        out.append("")
    return "\n".join(out) + "\n", unmatched

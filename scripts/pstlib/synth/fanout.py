"""Fanout buffers across the module hierarchy of a Yosys structural netlist (write_verilog).

Yosys synthesizes each module on its own and ABC buffers the nets inside one module only: it
assumes every input port driven by a BUFX2 and every output port loaded by 0.02 pF, so a net
that leaves a module into the input ports of many sub-module instances (the octave stage's
stall enable into its 32 sub-modules and on to their pipeline registers) is driven by one
small gate however many picofarads it reaches. A back end builds the missing tree (OpenROAD's
repair_design); this step stands in for it in the hierarchical netlist that is timed and
counted: every net of a module that drives input ports of at least MIN_INSTANCES sub-module
instances gets one buffer cell (CELL) in front of each of those instances (one buffer per
instance and net, driving all its pins on that net), fed by a tree of the same cell: the
net's own driver gets one buffer (a BUFX4 input, 0.014 pF, within the 0.02 pF ABC sized it
for at a port: tools.ABC_CONSTR), and no buffer drives more than MAX_FANOUT others. Without
the tree the driver saw one BUFX4 per instance: balanced's octave stage had a NAND2X1 driving
0.525 pF (its liberty limit 0.500 pF) and 39 pins over the 1.2 ns max transition. Clock pins (CLOCK_PINS) are left alone
(the clock is ideal in the SDC; clock-tree synthesis is a back-end step of its own).
"""
import re

CELL = "BUFX4"            # OSU018 cell put in front of each instance pin
CELL_IN, CELL_OUT = "A", "Y"
MIN_INSTANCES = 2         # a net into the input ports of >= this many sub-module instances
MAX_FANOUT = 16           # inserted buffers one buffer drives (16 x 0.014 pF BUFX4 inputs, 0.22 pF)
CLOCK_PINS = ("clk_i",)
PREFIX = "_fob"           # inserted wires _fobN_ and cells _fobcN_

_ID = r"(?:\\\S+|[A-Za-z_][\w$]*)"
_MODULE = re.compile(rf"module\s+({_ID})\s*\(")
_DECL = re.compile(rf"\s*(input|output|inout|wire|reg)\s+(?:signed\s+)?(?:\[(-?\d+):(-?\d+)\]\s+)?({_ID})\s*;")
_INST = re.compile(rf"\s*({_ID})\s+(?:#\(.*\)\s+)?({_ID})\s*\($")
_PIN = re.compile(rf"\s*\.({_ID})\((.*)\)\s*,?\s*$")
_ASSIGN = re.compile(r"\s*assign\s+(.+?)\s*=\s*(.+?)\s*;\s*$")
_CONST = re.compile(r"(\d+)'s?[bBhHdDoO][0-9a-fA-FxXzZ_?]+$")
_SIG = re.compile(rf"({_ID})\s*(?:\[(-?\d+)(?::(-?\d+))?\])?$")


def _split_concat(expr: str) -> list:
    """Items of a connection expression, most significant first: `{ a, b[3:0], 2'h0 }` ->
    ['a', 'b[3:0]', "2'h0"]; a single item is a list of one."""
    e = expr.strip()
    if not e.startswith("{"):
        return [e]
    if not e.endswith("}"):
        raise ValueError(f"connection not understood: {expr}")
    inner = e[1:-1]
    if "{" in inner:
        raise ValueError(f"nested concatenation not understood: {expr}")
    items = []
    cur = ""
    # Escaped names end at whitespace and may hold commas: split on ', ' outside names.
    i = 0
    while i < len(inner):
        c = inner[i]
        if c == "\\":
            j = i
            while j < len(inner) and not inner[j].isspace():
                j += 1
            cur += inner[i:j]
            i = j
            continue
        if c == ",":
            items.append(cur.strip())
            cur = ""
        else:
            cur += c
        i += 1
    items.append(cur.strip())
    return [it for it in items if it]


class _Module:
    def __init__(self, name: str, start: int):
        self.name = name
        self.start = start
        self.end = start
        self.ranges = {}      # signal -> (msb, lsb) or None (scalar)
        self.inputs = set()
        self.insts = []       # (type, name, {pin: (line index, expr)})
        self.assigns = []     # (lhs, rhs)
        self.last_decl = start


def _parse(lines: list) -> dict:
    mods = {}
    cur = None
    inst = None
    for i, line in enumerate(lines):
        if cur is None:
            m = _MODULE.match(line)
            if m:
                cur = _Module(m.group(1), i)
                mods[m.group(1).lstrip("\\")] = cur
            continue
        s = line.strip()
        if s == "endmodule":
            cur.end = i
            cur = None
            inst = None
            continue
        if inst is not None:
            if s == ");":
                inst = None
                continue
            m = _PIN.match(line)
            if m:
                inst[2][m.group(1).lstrip("\\")] = (i, m.group(2))
            continue
        m = _DECL.match(line)
        if m:
            kind, msb, lsb, sig = m.groups()
            sig = sig.rstrip()
            cur.ranges[sig] = None if msb is None else (int(msb), int(lsb))
            if kind == "input":
                cur.inputs.add(sig.lstrip("\\"))
            cur.last_decl = i
            continue
        m = _ASSIGN.match(line)
        if m:
            cur.assigns.append((m.group(1), m.group(2)))
            continue
        m = _INST.match(line)
        if m and m.group(1) not in ("module", "assign"):
            inst = (m.group(1).lstrip("\\"), m.group(2), {})
            cur.insts.append(inst)
    return mods


def _bits(item: str, mod: _Module) -> list:
    """Bits of one concatenation item, most significant first: (signal, index) with index
    None for a scalar, or None for a constant bit."""
    item = item.strip()
    m = _CONST.match(item)
    if m:
        return [None] * int(m.group(1))
    m = _SIG.match(item)
    if not m:
        raise ValueError(f"{mod.name}: expression item not understood: {item}")
    sig = m.group(1).rstrip()
    if sig not in mod.ranges:
        raise ValueError(f"{mod.name}: undeclared signal {sig}")
    rng = mod.ranges[sig]
    if m.group(2) is not None:
        hi = int(m.group(2))
        lo = int(m.group(3)) if m.group(3) is not None else hi
    elif rng is None:
        return [(sig, None)]
    else:
        hi, lo = rng
    step = -1 if hi >= lo else 1
    return [(sig, k) for k in range(hi, lo + step, step)]


def _ref(bit: tuple) -> str:
    sig, k = bit
    if k is None:
        return sig if not sig.startswith("\\") else sig + " "
    return f"{sig}{' ' if sig.startswith(chr(92)) else ''}[{k}]"


def tree_feeds(root: str, n: int, buf, max_fanout: int = MAX_FANOUT) -> list:
    """Inputs for N buffers fed from ROOT, none driving more than MAX_FANOUT of them: ROOT
    itself while N <= MAX_FANOUT, else one level of buffers (BUF(src) -> new wire) per
    MAX_FANOUT, fed the same way."""
    if n <= max_fanout:
        return [root] * n
    groups = -(-n // max_fanout)
    out = []
    for g, src in enumerate(tree_feeds(root, groups, buf, max_fanout)):
        out += [buf(src)] * min(max_fanout, n - g * max_fanout)
    return out


def insert_buffers(netlist: str, min_instances: int = MIN_INSTANCES, cell: str = CELL) -> tuple:
    """Buffer every net of a module that drives input ports of >= min_instances sub-module
    instances: one `cell` per (instance, net) in front of that instance's pins. Returns the
    new netlist text and {module name (backslash stripped): buffers inserted in it}."""
    lines = netlist.split("\n")
    mods = _parse(lines)
    counts = {}
    inserts = {}      # line index -> text inserted after it
    serial = 0
    for mname, mod in mods.items():
        # Aliases (assign a = b) join bits into one net.
        parent = {}

        def find(b):
            while parent.get(b, b) != b:
                parent[b] = parent.get(parent[b], parent[b])
                b = parent[b]
            return b

        for lhs, rhs in mod.assigns:
            lb = [b for it in _split_concat(lhs) for b in _bits(it, mod)]
            rb = [b for it in _split_concat(rhs) for b in _bits(it, mod)]
            if len(lb) != len(rb):
                continue   # width-extending assign: not an alias Yosys writes; leave it
            for x, y in zip(lb, rb):
                if x is not None and y is not None:
                    rx, ry = find(x), find(y)
                    if rx != ry:
                        parent[rx] = ry
        # Net -> {instance index: [(pin, position of the bit in the pin's item list)]}.
        loads = {}
        parsed = {}
        for n, (typ, iname, pins) in enumerate(mod.insts):
            sub = mods.get(typ)
            if sub is None:
                continue   # a library cell
            for pin, (li, expr) in pins.items():
                if pin in CLOCK_PINS or pin not in sub.inputs:
                    continue
                items = _split_concat(expr)
                parsed[(n, pin)] = (li, items)
                for pos, it in enumerate(items):
                    for bit in _bits(it, mod):
                        if bit is not None:
                            loads.setdefault(find(bit), {}).setdefault(n, []).append((pin, pos, bit))
        # Buffer the nets with enough instances.
        subst = {}   # (n, pin, bit) -> buffered wire
        added = []

        def buf(src: str) -> str:
            nonlocal serial
            wire = f"{PREFIX}{serial}_"
            added.append(f"  wire {wire};")
            added.append(f"  {cell} {PREFIX}c{serial}_ (.{CELL_IN}({src}), .{CELL_OUT}({wire}));")
            serial += 1
            counts[mname] = counts.get(mname, 0) + 1
            return wire

        for net, insts in loads.items():
            if len(insts) < min_instances:
                continue
            feeds = tree_feeds(buf(_ref(next(iter(insts.values()))[0][2])), len(insts), buf)
            for (n, uses), src in zip(insts.items(), feeds):
                wire = buf(src)
                for pin, pos, bit in uses:
                    subst[(n, pin, bit)] = wire
        if not added:
            continue
        for (n, pin), (li, items) in parsed.items():
            out = []
            touched = False
            for it in items:
                bits = _bits(it, mod)
                if any(b is not None and (n, pin, b) in subst for b in bits):
                    touched = True
                    out += [subst.get((n, pin, b), _ref(b)) for b in bits]
                else:
                    out.append(it)
            if touched:
                text = out[0] if len(out) == 1 else "{ " + ", ".join(out) + " }"
                m = _PIN.match(lines[li])
                lines[li] = lines[li][:m.start(2)] + text + lines[li][m.end(2):]
        inserts[mod.last_decl] = "\n".join(added)
    for li in sorted(inserts, reverse=True):
        lines.insert(li + 1, inserts[li])
    return "\n".join(lines), counts

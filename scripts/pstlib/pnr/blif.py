"""A placed block's netlist written from qflow's BLIF (synthesis/NAME.blif, the file graywolf
placed), for OpenSTA and the SPEF: qflow's own blif2Verilog writes some port names of the
large blocks as bytes that are not text (u_octave, the noise unit of reduced).

Instances are named as qflow's blif2cel names the placed cells: CELL_N, N counting each cell
type from 1 in BLIF order (the routed DEF's component names). Nets are the BLIF's names with
every character other than a letter, a digit or _ made _ (as blif2Verilog -c does); a
collision is an error. Pins on Yosys's constant nets ($true, $false, $undef: a block's netlist
before qflow) are left unconnected: timing ignores them.
"""
import collections
import re


def _logical_lines(text: str):
    buf = ""
    for line in text.splitlines():
        line = line.split("#", 1)[0].rstrip()
        if line.endswith("\\"):
            buf += line[:-1] + " "
            continue
        buf += line
        if buf.strip():
            yield buf.strip()
        buf = ""


OUTPUT_PINS = ("Y", "Q", "YC", "YS")     # the OSU018 cells' output pins
CONSTANTS = (["$true"], ["$false"], ["$undef"])   # Yosys's constant drivers (.names with no input)


def read_model(blif_text: str, where: str, conn: bool = False, covers=(["1"],)) -> tuple:
    """The BLIF's first model: (name, inputs, outputs, gates [(cell, [[pin, net], ...])],
    conns [(a, b)]). Yosys's constant drivers and their cover lines (COVERS) are skipped;
    `.conn` is read when CONN; any other logic or construct is a ValueError naming WHERE."""
    model, ins, outs, gates, conns = None, [], [], [], []
    for line in _logical_lines(blif_text):
        parts = line.split()
        if parts[0] == ".model":
            if model is not None:
                break
            model = parts[1]
        elif parts[0] == ".inputs":
            ins += parts[1:]
        elif parts[0] == ".outputs":
            outs += parts[1:]
        elif parts[0] in (".gate", ".subckt"):
            gates.append((parts[1], [p.split("=", 1) for p in parts[2:]]))
        elif parts[0] == ".conn" and conn:
            conns.append((parts[1], parts[2]))
        elif parts[0] == ".names":
            if parts[1:] not in CONSTANTS:
                raise ValueError(f"BLIF logic not expected in {where}: {line[:80]}")
        elif parts[0] == ".end":
            break
        elif parts[0].startswith("."):
            raise ValueError(f"BLIF construct not expected in {where}: {parts[0]}")
        elif parts not in covers:
            raise ValueError(f"BLIF line not expected in {where}: {line[:60]}")
    if model is None:
        raise ValueError("BLIF has no .model")
    return model, ins, outs, gates, conns


def to_verilog(blif_text: str) -> str:
    """Structural Verilog of the BLIF's one model (.inputs, .outputs, .gate lines); pins on
    Yosys's constant drivers are left unconnected."""
    model, ins, outs, gates, _ = read_model(blif_text, "a mapped netlist")
    # A port in both lists is how Yosys's write_blif writes an inout (submod makes one of a net
    # driven inside a block and read outside it): an output where a cell of the block drives it,
    # else an input (a Verilog module cannot name one port twice; OpenSTA then fails).
    both = set(ins) & set(outs)
    if both:
        driven = {net for _, pins in gates for pin, net in pins if pin in OUTPUT_PINS}
        ins = [n for n in ins if n not in both or n not in driven]
        outs = [n for n in outs if n not in both or n in driven]
    names = {}

    def name(n):
        if n not in names:
            v = re.sub(r"[^A-Za-z0-9_]", "_", n)
            if v and v[0].isdigit():
                v = "n" + v
            names[n] = v
        return names[n]
    ports = [name(n) for n in ins + outs]
    const = {"$true", "$false", "$undef"}
    gates = [(cell, [(p, n) for p, n in pins if n not in const]) for cell, pins in gates]
    nets = sorted({name(net) for _, pins in gates for _, net in pins} - set(ports))
    out = [f"module {model} ({', '.join(ports)});"]
    out += [f"input {name(n)};" for n in ins] + [f"output {name(n)};" for n in outs]
    out += [f"wire {n};" for n in nets]
    count = collections.Counter()
    for cell, pins in gates:
        count[cell] += 1
        conns = ", ".join(f".{p}({name(n)})" for p, n in pins)
        out.append(f"{cell} {cell}_{count[cell]} ( {conns} );")
    if len(set(names.values())) != len(names):
        dup = collections.Counter(names.values()).most_common(1)[0][0]
        raise ValueError(f"BLIF names collide as Verilog identifiers ({dup})")
    return "\n".join(out + ["endmodule", ""])

"""The memories of a synthesized netlist as behavioural models, in place of their timing
stand-ins.

scripts/synth.py maps every memory ($mem_v2) to timing stand-ins (scripts/synth/mem_standin_map.v):
each read-port data bit is one PST_MEMRD cell whose A0..A15 pins carry the port's address and
whose Y is the bit; each write-port data, enable and address bit ends at a PST_MEMWR capture
cell (CK, D). The stand-ins have no behaviour. Here the stand-ins of each memory are removed
from their module and one instance of the memory's model pst_gl_mem_<k> takes their place: the
same nets, with the memory's shape and initial content from Yosys's dump of the $mem_v2 cell
(mem.txt of a kept synthesis). Read ports are asynchronous and write ports write on the rising
edge of their clock with a per-bit enable, as the stand-in map requires (it refuses clocked
reads).
"""
import re

from ..synth import memarea

_INST = re.compile(r"^\s+(PST_MEMRD|PST_MEMWR)\s+\\(\S+)\.(rd|wr)\[(\d+)\]\.(bit|dbit|abit)\[(\d+)\]\.(cell|wd|we|wa)\s+\($")
_PIN = re.compile(r"^\s+\.(\w+)\((.*)\)\s*,?\s*$")
_MODULE = re.compile(r"^module\s+(\\\S+|[A-Za-z_][\w$]*)\s*\(")


class NetlistError(ValueError):
    pass


# One module per memory (pst_gl_mem_<k>), each read port with its own address and data ports
# (one vector for all ports would make a chained lookup, one port's data in another's address,
# a combinational loop to Verilator's ordering). Asynchronous reads; writes on the rising edge
# of the port's clock with a per-bit enable, a later write port winning (Yosys's $mem_v2 without
# a priority mask); an address past the memory reads 0 and is not written.
def memory_module(k: int, mem: dict, stub: bool = False) -> str:
    """The behavioural model of one memory, or with STUB its black box (ports only) for Yosys."""
    a, w, n, rp, wp = mem["abits"], mem["width"], mem["size"], mem["read_ports"], mem["write_ports"]
    ports = []
    for p in range(rp):
        ports += [f"input [{a - 1}:0] rd{p}_addr_i", f"output [{w - 1}:0] rd{p}_data_o"]
    for p in range(wp):
        ports += [f"input wr{p}_clk_i", f"input [{w - 1}:0] wr{p}_en_i", f"input [{a - 1}:0] wr{p}_addr_i",
                  f"input [{w - 1}:0] wr{p}_data_i"]
    head = f"module pst_gl_mem_{k} (" + ", ".join(ports) + ");"
    if stub:
        return "(* blackbox *)\n" + head + "\nendmodule\n"
    words = memarea.init_words(mem)
    init = "".join(reversed([f"{v:0{w}b}" for v in words]))
    lines = [f"// {mem['module']}/{mem['memory']}: {n} x {w}, {rp} read, {wp} write ports", head,
             f"  localparam logic [{n * w - 1}:0] Init = {n * w}'h{int(init, 2):0{(n * w + 3) // 4}x};",
             f"  logic [{w - 1}:0] mem_q [{n}];",
             f"  initial for (int i = 0; i < {n}; i++) mem_q[i] = Init[i*{w} +: {w}];"]
    for p in range(rp):
        lines.append(f"  assign rd{p}_data_o = 32'(rd{p}_addr_i) < {n} ? mem_q[rd{p}_addr_i] : '0;")
    for p in range(wp):
        lines += [f"  always_ff @(posedge wr{p}_clk_i)",
                  f"    if (32'(wr{p}_addr_i) < {n})",
                  f"      for (int b = 0; b < {w}; b++) if (wr{p}_en_i[b]) mem_q[wr{p}_addr_i][b] <= wr{p}_data_i[b];"]
    lines.append("endmodule")
    return "\n".join(lines) + "\n"


def _write_params(text: str) -> dict:
    """(module, memory) -> the write-port and read-clock parameters of its $mem_v2 cell."""
    names = [line.strip() for line in text.splitlines() if "/" in line and not line.startswith(" ")
             and not line.startswith("attribute")]
    blocks = re.split(r"\n\s*cell \$mem_v2 ", "\n" + text)[1:]
    out = {}
    for name, block in zip(names, blocks):
        module, memory = name.split("/", 1)
        out[(module, memory)] = {k: _bits_param(block, k) for k in
                                 ("WR_CLK_ENABLE", "WR_CLK_POLARITY", "RD_CLK_ENABLE")}
    return out


def _bits_param(block: str, key: str) -> int:
    """A parameter of the dump as an integer: a decimal or Yosys's WIDTH'BITS constant (0'
    for an empty one; x and z read as 0)."""
    m = re.search(rf"parameter \\{key} (\S+)", block)
    if not m:
        raise NetlistError(f"$mem_v2 dump has no parameter {key}")
    v = m.group(1)
    c = re.fullmatch(r"(\d+)'s?b?([01xz]*)|(-?\d+)", v)
    if not c:
        raise NetlistError(f"parameter {key}: cannot read {v[:40]!r}")
    if c.group(3) is not None:
        return int(c.group(3))
    bits = c.group(2).replace("x", "0").replace("z", "0")
    return int(bits, 2) if bits else 0


def _net(text: str) -> str:
    t = text.strip()
    return t + " " if t.startswith("\\") else t   # an escaped name ends at white space


def _concat(nets: list) -> str:
    """Verilog concatenation, most significant first, of nets listed least significant first."""
    return "{" + ", ".join(reversed(nets)) + "}"


def _instance(k: int, module: str, mem: dict, params: dict, cells: dict) -> list:
    """The pst_gl_mem_<k> instance of one memory from its stand-in cells
    {(kind, port, bit[, leaf]): {pin: net}}."""
    name, a, w = mem["memory"], mem["abits"], mem["width"]
    if mem["offset"] != 0:
        raise NetlistError(f"{module}/{name}: memory offset {mem['offset']} not supported")
    if params["RD_CLK_ENABLE"] != 0:
        raise NetlistError(f"{module}/{name}: clocked read ports not supported")
    wp = mem["write_ports"]
    if wp and (params["WR_CLK_ENABLE"] != (1 << wp) - 1 or params["WR_CLK_POLARITY"] != (1 << wp) - 1):
        raise NetlistError(f"{module}/{name}: only rising-edge clocked write ports are supported")
    extra, conns = [], []
    for p in range(mem["read_ports"]):
        bits = [cells.get(("bit", p, b)) for b in range(w)]
        first = next((c for c in bits if c), None)
        if first is None:
            raise NetlistError(f"{module}/{name}: read port {p} has no stand-in cell")
        data = []
        for b, c in enumerate(bits):
            if c is None or "Y" not in c:
                nc = f"\\{name}.gl_nc_{p}_{b} "
                extra.append(f"  wire {nc};")
                data.append(nc)
            else:
                data.append(_net(c["Y"]))
        conns += [f".rd{p}_addr_i({_concat([_net(first[f'A{b}']) for b in range(a)])})",
                  f".rd{p}_data_o({_concat(data)})"]
    for p in range(wp):
        try:
            wd = [cells[("dbit", p, b, "wd")] for b in range(w)]
            we = [cells[("dbit", p, b, "we")] for b in range(w)]
            wa = [cells[("abit", p, b, "wa")] for b in range(a)]
        except KeyError as e:
            raise NetlistError(f"{module}/{name}: write port {p}: stand-in {e} missing") from None
        conns += [f".wr{p}_clk_i({_net(wd[0]['CK'])})",
                  f".wr{p}_en_i({_concat([_net(c['D']) for c in we])})",
                  f".wr{p}_addr_i({_concat([_net(c['D']) for c in wa])})",
                  f".wr{p}_data_i({_concat([_net(c['D']) for c in wd])})"]
    lines = extra + [f"  pst_gl_mem_{k} \\{name}.gl  ("] + [f"    {c}," for c in conns]
    lines[-1] = lines[-1].rstrip(",")
    lines.append("  );")
    return lines


def replace_standins(netlist: str, mem_dump: str) -> tuple:
    """The netlist with every memory's stand-ins replaced by an instance of its model
    pst_gl_mem_<k>, and the models ([(k, memory)], memory_module's arguments). NetlistError
    when a stand-in has no memory in the dump or a memory of the dump has no stand-in."""
    mems = {(m["module"], m["memory"]): m for m in memarea.parse_memories(mem_dump)}
    index = {key: k for k, key in enumerate(sorted(mems))}
    params = _write_params(mem_dump)
    out, module, cells, skipping, pins = [], None, {}, False, None
    done = set()
    for line in netlist.splitlines():
        m = _MODULE.match(line)
        if m:
            module, cells = m.group(1).lstrip("\\"), {}
        if skipping:
            pm = _PIN.match(line)
            if pm:
                pins[pm.group(1)] = pm.group(2)
            elif line.strip() == ");":
                skipping = False
            continue
        im = _INST.match(line)
        if im:
            _, mem, _, port, kind, bit, leaf = im.groups()
            if (module, mem) not in mems:
                raise NetlistError(f"module {module}: stand-in of {mem}: no such memory in the dump")
            pins = {}
            key = ("bit", int(port), int(bit)) if kind == "bit" else (kind, int(port), int(bit), leaf)
            cells.setdefault(mem, {})[key] = pins
            skipping = True
            continue
        if line.startswith("endmodule") and module is not None:
            for mem in sorted(cells):
                k = index[(module, mem)]
                out += _instance(k, module, mems[(module, mem)], params[(module, mem)], cells[mem])
                done.add((module, mem))
        out.append(line)
    missing = sorted(set(mems) - done)
    if missing:
        raise NetlistError(f"memory {missing[0][0]}/{missing[0][1]} has no stand-in in the netlist")
    return "\n".join(out) + "\n", [(index[key], mems[key]) for key in sorted(done, key=lambda x: index[x])]

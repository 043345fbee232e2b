"""A Yosys structural netlist (write_verilog) read once: every module's instances with their type
and pin connections, names unescaped as OpenSTA names them. The power and equivalence flows
read netlist_sta.v through it."""
import re

_MODULE = re.compile(r"^module\s+(\\\S+|[A-Za-z_][\w$]*)\s*\(")
_INSTANCE = re.compile(r"^\s+(\\\S+|[A-Za-z_][\w$]*)\s+(\\\S+|[A-Za-z_][\w$]*)\s*\($")
_PIN = re.compile(r"^\s+\.(\w+)\((.+)\)\s*,?\s*$")
_KEYWORDS = ("module", "assign", "wire", "input", "output", "reg")


def net_name(text: str) -> str:
    """A connection as OpenSTA names its net: the escape and the space before a bit dropped."""
    t = text.strip()
    return (t[1:] if t.startswith("\\") else t).replace(" [", "[")


def instances(netlist: str) -> dict:
    """{module: [(type, instance, {pin: net})]} in file order; a type that is a module of the
    netlist is a sub-module instance, any other a leaf cell."""
    mods, cur, pins = {}, None, None
    for line in netlist.splitlines():
        m = _MODULE.match(line)
        if m:
            cur = mods.setdefault(m.group(1).lstrip("\\"), [])
            continue
        if cur is None:
            continue
        m = _INSTANCE.match(line)
        if m and m.group(1) not in _KEYWORDS:
            pins = {}
            cur.append((m.group(1).lstrip("\\"), m.group(2).lstrip("\\"), pins))
            continue
        m = _PIN.match(line)
        if m and pins is not None:
            pins[m.group(1)] = net_name(m.group(2))
    return mods

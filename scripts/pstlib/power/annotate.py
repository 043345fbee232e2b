"""Simulated activity onto the synthesized netlist: the RTL's traced signal names -> the nets of
the hierarchical netlist OpenSTA reads, and the leaf cells driving them.

The synthesis keeps the module hierarchy and every port's name (internal wire names are
purged), so what can be carried over one to one is the activity of every module port bit: it
belongs to the leaf cell driving that net inside its module (a flop's Q, a buffer's Y, a gate's
output); the other cells of an instance take the mean of its traced bits. Generate blocks join an
instance name with dots in Yosys' netlist (g_unit[0].genblk1.g_lattice.u_noise) and are scopes
in the trace (g_unit[0]/g_lattice/u_noise; Verilator leaves the unnamed genblk out): both are
compared with the unnamed blocks dropped.
"""
import re

from .. import netlist as netlist_reader
from ..synth.sta import netlist_instances

_GENBLK = re.compile(r"^genblk\d+$")


def _normal(name: str) -> str:
    """An instance name with its unnamed generate blocks dropped (a.genblk1.b -> a.b)."""
    return ".".join(p for p in name.split(".") if not _GENBLK.match(p))


def instance_tree(netlist: str, top: str = "pst_top") -> dict:
    """{module: {normalized instance name: (instance name, module)}} of the sub-module instances
    (leaf cells left out) of a Yosys netlist."""
    mods = netlist_instances(netlist)
    tree = {}
    for m, insts in mods.items():
        tree[m] = {_normal(i): (i, t) for i, (t, _) in insts.items() if t in mods}
    return tree


def map_scope(scope: list, tree: dict, top: str = "pst_top"):
    """A trace scope path (components below the top) -> the netlist's instance path ("a/b.c"),
    or None when it is not an instance (a generate block's own signals, a function scope)."""
    module, path, i = top, [], 0
    while i < len(scope):
        children = tree.get(module, {})
        for k in range(1, len(scope) - i + 1):
            key = ".".join(p for p in scope[i:i + k] if not _GENBLK.match(p))
            if key in children:
                name, module = children[key]
                path.append(name)
                i += k
                break
        else:
            return None
    return "/".join(path)


def net_activities(act, tree: dict, top: str = "pst_top") -> list:
    """[(net name, activity, duty)] for every traced bit of a signal declared in a module
    instance (ports among them), named as OpenSTA names the netlist's nets (path/sig[bit])."""
    out = []
    cache = {}
    for path, rates in act.rates.items():
        *scope, name = path.split("/")
        key = tuple(scope)
        if key not in cache:
            cache[key] = map_scope(scope, tree, top)
        inst = cache[key]
        if inst is None:
            continue
        prefix = f"{inst}/{name}" if inst else name
        lsb = act.lsb.get(path, 0)
        if len(rates) == 1 and lsb == 0:
            out.append((prefix, *rates[0]))
        else:
            out += [(f"{prefix}[{lsb + i}]", a, d) for i, (a, d) in enumerate(rates)]
    return out


OUTPUT_PINS = ("Y", "Q", "YC", "YS")       # the OSU018 cells' outputs


def port_drivers(netlist: str) -> dict:
    """{module: {net: leaf cell}} of every net driven by a leaf cell's output (OUTPUT_PINS) in
    a Yosys structural netlist: which cell a port bit's activity belongs to."""
    mods = netlist_reader.instances(netlist)
    return {m: {net: inst for t, inst, pins in insts if t not in mods
                for pin, net in pins.items() if pin in OUTPUT_PINS}
            for m, insts in mods.items()}


def _module_of(inst: str, tree: dict, top: str, cache: dict):
    """The module of instance path INST ("" is the top), None when there is no such instance."""
    if inst not in cache:
        module = top
        for part in inst.split("/") if inst else []:
            module = next((t for n, t in tree.get(module, {}).values() if n == part), None)
            if module is None:
                break
        cache[inst] = module
    return cache[inst]


def has_driver(name: str, tree: dict, drivers: dict, top: str = "pst_top", cache=None) -> bool:
    """Whether a leaf cell of its own module drives net NAME (path/net)."""
    inst, _, net = name.rpartition("/")
    module = _module_of(inst, tree, top, {} if cache is None else cache)
    return bool(module and net in drivers.get(module, {}))


def driven_cells(nets: list, tree: dict, drivers: dict, top: str = "pst_top") -> dict:
    """{cell path: activity} for the leaf cell driving each net of NETS ((path/net, a, d) from
    net_activities) where one does; a cell driving several traced nets keeps the first."""
    cache = {}
    out = {}
    for name, a, _ in nets:
        inst, _, net = name.rpartition("/")
        module = _module_of(inst, tree, top, cache)
        cell = drivers.get(module, {}).get(net) if module else None
        if cell is not None:
            out.setdefault(f"{inst}/{cell}" if inst else cell, a)
    return out


def scope_activity(act, tree: dict, top: str = "pst_top") -> dict:
    """{netlist instance path: mean activity of every traced bit declared in that instance (its
    ports, registers and wires, clocks left out)}; the top is ""."""
    sums = {}
    cache = {}
    for path, rates in act.rates.items():
        *scope, name = path.split("/")
        if name.startswith("clk"):
            continue
        key = tuple(scope)
        if key not in cache:
            cache[key] = map_scope(scope, tree, top)
        inst = cache[key]
        if inst is None:
            # a generate block's own signals: counted in the nearest enclosing instance
            for k in range(len(scope) - 1, -1, -1):
                inst = map_scope(scope[:k], tree, top)
                if inst is not None:
                    break
            cache[key] = inst
        acc = sums.setdefault(inst, [0.0, 0])
        acc[0] += sum(a for a, _ in rates)
        acc[1] += len(rates)
    return {k: s / n for k, (s, n) in sums.items() if n}

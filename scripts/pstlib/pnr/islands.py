"""Metal islands under the minimum area left by qrouter's routed DEF, found by magic's DRC
and repaired in the DEF before magic reads it again.

What the routed blocks of reduced showed (magic's "MetalN area < 20" errors, 0.4 x 0.4 um
islands, each exactly one via pad): qrouter 1.4.71 sometimes ends a route with a short stub on
the layer above a cell pin and drops the via at the stub's far end, off the pin, instead of on
it (`NEW metal2 ( 107200 16600 ) ( 107120 * ) M2_M1`: pin B of an OAI21X1 under 107200, the
via at 107120). The via's lower pad is then an island (a DRC error) and, when no other wire
reaches that pin, the pin is open (the LVS mismatch of the same block). Elsewhere it leaves a
via on a route's detour whose pad on one side touches nothing (a dangling via).

The repair, per island (its layer and centre from magic, `drc listall why`):
- the via whose pad is the island, found in the DEF at the centre, is moved to the other end of
  its wire when that end lies on a pin of the same net on the island's layer (a cell pin from
  the LEF, placed and oriented as the DEF places the cell): the stub then lands on its pin;
- else, if nothing of the net on the island's layer touches the pad (it is an island: magic
  said so), the via connects nothing there and is removed;
- an island under two vias (a true stacked via) is left and counted.
The DRC and LVS run again on the repaired layout; they are the check.
"""
import collections
import re

Via = collections.namedtuple("Via", "name bottom top")
Element = collections.namedtuple("Element", "net start end layer points via")   # text span [start, end)


def via_layers(lef_text: str) -> dict:
    """LEF VIA name -> its metal layers (lower, upper)."""
    out = {}
    for m in re.finditer(r"^VIA (\S+).*?^END \1", lef_text, re.M | re.S):
        metals = sorted({int(n) for n in re.findall(r"LAYER metal(\d+)", m.group(0))})
        if len(metals) == 2:
            out[m.group(1)] = (f"metal{metals[0]}", f"metal{metals[1]}")
    return out


def macro_pins(lef_text: str) -> dict:
    """LEF MACRO -> (width, height, {pin: [(layer, x1, y1, x2, y2) in um]})."""
    out = {}
    for m in re.finditer(r"^MACRO (\S+)(.*?)^END \1", lef_text, re.M | re.S):
        size = re.search(r"SIZE ([0-9.]+) BY ([0-9.]+)", m.group(2))
        pins = {}
        for p in re.finditer(r"^\s*PIN (\S+)(.*?)^\s*END \1", m.group(2), re.M | re.S):
            rects, layer = [], None
            for line in p.group(2).splitlines():
                t = line.split()
                if t[:1] == ["LAYER"]:
                    layer = t[1]
                elif t[:1] == ["RECT"] and layer:
                    rects.append((layer, *(float(v) for v in t[1:5])))
            pins[p.group(1)] = rects
        out[m.group(1)] = (float(size.group(1)), float(size.group(2)), pins)
    return out


def parse_magic_islands(text: str) -> list:
    """(layer, x, y) centres in magic units of the minimum-area errors in the output of
    ISLANDS_TCL (`WHY: Metal2 area < 20 ...` then `BOX x1 y1 x2 y2` lines)."""
    out, layer = [], None
    for line in text.splitlines():
        m = re.match(r"WHY: Metal(\d+) area <", line)
        if m:
            layer = f"metal{m.group(1)}"
            continue
        if line.startswith("WHY:"):
            layer = None
            continue
        b = re.match(r"\s+BOX (-?\d+) (-?\d+) (-?\d+) (-?\d+)$", line)
        if b and layer:
            x1, y1, x2, y2 = (int(v) for v in b.groups())
            out.append((layer, (x1 + x2) / 2, (y1 + y2) / 2))
    return out


# Magic: the block's DRC errors with their reason and boxes, and its internal unit in microns.
ISLANDS_TCL = """lef read {lef}
load {cell}
drc on
select top cell
expand
drc check
drc catchup
foreach {{why boxes}} [drc listall why] {{ puts "WHY: $why"; foreach b $boxes {{ puts "  BOX $b" }} }}
puts "SCALE [cif scale out]"
quit
"""


def _elements(def_text: str):
    """Every routed element of the NETS section (net, text span, layer, points, via)."""
    start = def_text.index("\nNETS ")
    end = def_text.index("\nEND NETS", start)
    net = None
    for m in re.finditer(r"^- (\S+)|(?:\+ ROUTED|NEW) (metal\d+)((?: \( [-\d*]+ [-\d*]+ \))+)(?: (\w+))?",
                         def_text[start:end], re.M):
        if m.group(1):
            net = m.group(1)
            continue
        pts, x, y = [], None, None
        for a, b in re.findall(r"\( (\S+) (\S+) \)", m.group(3)):
            x = x if a == "*" else int(a)
            y = y if b == "*" else int(b)
            pts.append((x, y))
        yield Element(net, start + m.start(), start + m.end(), m.group(2), pts, m.group(4))


def _components(def_text: str) -> dict:
    return {m.group(1): (m.group(2), int(m.group(3)), int(m.group(4)), m.group(5))
            for m in re.finditer(r"^- (\S+) (\S+) \+ PLACED \( (-?\d+) (-?\d+) \) (\w+) ;", def_text, re.M)}


def _net_pins(def_text: str, net: str) -> list:
    m = re.search(r"^- " + re.escape(net) + r"\s*\n((?:\s*\( .*\)\s*\n)+)", def_text, re.M)
    return re.findall(r"\( (\S+) (\S+) \)", m.group(1)) if m else []


def _pin_rects(comp, macros, pin, units) -> list:
    macro, x0, y0, orient = comp
    w, h, pins = macros[macro]
    out = []
    for layer, x1, y1, x2, y2 in pins.get(pin, []):
        if orient in ("FS", "S"):
            y1, y2 = h - y2, h - y1
        if orient in ("FN", "S"):
            x1, x2 = w - x2, w - x1
        out.append((layer, x0 + x1 * units, y0 + y1 * units, x0 + x2 * units, y0 + y2 * units))
    return out


def repair(def_text: str, islands: list, lef_text: str) -> tuple:
    """DEF_TEXT with each island (layer, x, y in DEF units) repaired as the module says, and
    counts {moved, removed, left}."""
    units = float(re.search(r"^UNITS DISTANCE MICRONS (\d+)", def_text, re.M).group(1))
    vias = via_layers(lef_text)
    macros = macro_pins(lef_text)
    comps = _components(def_text)
    elements = list(_elements(def_text))
    edits, counts = [], collections.Counter()
    tol = 0.05 * units
    for layer, x, y in islands:
        at = [e for e in elements if e.via in vias and layer in vias[e.via]
              and abs(e.points[-1][0] - x) <= tol and abs(e.points[-1][1] - y) <= tol]
        if len(at) != 1:
            counts["left"] += 1
            continue
        e = at[0]
        moved = False
        if len(e.points) >= 2 and e.layer != layer:
            # The stub's other end on a pin of the net: the via goes there.
            px, py = e.points[0]
            for comp, pin in _net_pins(def_text, e.net):
                if comp == "PIN" or comp not in comps:
                    continue
                if any(l == layer and x1 <= px <= x2 and y1 <= py <= y2
                       for l, x1, y1, x2, y2 in _pin_rects(comps[comp], macros, pin, units)):
                    pts = " ".join(f"( {a} {b} )" for a, b in reversed(e.points))
                    kw = def_text[e.start:e.end].split(" metal", 1)[0]
                    edits.append((e.start, e.end, f"{kw} {e.layer} {pts} {e.via}"))
                    counts["moved"] += 1
                    moved = True
                    break
        if moved:
            continue
        text = def_text[e.start:e.end]
        if len(e.points) == 1 and text.startswith("NEW"):
            edits.append((e.start, e.end, ""))          # a lone via: the element goes
        elif len(e.points) >= 2:
            edits.append((e.start, e.end, text[: text.rindex(" " + e.via)]))
        else:
            counts["left"] += 1
            continue
        counts["removed"] += 1
    for s, t, new in sorted(edits, reverse=True):
        def_text = def_text[:s] + new + def_text[t:]
    # An element removed whole leaves an empty line.
    def_text = re.sub(r"\n[ \t]*\n(?=\s*(?:NEW|;))", "\n", def_text)
    return def_text, {k: counts.get(k, 0) for k in ("moved", "removed", "left")}

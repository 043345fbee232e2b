"""Block pins placed from the cells they connect (graywolf's pin hints, qflow's NAME.cel2, and
the placed DEF's pins moved by their cells).

graywolf places a block's pins along the die edge with no regard to where the cells on their
nets end up, 1.2 µm apart: u_regs of reduced (1,924 pins) got them ringed 250 µm outside its
cells (median pin-to-cell 611 µm) and never routed; u_octave_g_serial (2,265 pins) 257 µm.

A placement whose pins are `far` (or any retry after qrouter left nets unrouted) is placed
again from the cells of the last placement:
- each pin goes to the die side nearest the centroid of the cells on its net, at the centroid's
  position along that side (`hints`); a side holding more pins than fit (two routing tracks
  apart, or one when the edge is too short) gives the pins that lose least by moving to their
  next side;
- along a side, pins keep their order and are spread so that none shares a slot (`spread`),
  then grouped into spans of about SPAN_UM: one `padgroup` per span with `restrict side` and
  `sidespace lo hi`, pins permutable inside it (`cel2`). graywolf follows these only roughly:
  its fractions are of its own core at pad placement (configpads.c), not of the final die;
- after graywolf has placed again, `snap` moves every pin to the routing track at the edge
  nearest its cells as placed.
"""
import collections
import math
import re

# One routing track per side (qrouter's OSU018 .info): B and T pins on vertical metal2 (0.8 µm
# pitch), L and R pins on horizontal metal3 (1.0 µm). Pins go two tracks apart (as qflow's
# arrangepins spaces them) when the sides have room for that, else one.
TRACK_UM = {"L": 1.0, "R": 1.0, "B": 0.8, "T": 0.8}
SPAN_UM = 40.0        # one pad group's share of a side

Die = collections.namedtuple("Die", "x0 y0 x1 y1")
SIDES = "LRBT"


def def_units(def_text: str) -> float:
    """DEF database units per µm."""
    return float(re.search(r"^UNITS DISTANCE MICRONS (\d+)", def_text, re.M).group(1))


def parse_def(def_text: str) -> tuple:
    """(die, {component: (x, y)}, {pin: [component, ...]}) from a placed DEF (DEF units)."""
    die = Die(*(int(v) for v in re.search(r"^DIEAREA \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)",
                                            def_text, re.M).groups()))
    comp = def_text[def_text.index("\nCOMPONENTS"):def_text.index("\nEND COMPONENTS")]
    pos = {m.group(1): (int(m.group(2)), int(m.group(3)))
           for m in re.finditer(r"^- (\S+) \S+ \+ (?:PLACED|FIXED) \( (-?\d+) (-?\d+) \)", comp, re.M)}
    nets = def_text[def_text.index("\nNETS"):def_text.index("\nEND NETS")]
    cells = {}
    for stmt in nets.split("\n- ")[1:]:
        conns = re.findall(r"\(\s*(\S+)\s+(\S+)\s*\)", stmt.split("+", 1)[0])
        pins = [b for a, b in conns if a == "PIN"]
        comps = [a for a, _ in conns if a != "PIN" and a in pos]
        for p in pins:
            cells[p] = comps
    return die, pos, cells


def _side_distances(die: Die, x: float, y: float) -> dict:
    return {"L": x - die.x0, "R": die.x1 - x, "B": y - die.y0, "T": die.y1 - y}


def _along(die: Die, side: str, x: float, y: float) -> float:
    """Position along SIDE as a fraction (L, R from the bottom; B, T from the left)."""
    if side in "LR":
        return min(1.0, max(0.0, (y - die.y0) / (die.y1 - die.y0)))
    return min(1.0, max(0.0, (x - die.x0) / (die.x1 - die.x0)))


def side_capacity(die: Die, units: float, pins: int = 0) -> dict:
    """Side -> how many pins it holds (corners kept clear): at two tracks apart when all PINS
    fit so, else one."""
    w, h = (die.x1 - die.x0) / units, (die.y1 - die.y0) / units
    # Two tracks clear of each corner (snap): a side that `hints` fills to the brim must still
    # hold its pins two tracks apart there (top of reduced got a side one track apart: metal3
    # spacing errors between the routed pins).
    for tracks in (2, 1):
        cap = {s: max(0, int((h if s in "LR" else w) / TRACK_UM[s]) - 5) // tracks for s in SIDES}
        if sum(cap.values()) >= pins:
            break
    return cap


def hints(die: Die, pos: dict, cells: dict, units: float) -> dict:
    """Pin -> (side, fraction along it). A pin with no placed cell on its net keeps no hint."""
    want = {}
    for pin, comps in cells.items():
        if not comps:
            continue
        x = sum(pos[c][0] for c in comps) / len(comps)
        y = sum(pos[c][1] for c in comps) / len(comps)
        want[pin] = (x, y)
    cap = side_capacity(die, units, len(want))
    ranked = {p: sorted(SIDES, key=lambda s, d=_side_distances(die, *xy): (d[s], s)) for p, xy in want.items()}
    side = {p: r[0] for p, r in ranked.items()}
    # Overfull sides give the pins that lose least by moving to their next side with room.
    for _ in range(len(SIDES)):
        count = collections.Counter(side.values())
        over = [s for s in SIDES if count[s] > cap[s]]
        if not over:
            break
        for s in over:
            movers = []
            for p in (p for p in side if side[p] == s):
                d = _side_distances(die, *want[p])
                nxt = next((t for t in ranked[p] if t != s and count[t] < cap[t]), None)
                if nxt:
                    movers.append((d[nxt] - d[s], p, nxt))
            for _, p, nxt in sorted(movers)[:count[s] - cap[s]]:
                if count[nxt] < cap[nxt]:
                    side[p] = nxt
                    count[nxt] += 1
                    count[s] -= 1
    return {p: (side[p], _along(die, side[p], *want[p])) for p in want}


def spread(fractions: list, slots: int) -> list:
    """Slots 0..SLOTS-1 for pins wanted at FRACTIONS (sorted): each at its wanted slot or the
    nearest later free one, pushed back from the end when they run out (order kept)."""
    n = len(fractions)
    if n > slots:
        raise ValueError(f"{n} pins do not fit in {slots} slots")
    out, last = [], -1
    for f in fractions:
        last = max(min(slots - 1, int(f * slots)), last + 1)
        out.append(last)
    for i in range(n - 1, -1, -1):
        out[i] = min(out[i], slots - (n - i))
    return out


def cel2(die: Die, hint: dict, units: float) -> str:
    """The pad groups (qflow's .cel2) for pin -> (side, fraction)."""
    cap = side_capacity(die, units, len(hint))
    lines = []
    for s in SIDES:
        pins = sorted((f, p) for p, (side, f) in hint.items() if side == s)
        if not pins:
            continue
        length = (die.y1 - die.y0 if s in "LR" else die.x1 - die.x0) / units
        spans = max(1, int(round(length / SPAN_UM)))
        slots = spread([f for f, _ in pins], cap[s])
        groups = collections.defaultdict(list)
        for (_, p), k in zip(pins, slots):
            groups[min(spans - 1, k * spans // cap[s])].append(p)
        for g in sorted(groups):
            lines.append(f"padgroup pg_{s}{g} permute")
            lines += [f"twpin_{p} nonfixed" for p in groups[g]]
            lines += [f"restrict side {s}", f"sidespace {g / spans:.4f} {(g + 1) / spans:.4f}", ""]
    return "\n".join(lines)


def from_def(def_text: str) -> tuple:
    """(.cel2 text, summary) for the placed DEF_TEXT."""
    units = def_units(def_text)
    die, pos, cells = parse_def(def_text)
    h = hints(die, pos, cells, units)
    count = collections.Counter(s for s, _ in h.values())
    return cel2(die, h, units), {"pins": len(cells), "hinted": len(h), **{f"side_{s}": count[s] for s in SIDES}}


def pin_distance_um(def_text: str) -> float:
    """Median distance (µm, Manhattan) from each placed block pin to the nearest cell on its net:
    the figure that says whether the pins sit by their cells."""
    units = def_units(def_text)
    _, pos, cells = parse_def(def_text)
    pins = def_text[def_text.index("\nPINS"):def_text.index("\nEND PINS")]
    at = {m.group(1): (int(m.group(2)), int(m.group(3)))
          for m in re.finditer(r"^- (\S+) \+ NET \S+.*?\+ (?:PLACED|FIXED) \( (-?\d+) (-?\d+) \)", pins, re.M | re.S)}
    d = sorted(min(abs(pos[c][0] - at[p][0]) + abs(pos[c][1] - at[p][1]) for c in cells[p]) / units
               for p in cells if cells[p] and p in at)
    return d[len(d) // 2] if d else math.nan


# A PINS entry as qflow's place2def writes it (name, net, other clauses, layer, rectangle, x, y).
PIN_ENTRY = re.compile(r"^- (\S+) \+ NET (\S+)\s+((?:\+ (?:DIRECTION|USE) \S+\s+)*)\+ LAYER (\S+) "
                       r"(\( -?\d+ -?\d+ \) \( -?\d+ -?\d+ \))\s+\+ PLACED \( (-?\d+) (-?\d+) \) \S+ ;", re.M)


def _tracks(def_text: str, axis: str, layer: str) -> tuple:
    m = re.search(rf"^TRACKS {axis} (-?[\d.]+) DO (\d+) STEP (\d+) LAYER {layer} ;", def_text, re.M)
    if not m:
        raise ValueError(f"placed DEF has no {layer} TRACKS {axis}")
    return float(m.group(1)), int(m.group(2)), int(m.group(3))


def snap(def_text: str) -> tuple:
    """The placed DEF with every block pin moved to a routing track of its own at the die edge
    (B and T pins on metal2, L and R on metal3, at the edge offset qflow used on that side; pins
    in order along a side, two tracks apart when it has room, else one): a pin whose net has
    placed cells to the side nearest their centroid, on the track nearest it; any other pin as
    if its own cell stood where graywolf put it. Returns it with the median pin-to-cell distance before
    and after (µm). graywolf follows the hints only roughly (its side fractions are of its own
    core, not the die); this puts each pin where its cells ended up."""
    units = def_units(def_text)
    die, pos, cells = parse_def(def_text)
    start = def_text.index("\nPINS")
    end = def_text.index("\nEND PINS")
    entries = list(PIN_ENTRY.finditer(def_text, start, end))
    # A pin with no placed cell on its net (an unused input bit, a pin wired straight to another
    # pin) stands in for its own cell where graywolf put it: it keeps its side and place unless
    # the side is full, and takes a track of its own like the others (left where graywolf put it,
    # it shared a track with a moved pin and qrouter found no tap for either: u_regs 9,
    # u_octave_g_serial 17, top 28 nets of reduced). The power pins (vdd, gnd: special nets,
    # not in NETS) stay where qflow put them.
    pos, cells = dict(pos), dict(cells)
    for e in entries:
        if e.group(1) in cells and not cells[e.group(1)]:
            pos[f"pin {e.group(1)}"] = (int(e.group(6)), int(e.group(7)))
            cells[e.group(1)] = [f"pin {e.group(1)}"]
    want = hints(die, pos, cells, units)
    # The edge offset qflow used on each side (B and L one track in, T and R on the edge).
    edge = collections.defaultdict(collections.Counter)
    for e in entries:
        x, y = int(e.group(6)), int(e.group(7))
        d = _side_distances(die, x, y)
        s = min(d, key=d.get)
        edge[s][x if s in "LR" else y] += 1
    at = {s: (edge[s].most_common(1)[0][0] if edge[s] else {"L": die.x0, "R": die.x1, "B": die.y0, "T": die.y1}[s])
          for s in SIDES}
    tx = _tracks(def_text, "X", "metal2")
    ty = _tracks(def_text, "Y", "metal3")
    per_side = collections.defaultdict(list)
    for p, (s, f) in want.items():
        per_side[s].append((f, p))
    place, apart = {}, {}
    for s, items in per_side.items():
        first, count, step = ty if s in "LR" else tx
        lo, hi = (die.y0, die.y1) if s in "LR" else (die.x0, die.x1)
        # Usable tracks: inside the die, two tracks clear of each corner.
        grid = [first + k * step for k in range(count) if lo + 2 * step <= first + k * step <= hi - 2 * step]
        apart[s] = 2 if len(grid) >= 2 * len(items) else 1
        slots = grid[::apart[s]]
        items.sort()
        idx = spread([f for f, _ in items], len(slots))
        for (_, p), k in zip(items, idx):
            c = int(round(slots[k]))
            place[p] = (s, (at[s], c) if s in "LR" else (c, at[s]))
    if set(place) - {e.group(1) for e in entries}:
        raise ValueError(f"placed DEF: pins not in the PINS section's form: {sorted(set(place) - {e.group(1) for e in entries})[:3]}")
    shared = collections.Counter(place.values())
    if any(n > 1 for n in shared.values()):
        raise ValueError(f"placed DEF: pins snapped onto one track: {[k for k, n in shared.items() if n > 1][:3]}")
    out, last = [], 0
    for e in entries:
        name = e.group(1)
        if name not in place:
            continue
        s, (x, y) = place[name]
        layer = "metal3" if s in "LR" else "metal2"
        out += [def_text[last:e.start()],
                f"- {name} + NET {' '.join([e.group(2), *e.group(3).split()])}\n  + LAYER {layer} {e.group(5)}\n  + PLACED ( {x} {y} ) N ;"]
        last = e.end()
    out.append(def_text[last:])
    new = "".join(out)
    return new, {"moved": len(place), "median_pin_to_cell_um_before_snap": round(pin_distance_um(def_text), 1),
                 "median_pin_to_cell_um": round(pin_distance_um(new), 1), "tracks_apart": apart}


RING_RATIO = 1.5   # die area over the placed cells' extent above which the pins are ringed out


def ring_ratio(def_text: str) -> float:
    """The die's area over the extent of its placed cells (fillers left out): about 1 when the
    pins sit by the cells; u_regs of reduced, 1,924 pins ringed 250 µm out by graywolf: 3.1."""
    die, pos, _ = parse_def(def_text)
    comp = def_text[def_text.index("\nCOMPONENTS"):def_text.index("\nEND COMPONENTS")]
    kinds = dict(re.findall(r"^- (\S+) (\S+)", comp, re.M))
    xy = [v for c, v in pos.items() if not kinds.get(c, "").startswith("FILL")]
    if not xy:
        return 1.0
    w = max(x for x, _ in xy) - min(x for x, _ in xy)
    h = max(y for _, y in xy) - min(y for _, y in xy)
    return (die.x1 - die.x0) * (die.y1 - die.y0) / max(1, w * h)


FAR = 0.05   # median pin-to-cell distance over the die's half perimeter above which pins are far


def far(def_text: str) -> bool:
    """Whether graywolf placed the pins far from their cells: pins ringed outside the cells
    (ring_ratio over RING_RATIO) or a median pin-to-cell distance over FAR of the die's
    half perimeter. Measured on reduced's first placements: u_octave 23 µm of 2,030 (1.1 %),
    u_octave_g_serial 257 of 2,454 (10 %, 2,265 pins), u_regs 611 of 2,461 (25 %, ring 3.1)."""
    die, _, _ = parse_def(def_text)
    units = def_units(def_text)
    half = ((die.x1 - die.x0) + (die.y1 - die.y0)) / units
    d = pin_distance_um(def_text)
    return ring_ratio(def_text) > RING_RATIO or (not math.isnan(d) and d > FAR * half)

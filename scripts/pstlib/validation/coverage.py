"""Verilator coverage data (.dat, "SystemC::Coverage-3") read and summarised for
scripts/coverage.sh: line coverage of rtl/ per file, the functional (`cover property`) points
hit and missed per instance, toggle coverage per file.

A .dat line is   C '<\\1>key<\\2>value<\\1>key<\\2>value...' COUNT
with keys f (file), l (line), page (v_line/MODULE, v_branch/..., v_toggle/..., v_user/...),
o (the point's name), h (instance hierarchy). Line and branch points are per instance; a source
line counts as covered when any instance of any profile reached it."""
import collections
import re
import sys

_POINT = re.compile(r"^C '(.*)' (\d+)$")


def read_points(path):
    """[(dict of keys, count)] of one .dat file."""
    out = []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = _POINT.match(line.rstrip("\n"))
            if not m:
                continue
            keys = {}
            for part in m.group(1).split("\x01"):
                if "\x02" in part:
                    k, v = part.split("\x02", 1)
                    keys[k] = v
            out.append((keys, int(m.group(2))))
    return out


def kind(keys):
    return keys.get("page", "").split("/")[0]   # v_line, v_branch, v_toggle, v_user


def line_coverage(points, only=None):
    """{file: (covered lines, lines)}: lines with a line or branch point, hit in any instance."""
    lines = collections.defaultdict(dict)
    for keys, n in points:
        if kind(keys) not in ("v_line", "v_branch"):
            continue
        f = keys.get("f", "?")
        if only and not only(f):
            continue
        # A block point spans lines S=a-b; count every line of the block.
        span = keys.get("S", keys.get("l", "0"))
        for part in span.split(","):
            a, _, b = part.partition("-")
            for ln in range(int(a), int(b or a) + 1):
                lines[f][ln] = lines[f].get(ln, 0) + n
    return {f: (sum(1 for c in d.values() if c > 0), len(d), sorted(ln for ln, c in d.items() if c == 0))
            for f, d in lines.items()}


def user_points(points):
    """[(instance.point, file:line, count)] of every `cover property` point, by name."""
    out = collections.defaultdict(int)
    where = {}
    for keys, n in points:
        if kind(keys) != "v_user":
            continue
        h = keys.get("h", "?")
        out[h] += n
        where[h] = f"{keys.get('f', '?')}:{keys.get('l', '?')}"
    return sorted((h, where[h], n) for h, n in out.items())


def toggle_coverage(points, only=None):
    """{file: (toggled, points)}."""
    per = collections.defaultdict(lambda: [0, 0])
    seen = {}
    for keys, n in points:
        if kind(keys) != "v_toggle":
            continue
        f = keys.get("f", "?")
        if only and not only(f):
            continue
        k = (f, keys.get("l"), keys.get("o"), keys.get("h"))
        seen[k] = seen.get(k, 0) + n
    for (f, *_), n in seen.items():
        per[f][0] += n > 0
        per[f][1] += 1
    return {f: tuple(v) for f, v in per.items()}


def report(dat, rtl_prefix="rtl/"):
    pts = read_points(dat)
    # The design's lines and bits: rtl/ without the checkers of rtl/sva/ (their points are the
    # cover points below).
    only = lambda f: rtl_prefix in f and rtl_prefix + "sva/" not in f
    L = ["# RTL coverage (Verilator 5.006, merged over every run and profile)", ""]
    lc = line_coverage(pts, only)
    th = tn = 0
    L += ["## Line coverage of rtl/ (line and branch points; a line counts when any instance hit it)", "",
          "| file | lines hit | lines | % | lines never hit |", "|---|---:|---:|---:|---|"]
    for f in sorted(lc):
        h, n, miss = lc[f]
        th += h
        tn += n
        L.append(f"| {f.split('/')[-1]} | {h} | {n} | {100.0 * h / max(n, 1):.1f} | {', '.join(map(str, miss[:30]))} |")
    L += [f"| **total** | {th} | {tn} | {100.0 * th / max(tn, 1):.1f} | |", ""]
    up = user_points(pts)
    missed = [p for p in up if p[2] == 0]
    L += [f"## Functional cover points: {len(up) - len(missed)} of {len(up)} hit", ""]
    if missed:
        L += ["Never hit:", ""] + [f"- `{h}` ({w})" for h, w, _ in missed] + [""]
    L += ["| point | where | count |", "|---|---|---:|"] + [f"| `{h}` | {w} | {n} |" for h, w, n in up] + [""]
    tc = toggle_coverage(pts, only)
    t1 = sum(v[0] for v in tc.values())
    t2 = sum(v[1] for v in tc.values())
    L += [f"## Toggle coverage of rtl/: {t1} of {t2} signal bits toggled ({100.0 * t1 / max(t2, 1):.1f} %)", "",
          "| file | toggled | bits | % |", "|---|---:|---:|---:|"]
    L += [f"| {f.split('/')[-1]} | {a} | {b} | {100.0 * a / max(b, 1):.1f} |" for f, (a, b) in sorted(tc.items())]
    return "\n".join(L) + "\n", (th, tn), (len(up) - len(missed), len(up))


if __name__ == "__main__":
    text, (h, n), (uh, un) = report(sys.argv[1])
    if len(sys.argv) > 2:
        open(sys.argv[2], "w").write(text)
    print(f"rtl/ lines {h} / {n} ({100.0 * h / max(n, 1):.1f} %); cover points {uh} / {un} hit")

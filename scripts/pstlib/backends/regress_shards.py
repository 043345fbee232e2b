"""`pst regress` in shards: the plan (scenes x profiles; random fragments in chunks of --from),
one shard's run and its completeness, and the merge of the shards' JSON and JUnit into one
result that names the first failure with its replay command.

A shard is one `pst regress` command with its own outputs in OUT/shards/: NAME.json (-o),
NAME.xml (--junit), NAME.log (stdout and stderr) and, written last, NAME.done.json (its
arguments, exit status and time). A shard is complete when its done record holds the same
arguments as the plan and exit status 0 (passed) or 1 (a mismatch or an RTL assertion: a
result like any other), and its JSON and JUnit parse. A shard that was killed, crashed or
refused its input (exit 2) leaves no done record: the launcher runs it again, alone, and a
later run of the same command skips every complete shard.

Random chunks: the stream is cut into segments (testbench/verify/random: a fresh RTL model and random
gaps and stalls per segment), and `--from K` starts at the segment that holds fragment K. The
chunks are cut at segment starts (`pst regress --list --random` prints them), so the shards
together simulate exactly the fragments one process would, each once, with the same inputs."""
import dataclasses
import json
import math
import os
import pathlib
import re
import time
import xml.etree.ElementTree as ET

from .. import atomic
from ..procs import run
from ..pstjson import regress_runs

SHARDS = "shards"


@dataclasses.dataclass(frozen=True)
class Shard:
    name: str                 # file-safe, unique in the plan
    args: tuple               # `pst regress` arguments (its outputs -o and --junit added by run_shard)
    profile: str
    scene: str = ""           # scene file (scene shards)
    first: int = 0            # random shards: --from and --random
    count: int = 0

    def to_json(self) -> dict:
        return dataclasses.asdict(self) | {"args": list(self.args)}

    @staticmethod
    def from_json(d: dict) -> "Shard":
        return Shard(**(d | {"args": tuple(d["args"])}))


def chunks(first: int, count: int, starts: list, chunk: int) -> list:
    """(from, n) pairs covering [first, first + count), cut only at segment STARTS (the first
    fragment of every segment from the one holding FIRST on), each piece of at least CHUNK
    fragments but the last. The first piece starts at FIRST (pst runs its segment whole)."""
    if count < 1 or chunk < 1:
        raise ValueError("count and chunk must be >= 1")
    if not starts or starts[0] > first or any(b <= a for a, b in zip(starts, starts[1:])):
        raise ValueError(f"segment starts must begin at or before {first} and increase")
    end = first + count
    cuts = [first]
    for s in starts[1:]:
        if s >= end:
            break
        if s > first and s - cuts[-1] >= chunk:
            cuts.append(s)
    return [(a, b - a) for a, b in zip(cuts, cuts[1:] + [end])]


def default_chunk(count: int, workers: int, largest: int = 1_000_000) -> int:
    """At most LARGEST fragments per shard, and at least two shards per worker when that is smaller."""
    return max(1, min(largest, math.ceil(count / (2 * max(1, workers)))))


def plan_random(profiles: list, starts: list, count: int, seed: int, first: int, chunk: int, batch: int = 0,
                extra=()) -> list:
    """One shard per profile and chunk (chunks()); EXTRA: more `pst regress` arguments for every shard,
    but --inject-assert=I only for the shards whose fragments hold I (pst refuses a self-test
    index outside its run: it could not fire)."""
    b = ("--batch", str(batch)) if batch else ()
    return [Shard(f"random-{p}-{k:010d}", ("--random", str(n), "--seed", str(seed), "--from", str(k), *b,
                                           "--profile", p, "-q", *_for_chunk(extra, k, n)), p, first=k, count=n)
            for p in profiles for k, n in chunks(first, count, starts, chunk)]


def _for_chunk(extra, first: int, count: int) -> list:
    """EXTRA without an --inject-assert=I whose I is outside fragments [first, first + count)."""
    out = []
    for x in extra:
        m = re.fullmatch(r"--inject-assert=(\d+)", str(x))
        if m and not first <= int(m.group(1)) < first + count:
            continue
        out.append(x)
    return out


def plan_scenes(runs: list, size: int, extra=()) -> list:
    """One shard per (scene file, profile) of RUNS (what `pst regress --list` printed)."""
    out = []
    stems = {}
    for scene, profile in runs:
        stem = re.sub(r"[^A-Za-z0-9_.-]", "_", pathlib.Path(scene).stem)
        i = stems.setdefault(scene, len(stems))
        out.append(Shard(f"scene{i:03d}-{stem}-{profile}", (scene, "--size", str(size), "--profile", profile, *extra),
                         profile, scene=scene))
    return out


def parse_list(text: str, random: bool):
    """`pst regress --list` output: (profiles, segment starts) with --random, else (scene, profile) pairs."""
    lines = [ln for ln in text.splitlines() if ln.strip()]
    if random:
        profiles, starts = [], []
        for ln in lines:
            kind, _, v = ln.strip().partition(" ")
            if kind == "profile" and v:
                profiles.append(v)
            elif kind == "segment" and v.isdigit():
                starts.append(int(v))
            else:
                raise ValueError(f"pst regress --list: line not understood: {ln!r}")
        return profiles, starts
    pairs = []
    for ln in lines:
        scene, sep, profile = ln.rpartition("\t")
        if not sep:
            raise ValueError(f"pst regress --list: line not understood: {ln!r}")
        pairs.append((scene, profile))
    return pairs


# ----------------------------------------------------------------------------------------------
# One shard

def paths(out: pathlib.Path, name: str) -> dict:
    d = pathlib.Path(out) / SHARDS
    return {k: d / f"{name}{ext}" for k, ext in
            (("json", ".json"), ("xml", ".xml"), ("log", ".log"), ("done", ".done.json"), ("pid", ".pid"))}


def _parses(p: dict) -> bool:
    try:
        runs = regress_runs(json.loads(p["json"].read_text()))
        ET.parse(p["xml"])
    except (OSError, ValueError, ET.ParseError):
        return False
    return isinstance(runs, list)


def complete(out: pathlib.Path, shard: Shard):
    """The shard's done record when its result is complete and made with the plan's arguments, else None."""
    p = paths(out, shard.name)
    try:
        rec = json.loads(p["done"].read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(rec, dict) or rec.get("args") != list(shard.args) or rec.get("rc") not in (0, 1):
        return None
    return rec if _parses(p) else None


def run_shard(out: pathlib.Path, shard: Shard, pst: str, timeout=None) -> dict:
    """Runs the shard's `pst regress` (its pid in NAME.pid while it runs) and, when it finished with
    a result (exit 0 or 1, JSON and JUnit readable), writes the done record. Returns the record,
    with "complete" false when there is none."""
    p = paths(out, shard.name)
    p["json"].parent.mkdir(parents=True, exist_ok=True)
    for k in ("done", "json", "xml"):
        p[k].unlink(missing_ok=True)
    t0 = time.time()
    cmd = [pst, "regress", *shard.args, "-o", p["json"], "--junit", p["xml"]]
    rc, so, se = run(cmd, timeout=timeout, on_start=lambda pid: atomic.write_text(p["pid"], f"{pid}\n"))
    p["pid"].unlink(missing_ok=True)
    atomic.write_text(p["log"], f"$ {' '.join(map(str, cmd))}\n{so}{se}(exit {rc})\n")
    rec = {"name": shard.name, "args": list(shard.args), "rc": rc, "seconds": round(time.time() - t0, 2),
           "host": os.uname().nodename}
    if rc in (0, 1) and _parses(p):
        atomic.write_text(p["done"], json.dumps(rec, indent=1) + "\n")
        return rec | {"complete": True}
    return rec | {"complete": False}


def read_state(path: pathlib.Path, plan: list) -> dict:
    """OUT/state.json: runs per shard (attempts), kept across launches for the shards of PLAN."""
    try:
        st = json.loads(pathlib.Path(path).read_text())
    except (OSError, ValueError):
        st = {}
    att = st.get("attempts") if isinstance(st, dict) else None
    names = {s.name for s in plan}
    return {"attempts": {k: v for k, v in (att if isinstance(att, dict) else {}).items()
                         if k in names and isinstance(v, int)}}


# ----------------------------------------------------------------------------------------------
# Merging

ASSERT_RE = re.compile(r"%Error: (\S+:\d+): Assertion failed in (.*)")


def _first_assertion(log: pathlib.Path):
    """The first failed assertion the simulator printed in a shard's log: "file:line: path: message"."""
    try:
        text = log.read_text(errors="replace")
    except OSError:
        return None
    found = [m for m in ASSERT_RE.finditer(text)]
    named = [m for m in found if "'assert' failed" not in m.group(2)]   # a named checker over an anonymous one
    m = (named or found or [None])[0]
    return f"{m.group(1)}: {m.group(2)}" if m else None


def _replay(cmd, pst: str):
    return f"{pst}{cmd[3:]}" if cmd and cmd.startswith("pst ") else cmd


def merge(out: pathlib.Path, plan: list, pst: str, attempts=None) -> dict:
    """One result from the shards' outputs (complete shards only; the others are listed as
    missing): every run, per-profile totals, and the first failure with its replay command."""
    attempts = attempts or {}
    runs, missing, failed, shards = [], [], [], {}
    for s in plan:
        rec = complete(out, s)
        shards[s.name] = {"complete": rec is not None, "attempts": attempts.get(s.name, 0)}
        if rec is None:
            missing.append(s.name)
            continue
        shards[s.name] |= {"rc": rec["rc"], "seconds": rec.get("seconds"), "host": rec.get("host")}
        for r in regress_runs(json.loads(paths(out, s.name)["json"].read_text())):
            runs.append(r | {"shard": s.name})
        if rec["rc"] != 0:
            failed.append(s.name)
    random = any(s.count for s in plan)
    order = {s.name: i for i, s in enumerate(plan)}
    bad = [r for r in runs if not r.get("passed", False)]
    first = None
    if bad:
        if random:   # the lowest fragment index, then the plan's order (profiles)
            key = lambda r: (r.get("first_bad") if r.get("first_bad") is not None else math.inf, order[r["shard"]])
        else:
            key = lambda r: order[r["shard"]]
        r = min(bad, key=key)
        first = {"shard": r["shard"], "profile": r.get("profile"), "scene": r.get("scene"), "seed": r.get("seed"),
                 "fragment": r.get("first_bad"), "kind": "assertion" if r.get("assertion") else "mismatch",
                 "mismatches": r.get("mismatches"), "replay": _replay(r.get("replay"), pst)}
        if r.get("assertion"):
            first["assertion"] = _first_assertion(paths(out, r["shard"])["log"])
    profiles = {}
    for s in plan:
        profiles.setdefault(s.profile, {"shards": 0, "runs": 0, "failed": 0, "mismatches": 0, "assertions": 0})
        profiles[s.profile]["shards"] += 1
        if random:
            pr = profiles[s.profile]
            pr["from"] = min(pr.get("from", s.first), s.first)
            pr["to"] = max(pr.get("to", 0), s.first + s.count)
    for r in runs:
        pr = profiles.setdefault(r.get("profile"), {"shards": 0, "runs": 0, "failed": 0, "mismatches": 0, "assertions": 0})
        pr["runs"] += 1
        pr["failed"] += not r.get("passed", False)
        pr["mismatches"] += r.get("mismatches") or 0
        pr["assertions"] += bool(r.get("assertion"))
        if random:
            pr["simulated"] = pr.get("simulated", 0) + (r.get("fragments") or 0)
            pr["seconds"] = round(pr.get("seconds", 0) + (r.get("seconds") or 0), 2)
    return {"mode": "random" if random else "scenes", "passed": not bad and not missing and not failed,
            "complete": not missing, "shards": shards, "missing": missing, "failed_shards": failed,
            "profiles": profiles, "first_failure": first, "runs": runs}


def merge_junit(out: pathlib.Path, plan: list, suite: str) -> str:
    """One JUnit document of every complete shard's test cases, plus an error case per missing shard."""
    cases, failures, errors, skipped, secs = [], 0, 0, 0, 0.0
    for s in plan:
        p = paths(out, s.name)
        if complete(out, s) is None:
            tc = ET.Element("testcase", classname="regress.shard", name=s.name, time="0")
            ET.SubElement(tc, "error", message="shard left no complete result (killed, crashed or refused its input)")
            cases.append(tc)
            errors += 1
            continue
        for tc in ET.parse(p["xml"]).getroot().iter("testcase"):
            tc.set("name", f"{tc.get('name')} [{s.name}]" if s.count else tc.get("name", ""))
            cases.append(tc)
            failures += tc.find("failure") is not None
            errors += tc.find("error") is not None
            skipped += tc.find("skipped") is not None
            secs += float(tc.get("time") or 0)
    root = ET.Element("testsuites")
    ts = ET.SubElement(root, "testsuite", name=suite, tests=str(len(cases)), failures=str(failures),
                       errors=str(errors), skipped=str(skipped), time=f"{secs:.3f}")
    ts.extend(cases)
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def summary(m: dict) -> str:
    """The merged result for the terminal."""
    lines = []
    if m["mode"] == "random":
        lines.append(f"{'profile':<20} {'shards':>6} {'fragments':>24} {'simulated':>11} {'mismatch':>9} {'assert':>7} "
                     f"{'frag/s/shard':>13}")
        for name, pr in m["profiles"].items():
            rng = f"{pr.get('from', 0)}..{pr.get('to', 0)}"
            rate = pr.get("simulated", 0) / pr["seconds"] if pr.get("seconds") else 0
            lines.append(f"{name:<20} {pr['shards']:>6} {rng:>24} {pr.get('simulated', 0):>11} {pr['mismatches']:>9} "
                         f"{pr['assertions']:>7} {rate:>13.0f}")
    n = len(m["shards"])
    if m["missing"]:
        lines.append(f"incomplete: {len(m['missing'])} of {n} shards left no result: {', '.join(m['missing'])}")
    f = m["first_failure"]
    if f:
        where = (f"seed {f['seed']}, fragment {f['fragment']}" if f.get("seed") is not None
                 else f"scene {f.get('scene')}")
        what = "RTL assertion" + (f" ({f['assertion']})" if f.get("assertion") else "") \
            if f["kind"] == "assertion" else f"{f.get('mismatches')} mismatches"
        lines.append(f"first failure: shard {f['shard']} [{f['profile']}]: {where}: {what}")
        if f.get("replay"):
            lines.append(f"replay alone: {f['replay']}")
    verdict = "PASSED" if m["passed"] else "FAILED"
    lines.append(f"{verdict}: {n} shards, {len(m['failed_shards'])} failed, {len(m['missing'])} without a result, "
                 f"{len(m['runs'])} runs")
    return "\n".join(lines)

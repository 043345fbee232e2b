"""Digests of a result's inputs: what a record (the multiplier proof, the silicon baseline) was
made from, so that a cheap check can tell whether the record still stands for the current tree
and name the files that changed when it does not.

A record keeps {relative path: SHA-256 of the file's content} for every input file and the
versions of the tools that made it; `stale` compares that with the tree as it is now. A TOML
file's content is its parsed values (canonical JSON), so an edited comment does not void a
record; every other file's content is its bytes."""
import hashlib
import json
import pathlib
import tomllib

from .paths import ROOT


def files(globs, root: pathlib.Path = ROOT) -> list:
    """The files matching GLOBS (relative to ROOT, `**` allowed), sorted, without duplicates."""
    found = set()
    for g in globs:
        found.update(p for p in root.glob(g) if p.is_file())
    return sorted(found)


def content(path: pathlib.Path) -> bytes:
    """What a record digests of PATH: a TOML file's values as canonical JSON, else its bytes."""
    data = path.read_bytes()
    if path.suffix == ".toml":
        return json.dumps(tomllib.loads(data.decode()), sort_keys=True, default=str).encode()
    return data


def inputs(globs, root: pathlib.Path = ROOT) -> dict:
    """{path relative to ROOT: SHA-256 of its content} for every file matching GLOBS."""
    return {p.relative_to(root).as_posix(): hashlib.sha256(content(p)).hexdigest()
            for p in files(globs, root)}


def summary(record_inputs: dict, tools: dict) -> str:
    """One short digest of a record's inputs and tools (for messages and report headers)."""
    text = json.dumps({"inputs": record_inputs, "tools": tools}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def stale(recorded: dict, now: dict, recorded_tools: dict = None, now_tools: dict = None) -> list:
    """What differs between a record and the tree: each changed, added or removed file
    ("rtl/x.sv changed") and each tool whose version moved. Empty when the record stands."""
    out = []
    for k in sorted(set(recorded) | set(now)):
        if k not in now:
            out.append(f"{k} removed")
        elif k not in recorded:
            out.append(f"{k} added")
        elif recorded[k] != now[k]:
            out.append(f"{k} changed")
    for k in sorted(set(recorded_tools or {}) | set(now_tools or {})):
        a, b = (recorded_tools or {}).get(k), (now_tools or {}).get(k)
        if a != b:
            out.append(f"tool {k}: {a} -> {b}")
    return out

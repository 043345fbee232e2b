"""Provenance of an output: which commit, which tools, which command line and which schema made
it. One helper for every Python-written output (the main job's report, the baseline check's
JSON), so that a report found on a disk says what it was made from.

    provenance.collect(schema=1)   -> {"schema": 1, "commit": "abc123...[-dirty]" | "unknown",
                                       "tools": {"verilator": ..., "yosys": ..., "opensta": ...,
                                                 "python": ...},
                                       "command": "scripts/report.py out --md ..."}

A tool that is not installed (or does not answer) is "not found"; outside a git checkout the
commit is "unknown".
"""
import functools
import pathlib
import platform
import shlex
import subprocess
import sys

from ..paths import ROOT

# name -> the command printing its version (first line of its output).
TOOLS = {"verilator": ["verilator", "--version"], "yosys": ["yosys", "-V"], "opensta": ["sta", "-version"]}
NOT_FOUND = "not found"


def _first_line(cmd: list, cwd=None, timeout: float = 20):
    """The first line of CMD's output (stdout, else stderr), None when it cannot run or fails."""
    try:
        r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, stdin=subprocess.DEVNULL,
                           timeout=timeout)
    except (OSError, subprocess.SubprocessError):
        return None
    if r.returncode != 0:
        return None
    lines = (r.stdout or r.stderr).strip().splitlines()
    return lines[0].strip() if lines else None


def commit(root: pathlib.Path = ROOT) -> str:
    """`git rev-parse HEAD` of ROOT, with "-dirty" when `git status --porcelain` lists anything;
    "unknown" outside a git checkout (or without git)."""
    head = _first_line(["git", "-C", str(root), "rev-parse", "HEAD"])
    if not head:
        return "unknown"
    try:
        r = subprocess.run(["git", "-C", str(root), "status", "--porcelain"], capture_output=True, text=True,
                           stdin=subprocess.DEVNULL, timeout=60)
        dirty = r.returncode == 0 and r.stdout.strip() != ""
    except (OSError, subprocess.SubprocessError):
        dirty = False
    return head + ("-dirty" if dirty else "")


@functools.lru_cache(maxsize=None)
def tool_versions() -> dict:
    """{verilator, yosys, opensta, python}: each tool's version line, NOT_FOUND when absent."""
    out = {name: _first_line(cmd) or NOT_FOUND for name, cmd in TOOLS.items()}
    out["python"] = f"Python {platform.python_version()} ({sys.executable})"
    return out


def command_line(argv=None) -> str:
    """The command line (ARGV, default sys.argv), shell-quoted."""
    return shlex.join(sys.argv if argv is None else argv)


def collect(schema: int, argv=None, root: pathlib.Path = ROOT) -> dict:
    """The provenance record of an output of schema version SCHEMA."""
    return {"schema": schema, "commit": commit(root), "tools": dict(tool_versions()),
            "command": command_line(argv)}


def line(p: dict) -> str:
    """One line for a report's header: commit, tools, command, schema."""
    tools = ", ".join(f"{k} {v}" for k, v in p.get("tools", {}).items())
    return f"commit {p.get('commit', 'unknown')}; {tools}; command `{p.get('command', '')}`; schema {p.get('schema')}"

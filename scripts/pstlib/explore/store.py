"""Stored results of an exploration (OUT/results/NAME.json, written through a temporary file
and a rename, so an interrupted run resumes) and the one rule for reusing one."""
import json
import pathlib

from .. import atomic


def read_json(path: pathlib.Path):
    """The parsed file, None when it is missing or not JSON."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


class Store:
    def __init__(self, out: pathlib.Path, indent: int = 1):
        self.dir = pathlib.Path(out) / "results"
        self.indent = indent

    def path(self, name: str) -> pathlib.Path:
        return self.dir / f"{name}.json"

    def get(self, name: str):
        return read_json(self.path(name))

    def put(self, name: str, r: dict) -> dict:
        atomic.write_text(self.path(name), json.dumps(r, indent=self.indent) + "\n")
        return r


def reusable(r, sha: str, same: dict, scenes: dict, retry_failed: bool, area_missing) -> bool:
    """A stored result R (None or a parsed results/NAME.json) stands for the point as it is:
    the same content key SHA, the same values of the fields in SAME (render settings, the pst
    build), not failed (a failed one stands unless RETRY_FAILED), every scene of SCENES
    (field -> scene names: the field of R holding them) scored, and area_missing(R) false (its
    area done, or none wanted)."""
    if not isinstance(r, dict) or r.get("profile_sha") != sha:
        return False
    if any(r.get(k) != v for k, v in same.items()):
        return False
    if r.get("status") != "ok":
        return not retry_failed
    if any(set(names) - set(r.get(field) or {}) for field, names in scenes.items()):
        return False
    return not area_missing(r)

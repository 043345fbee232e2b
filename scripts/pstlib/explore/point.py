"""One point of an exploration: a profile (its values, its file's text) and how it was reached."""
import dataclasses
import hashlib
import json
import pathlib

from .. import contract


def text_key(text: str) -> str:
    """Content key of a text (a sweep point: its profile and scene copies)."""
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def values_key(doc: dict) -> str:
    """Content key of a profile's values (a search point: comments and order aside)."""
    return hashlib.sha256(json.dumps(doc, sort_keys=True).encode()).hexdigest()[:12]


@dataclasses.dataclass
class Point:
    name: str
    doc: dict                       # the profile's values
    text: str                       # its file's text (comments kept)
    sha: str                        # content key its results are stored under
    profile: pathlib.Path | None = None     # its file
    move: str = ""                  # how it was reached ("coord_frac 16->14", "start (full)")
    knob: str = ""                  # a sweep's knob ("base" for the base itself)
    value: object = None            # and its value
    scene_files: dict = dataclasses.field(default_factory=dict)   # scene name -> file rendered
    synth_name: str = ""            # out/synth/<synth_name>.json holds its gate count
    is_base: bool = False

    @property
    def cpp(self) -> int:
        """Clocks per pixel (the contract's cycle formulas)."""
        return contract.stage_cycles(self.doc)["pixel"]

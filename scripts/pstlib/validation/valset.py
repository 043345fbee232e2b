"""The held-out validation set: scenes drawn from every stratum of the training generator, on
seeds the training generator never takes.

Why: a profile was once accepted on 16 plain random draws (scenegen's "valid" stream) and then
lost up to 10 dB on textures of kinds that set did not hold (a full quadric under a step map
with a blended MIP, a plane to the horizon with nearest MIP and eight rotated octaves, a
rotated marble on a torus with a clamped map). This set is stratified by those kinds. Scene
i belongs to stratum STRATA[i % 8]; a stratum pins the features that define it and walks the
others (scenegen's shuffled walks, a stream per stratum and feature), so 8 scenes hold every
stratum once and 64 hold every stratum eight times, with every filter, wrap, interpolation,
matrix kind, quadric kind, mesh and octave count 1..8 among them. The first scene of some
strata is one of those three kinds exactly (ANCHORS).

Strata:
- step_sensitive: a step colour map taken mod with no filter, nearest MIP or the summed-area
  table (the training generator's step-sensitive stratum: a tiny change of f moves whole pixels
  across a step or the wrap, and of W for the table);
- quadric_step: a full quadric with cross terms (B, C, F) under a step map, any filter;
- horizon: a large plane seen from low down running to the horizon (footprints from a pixel to
  the whole table, filter widths and MIP levels over their whole range), 5..8 octaves;
- rotated_clamp: a rotated marble (linear quadric, rotated octaves) with a clamped map;
- affine_full: general affine octave matrices with a full quadric;
- npot_axis: axis-aligned octaves at non-power-of-two frequencies (never the paper's 2^k);
- step_clamp: a step colour map clamped (steps without the wrap), any filter;
- plain: the training generator's plain draw (every feature walked).
Numbers (frequencies, lacunarity, offsets, amplitudes, quadric coefficients, ramps, cameras)
are drawn as scenegen draws them, inside both named profiles' input formats.

Seeds: the training generator (scenegen, scripts/gen_scenes.py, scripts/search.py --seed)
takes seeds 0..TRAIN_SEED_END-1; this set takes [TRAIN_SEED_END, 2 * TRAIN_SEED_END) and
refuses others, and its streams are named "holdout" besides: no scene of it is a training
scene. Deterministic: a scene is a function of (seed, index, size) alone, and scene k does not
change when the set grows.

The training twin (TRAINING, `scripts/validate.py --train`): the same strata drawn on training
seeds (0..TRAIN_SEED_END-1, stream "strata_train", scenes trn_NNN), for choosing formats and
structures by the same rule without looking at the held-out scenes; a choice is then judged once
on the held-out set (HOLDOUT, the default everywhere).
"""
import json
import math
import pathlib
from typing import NamedTuple

from .. import atomic
from . import scenegen
from .scenegen import FILTERS, INTERPS, MATRIX_KINDS, MESHES, OCTAVE_COUNTS, QUADRIC_KINDS, STEP_FILTERS, WRAPS

SEED_BEGIN = scenegen.TRAIN_SEED_END
SEED_END = 2 * scenegen.TRAIN_SEED_END
DEFAULT_SEED = SEED_BEGIN + 1
DEFAULT_COUNT = 64
DEFAULT_SIZE = 128
STREAM = "holdout"


class Split(NamedTuple):
    """Which seeds a set takes, the generator stream it draws from and its scenes' prefix."""
    name: str
    seed_begin: int
    seed_end: int
    stream: str
    prefix: str


HOLDOUT = Split("validation", SEED_BEGIN, SEED_END, STREAM, "val")
TRAINING = Split("training", 0, scenegen.TRAIN_SEED_END, "strata_train", "trn")
TRAIN_DEFAULT_SEED = 1

# Stratum -> the values each feature may take (one value: pinned). Features: filter, wrap,
# interp, matrix (octave matrix kind), quadric (kind), mesh, octaves (count).
_ALL = {"filter": FILTERS, "wrap": WRAPS, "interp": INTERPS, "matrix": MATRIX_KINDS, "quadric": QUADRIC_KINDS,
        "mesh": MESHES, "octaves": OCTAVE_COUNTS}
STRATA = {
    "step_sensitive": {"interp": ["step"], "wrap": ["mod"], "filter": STEP_FILTERS},
    "quadric_step": {"quadric": ["full"], "interp": ["step"]},
    "horizon": {"mesh": ["horizon"], "octaves": [5, 6, 7, 8], "filter": ["mip", "mip_linear", "sat", "none"]},
    "rotated_clamp": {"matrix": ["rotated"], "quadric": ["linear"], "wrap": ["clamp"]},
    "affine_full": {"matrix": ["general"], "quadric": ["full"]},
    "npot_axis": {"matrix": ["axis"]},
    "step_clamp": {"interp": ["step"], "wrap": ["clamp"]},
    "plain": {},
}
STRATUM_NAMES = list(STRATA)
# The first scene of these strata: the three kinds above (numbers still drawn).
ANCHORS = {
    "quadric_step": {"filter": "mip_linear", "wrap": "mod"},
    "horizon": {"filter": "mip", "octaves": 8, "matrix": "rotated"},
    "rotated_clamp": {"mesh": "torus", "interp": "linear", "filter": "mip_linear"},
}
SIZE_RANGE = (16, 2048)
MAX_COUNT = 4096


def check_seed(seed: int, flag: str = "--seed", split: Split = HOLDOUT) -> int:
    """SEED if it is a seed of SPLIT, else ValueError (what the command lines print)."""
    if not isinstance(seed, int) or not split.seed_begin <= seed < split.seed_end:
        other = TRAINING if split is HOLDOUT else HOLDOUT
        raise ValueError(f"{flag}: {split.name} seeds are {split.seed_begin}..{split.seed_end - 1} ({other.name} "
                         f"takes {other.seed_begin}..{other.seed_end - 1}), got {seed}")
    return seed


def stratum_of(index: int) -> str:
    return STRATUM_NAMES[index % len(STRATUM_NAMES)]


def features_of(seed: int, index: int, split: Split = HOLDOUT) -> dict:
    """The categorical features of scene INDEX: its stratum's pinned values, the anchor's for
    the stratum's first scene, and walks through the allowed values for the rest."""
    check_seed(seed, split=split)
    st = stratum_of(index)
    j = index // len(STRATUM_NAMES)
    allowed = dict(_ALL, **STRATA[st])
    out = {f: scenegen._stratum(seed, split.stream, f"{st}/{f}", list(v), j) for f, v in allowed.items()}
    if j == 0:
        out.update(ANCHORS.get(st, {}))
    out["stratum"] = st
    return out


def horizon_camera(r) -> tuple:
    """A large plane (y = 0) seen from low down, the horizon in the upper part of the picture:
    eye at height 0.3..1.5, looking 1.5..10 degrees down; texture scale such that |s| stays
    inside the input formats (|s| < 12 with the offset) to the plane's far edge."""
    hs = r.uniform(120.0, 300.0)
    obj = {"mesh": "plane", "half_size": hs, "divisions": 8}
    h = r.uniform(0.3, 1.5)
    az = r.uniform(0, 2 * math.pi)
    pitch = math.radians(r.uniform(1.5, 10.0))
    d = 20.0
    eye = [0.0, h, 0.0]
    target = [d * math.sin(az), h - d * math.tan(pitch), d * math.cos(az)]
    obj["tex_scale"] = r.uniform(3.0, 6.0) / hs
    obj["tex_rotate"] = [r.uniform(0, 360) for _ in range(3)]
    obj["tex_offset"] = [r.uniform(-3, 3) for _ in range(3)]
    return {"eye": eye, "target": target, "fovy": r.uniform(35.0, 50.0), "near": 0.05}, obj


def scene(seed: int, index: int, size: int = DEFAULT_SIZE, split: Split = HOLDOUT) -> tuple:
    """(file name, TOML text, features) of scene INDEX of SPLIT (the validation set by default)."""
    f = features_of(seed, index, split)
    r = scenegen._rng(seed, split.stream, "scene", index)
    octs, ofeat = scenegen.octaves(r, f["octaves"], f["matrix"])
    quad = scenegen.quadric(r, f["quadric"])
    cmap = scenegen.colormap(r, f["wrap"], f["interp"])
    if f["mesh"] == "horizon":
        cam, obj = horizon_camera(r)
    else:
        cam, obj = scenegen.camera_and_object(r, f["mesh"])
    name = f"{split.prefix}_{index:03d}"
    header = [f"# {split.name.capitalize()} scene {name} (scripts/validate.py, seed {seed}), stratum {f['stratum']}: "
              f"{f['octaves']} octave(s), {f['matrix']} matrices,",
              f"# {f['quadric']} quadric, {f['interp']} colour map ({f['wrap']}), filter {f['filter']}, "
              f"mesh {f['mesh']}.",
              f'title = "{split.name} {name} (seed {seed}, {f["stratum"]})"']
    text = scenegen.scene_toml(header, size, [r.uniform(0, 0.25) for _ in range(3)], cam, quad, f["filter"], cmap,
                               octs, obj)
    step = f["interp"] == "step" and f["wrap"] == "mod" and f["filter"] in STEP_FILTERS
    feats = dict(ofeat, name=name, seed=seed, index=index, stratum=f["stratum"], filter=f["filter"], wrap=f["wrap"],
                 interp=f["interp"], quadric=f["quadric"], cross_terms=f["quadric"] == "full", mesh=f["mesh"],
                 octave_kind=f["matrix"], step_sensitive=step, horizon=f["mesh"] == "horizon",
                 ramp_keys=len(cmap["ramp"]))
    return f"{name}.toml", text, feats


def check(seed: int, count: int, size: int, split: Split = HOLDOUT) -> None:
    """ValueError("--flag: what is wrong") unless SEED, COUNT and SIZE make a set of SPLIT."""
    check_seed(seed, split=split)
    if not isinstance(count, int) or not 1 <= count <= MAX_COUNT:
        raise ValueError(f"--count: 1..{MAX_COUNT} scenes, got {count}")
    if not isinstance(size, int) or not SIZE_RANGE[0] <= size <= SIZE_RANGE[1]:
        raise ValueError(f"--size: {SIZE_RANGE[0]}..{SIZE_RANGE[1]} pixels, got {size}")


def generate(seed: int = DEFAULT_SEED, count: int = DEFAULT_COUNT, size: int = DEFAULT_SIZE,
             split: Split = HOLDOUT) -> list:
    """[(file name, text, features)] of scenes 0..COUNT-1."""
    check(seed, count, size, split)
    return [scene(seed, i, size, split) for i in range(count)]


def describe(feats: dict) -> str:
    """One line of a scene's features for the reports."""
    return (f"{feats['stratum']}: {feats['octaves']} {feats['octave_kind']} octave(s)"
            f"{' (non-2^k)' if feats.get('non_power_of_two') else ''}, {feats['quadric']} quadric, "
            f"{feats['interp']} map ({feats['wrap']}), filter {feats['filter']}, {feats['mesh']}")


def write(out: pathlib.Path, seed: int = DEFAULT_SEED, count: int = DEFAULT_COUNT, size: int = DEFAULT_SIZE,
          split: Split = HOLDOUT) -> dict:
    """OUT/PREFIX_NNN.toml (files of other counts or the other split removed) and OUT/manifest.json;
    the manifest."""
    scenes = generate(seed, count, size, split)
    manifest = {"seed": seed, "count": count, "size": size, "split": split.name, "generator": "scripts/pstlib/validation/valset.py",
                "scenes": [f for _, _, f in scenes]}
    write_set(out, scenes, (HOLDOUT.prefix, TRAINING.prefix), manifest)
    return manifest


def write_set(out, files, prefixes, manifest: dict) -> None:
    """A generated scene set in OUT: FILES [(file name, text, features)] written where changed, the
    other PREFIX_*.toml files of either split removed, OUT/manifest.json."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    names = {f for f, _, _ in files}
    for old in [p for prefix in prefixes for p in out.glob(f"{prefix}_*.toml")]:
        if old.name not in names:
            old.unlink()
    for fname, text, _ in files:
        atomic.write_if_changed(out / fname, text)
    atomic.write_text(out / "manifest.json", json.dumps(manifest, indent=1) + "\n")

"""Fly-ins held apart from anything tuned: seeded animated scenes (a camera moving over a textured
ground plane) for judging the antialiasing in motion, as valset.py's stills judge precision.

Why: the subband unit's weight-table offset was chosen on the seascape fly-in, the same scene its
flicker goal was measured on; on a held-out fly-in it fell below the goal. This set holds, for
every noise basis a hardware profile computes (rayshade, perlin2002, worley, subband), every kind
of camera path:
- forward: toward the horizon along the view direction, eye 0.5..2 above the plane;
- sideways: the eye and the target slide across the view direction (a strafe);
- orbit: the eye circles a point on the plane, looking at it (nine keys over 40..100 degrees);
- zoom: the eye stands, the field of view narrows from 45..60 to 12..25 degrees;
- grazing: a low (0.12..0.4) flight at 25..65 degrees to the view direction, looking 0.5..3
  degrees down (the issue's "low, diagonal flight");
and every kind of colour map: smooth ramps and steps (interp linear | step), each clamped or taken
mod (ramp_clamp, ramp_mod, step_clamp, step_mod), 4..8 keys spread over the table with colours
apart (colormap(): no map is nearly constant where f lies).

Sequence i of the validation set has basis BASES[i % 4] and path PATHS[i % 5]: 20 sequences hold
every (basis, path) pair once; the colour-map kind walks a shuffled list. The training set
(TRAINING) draws basis BASES[i % 4] and walks paths and maps on its own stream and seeds: 8
sequences hold every basis twice and every path and map kind at least once; a table, offset or
weight chosen for the antialiasing is chosen on it and judged once on the validation set.

Every scene is a plane (y = 0; the subband basis on its plane, param "xz") with one texture of 2..4
octaves (the test profiles hold 4: the hardware drops none; worley's amplitudes x 3, its F_k
spreading less), a constant quadric (worley's centring f's mean on 0.5), filter "sat",
bandlimit off, and the noise keys the basis's hardware unit computes (worley: the octant search, 4
points, the ROM's cubes; subband: the unit's tile, K = 8, heuristic weights, sigma 1/sqrt(12)), so
every hardware profile of its basis runs it bit for bit. Values stay inside the input formats
(|s| < 64 with the offset, inside reduced's coordinate format; |M| < 48; |a| <= 1.5, |a M| <= 48).
Deterministic: a sequence is a function of (seed, index, frames, size) alone, and sequence k does
not change when the set grows.

Seeds as valset.py's: training 0..999,999, validation 1,000,000..1,999,999, on streams of their
own ("flyin_train", "flyin_holdout")."""
import math
from typing import NamedTuple

from . import scenegen, valset
from .scenegen import _vec

BASES = ["rayshade", "perlin2002", "worley", "subband"]
PATHS = ["forward", "sideways", "orbit", "zoom", "grazing"]
CMAPS = ["ramp_clamp", "ramp_mod", "step_clamp", "step_mod"]

SEED_BEGIN, SEED_END = valset.SEED_BEGIN, valset.SEED_END   # the strata sets' validation seeds
DEFAULT_FRAMES = 16
DEFAULT_SIZE = 48
FRAMES_RANGE = (3, 256)
SIZE_RANGE = (8, 512)
MAX_COUNT = 1024


# A split of the fly-ins: valset.Split's fields, then the defaults of its --seed and --count.
Split = NamedTuple("Split", [*valset.Split.__annotations__.items(), ("default_seed", int), ("default_count", int)])


VALIDATION = Split("validation", SEED_BEGIN, SEED_END, "flyin_holdout", "fval", SEED_BEGIN + 1, 20)
TRAINING = Split("training", 0, scenegen.TRAIN_SEED_END, "flyin_train", "ftrn", 1, 8)
SPLITS = {s.name: s for s in (VALIDATION, TRAINING)}

# The hardware's noise keys per basis (scenes/README.md "Noise bases"; sim/test_profiles/).
WORLEY_COEFS = [[1.0, 0.0], [-1.0, 1.0], [0.5, 0.5], [0.0, 1.0]]
SUBBAND_NOISE = 'noise = { basis = "subband", orientations = 8, param = "xz", tile_size = 256, seed = 1, sigma = 0.2887 }'


def check_seed(seed, split: Split = VALIDATION, flag: str = "--seed") -> int:
    if isinstance(seed, bool) or not isinstance(seed, int) or not split.seed_begin <= seed < split.seed_end:
        other = TRAINING if split is VALIDATION else VALIDATION
        raise ValueError(f"{flag}: {split.name} seeds are {split.seed_begin}..{split.seed_end - 1} ({other.name} "
                         f"takes {other.seed_begin}..{other.seed_end - 1}), got {seed}")
    return seed


def check(seed, count, frames, size, split: Split = VALIDATION) -> None:
    """ValueError("--flag: what is wrong") unless the arguments make a set of SPLIT."""
    check_seed(seed, split)
    for flag, v, lo, hi, what in (("--count", count, 1, MAX_COUNT, "sequences"),
                                  ("--frames", frames, *FRAMES_RANGE, "frames"),
                                  ("--size", size, *SIZE_RANGE, "pixels")):
        if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
            raise ValueError(f"{flag}: {lo}..{hi} {what}, got {v}")


def features_of(seed: int, index: int, split: Split = VALIDATION) -> dict:
    check_seed(seed, split)
    basis = BASES[index % len(BASES)]
    if split is VALIDATION:
        path = PATHS[index % len(PATHS)]
    else:
        path = scenegen._stratum(seed, split.stream, "path", PATHS, index)
    cmap = scenegen._stratum(seed, split.stream, "cmap", CMAPS, index)
    return {"basis": basis, "path": path, "cmap": cmap}


def _octaves(r, basis: str) -> list:
    """2..4 octaves: rotated matrices on the lattice bases, axis-aligned (anisotropic in the
    plane) on the subband basis, whose unit samples the plane's (s, r)."""
    count = r.randint(2, 4)
    kind = "axis" if basis == "subband" else r.choice(["rotated", "axis"])
    octs, _ = scenegen.octaves(r, count, kind)
    if basis == "subband":
        for o in octs:
            o["offset"] = [o["offset"][0], 0.0, o["offset"][2]]
    return octs


# Mean of F1 and F2 of the worley unit's variant (octant search, 4 points, the ROM's cubes:
# scenes/README.md "Noise bases"), to centre f on the map.
WORLEY_MEAN_F = (0.368, 0.494)
MAP_KEYS = (4, 8)


def colormap(r, wrap: str, interp: str) -> dict:
    """4..8 keys spread over the table (key k near k / (keys - 1), jittered by up to a third of the
    spacing), each colour at least 0.3 (max over RGB) from the key before it, so that no map is
    nearly constant over the range f takes (a 2-key step map taken mod is one colour)."""
    keys = r.randint(*MAP_KEYS)
    step = 1.0 / (keys - 1)
    pos = [0.0] + [(k + r.uniform(-1 / 3, 1 / 3)) * step for k in range(1, keys - 1)] + [1.0]
    ramp = []
    for p in pos:
        while True:
            c = [r.random() for _ in range(3)]
            if not ramp or max(abs(a - b) for a, b in zip(c, ramp[-1][1:])) >= 0.3:
                break
        ramp.append([p] + c)
    if wrap == "mod" and r.random() < 0.5:
        ramp[-1][1:] = ramp[0][1:]     # seamless, like the paper's mod maps
    return {"size": 256, "wrap": wrap, "interp": interp, "ramp": ramp}


def _heading(r):
    az = r.uniform(0, 2 * math.pi)
    return az, (math.sin(az), math.cos(az))


def _pt(p):
    return [round(v, 5) for v in p]


def camera_path(r, path: str) -> tuple:
    """(camera table, tracks): the still's camera and [(field, keys)] of the path; keys
    [[t, value...]]."""
    az, (dx, dz) = _heading(r)
    side = (dz, -dx)
    fovy = r.uniform(38.0, 50.0)
    if path in ("forward", "sideways", "grazing"):
        h = r.uniform(0.12, 0.4) if path == "grazing" else r.uniform(0.5, 2.0)
        pitch = math.radians(r.uniform(0.5, 3.0) if path == "grazing" else r.uniform(2.0, 10.0))
        d = 20.0
        eye = [0.0, h, 0.0]
        target = [d * dx, h - d * math.tan(pitch), d * dz]
        if path == "forward":
            move = [dx * r.uniform(4.0, 12.0), 0.0, dz * r.uniform(4.0, 12.0)]
        elif path == "sideways":
            s = r.uniform(2.0, 6.0) * r.choice([-1, 1])
            move = [side[0] * s, 0.0, side[1] * s]
        else:
            ang = math.radians(r.uniform(25.0, 65.0)) * r.choice([-1, 1])
            ca, sa = math.cos(ang), math.sin(ang)
            dist = r.uniform(3.0, 8.0)
            move = [(dx * ca + side[0] * sa) * dist, 0.0, (dz * ca + side[1] * sa) * dist]
        eye1 = [e + m for e, m in zip(eye, move)]
        target1 = [t + m for t, m in zip(target, move)]
        cam = {"eye": eye, "target": target, "fovy": fovy, "near": 0.05}
        return cam, [("camera.eye", [[0.0, *_pt(eye)], [1.0, *_pt(eye1)]]),
                     ("camera.target", [[0.0, *_pt(target)], [1.0, *_pt(target1)]])]
    if path == "orbit":
        radius = r.uniform(3.0, 9.0)
        h = r.uniform(0.6, 3.0)
        center = [r.uniform(-2, 2), 0.0, r.uniform(-2, 2)]
        sweep = math.radians(r.uniform(40.0, 100.0)) * r.choice([-1, 1])
        keys = []
        for k in range(9):
            a = az + sweep * k / 8
            keys.append([k / 8, *_pt([center[0] - radius * math.sin(a), h, center[2] - radius * math.cos(a)])])
        cam = {"eye": keys[0][1:], "target": center, "fovy": fovy, "near": 0.05}
        return cam, [("camera.eye", keys)]
    if path == "zoom":
        h = r.uniform(0.8, 2.5)
        pitch = math.radians(r.uniform(4.0, 15.0))
        d = 20.0
        cam = {"eye": [0.0, h, 0.0], "target": [d * dx, h - d * math.tan(pitch), d * dz],
               "fovy": r.uniform(45.0, 60.0), "near": 0.05}
        return cam, [("camera.fovy", [[0.0, round(cam["fovy"], 4)], [1.0, round(r.uniform(12.0, 25.0), 4)]])]
    raise ValueError(f"path: one of {', '.join(PATHS)}, got {path!r}")


def _noise_line(basis: str, coef=None):
    if basis == "rayshade":
        return None
    if basis == "perlin2002":
        return 'noise = { basis = "perlin2002" }'
    if basis == "worley":
        return (f'noise = {{ basis = "worley", coef = {_vec(coef)}, search = "octant", max_points = 4, '
                f'cubes = "rom256" }}')
    return SUBBAND_NOISE


def sequence(seed: int, index: int, frames: int = DEFAULT_FRAMES, size: int = DEFAULT_SIZE,
             split: Split = VALIDATION) -> tuple:
    """(file name, TOML text, features) of sequence INDEX of SPLIT."""
    f = features_of(seed, index, split)
    r = scenegen._rng(seed, split.stream, "sequence", index)
    basis, path, ckind = f["basis"], f["path"], f["cmap"]
    octs = _octaves(r, basis)
    interp, wrap = ("linear" if ckind.startswith("ramp") else "step"), ckind.split("_")[1]
    cmap = colormap(r, wrap, interp)
    cam, tracks = camera_path(r, path)
    hs = r.uniform(150.0, 300.0)
    k = r.uniform(0.03, 0.2)       # |s| <= 60 (+ 3) at the plane's edge: inside reduced's coord format
    scale = k if r.random() < 0.5 else [k, k, k / r.uniform(1.5, 4.0)]    # or stretched, as the seascape's
    obj = {"mesh": "plane", "half_size": hs, "divisions": 8, "tex_scale": scale,
           "tex_offset": [r.uniform(-3, 3), 0.0, r.uniform(-3, 3)]}
    if basis == "subband":        # the unit's plane: rotations about y only
        obj["tex_rotate"] = [0.0, r.uniform(0, 360), 0.0]
    else:
        obj["tex_rotate"] = [r.uniform(0, 360) for _ in range(3)]
    coef = r.choice(WORLEY_COEFS) if basis == "worley" else None
    if coef:
        # F_k spread much less than the lattice noises: amplitudes up to x 3 (|a| <= 1.5 and
        # |a M| <= 40: inside reduced's amplitude and gradient-matrix formats), J centres f's mean on 0.5
        k = min([3.0, 1.5 / max(abs(o["amplitude"]) for o in octs)] +
                [40.0 / (abs(o["amplitude"]) * max(abs(v) for row in o["matrix"] for v in row)) for o in octs])
        for o in octs:
            o["amplitude"] *= k
        mean = sum(a * b for a, b in zip(coef, WORLEY_MEAN_F))
        quad = {"J": 0.5 - mean * sum(o["amplitude"] for o in octs) + r.uniform(-0.1, 0.1)}
    else:
        quad = {"J": r.uniform(0.35, 0.65)}
    noise = _noise_line(basis, coef)
    name = f"{split.prefix}_{index:03d}"
    header = [f"# Fly-in {name} of the {split.name} set (scripts/flyins.py, seed {seed}): basis {basis}, "
              f"path {path}, colour map {ckind},",
              f"# {len(octs)} octave(s) on a ground plane, {frames} frames.",
              f'title = "{split.name} fly-in {name} (seed {seed}, {basis}, {path}, {ckind})"']
    text = scenegen.scene_toml(header, size, [r.uniform(0.3, 0.7) for _ in range(3)], cam, quad, "sat", cmap,
                               octs, obj)
    if noise:
        text = text.replace('filter = "sat"\n', f'filter = "sat"\n{noise}\n', 1)
    lines = ["", "# Time track (pst animate): the camera path.", "[animation]", f"frames = {frames}", "fps = 24"]
    for field, keys in tracks:
        lines += ["[[animation.track]]", f'field = "{field}"',
                  "keys = [" + ", ".join(_vec(k) for k in keys) + "]"]
    text += "\n".join(lines) + "\n"
    feats = {"name": name, "seed": seed, "index": index, "split": split.name, "basis": basis, "path": path,
             "cmap": ckind, "wrap": wrap, "interp": interp, "octaves": len(octs), "frames": frames, "size": size}
    return f"{name}.toml", text, feats


def generate(seed: int, count: int, frames: int = DEFAULT_FRAMES, size: int = DEFAULT_SIZE,
             split: Split = VALIDATION) -> list:
    check(seed, count, frames, size, split)
    return [sequence(seed, i, frames, size, split) for i in range(count)]


def coverage(feats: list) -> dict:
    """Which bases, paths and colour-map kinds FEATS miss: {kind: [missing values]}."""
    return {k: [v for v in vals if v not in {f[k] for f in feats}]
            for k, vals in (("basis", BASES), ("path", PATHS), ("cmap", CMAPS))}


def write(out, seed: int, count: int, frames: int = DEFAULT_FRAMES, size: int = DEFAULT_SIZE,
          split: Split = VALIDATION) -> dict:
    """OUT/PREFIX_NNN.toml (other sequences of either split removed) and OUT/manifest.json."""
    seqs = generate(seed, count, frames, size, split)
    manifest = {"seed": seed, "count": count, "frames": frames, "size": size, "split": split.name,
                "generator": "scripts/pstlib/validation/flyins.py", "sequences": [f for _, _, f in seqs]}
    valset.write_set(out, seqs, (VALIDATION.prefix, TRAINING.prefix), manifest)
    return manifest

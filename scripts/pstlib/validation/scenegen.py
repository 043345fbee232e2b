"""Random textures and scenes: textures the nine paper scenes do not show.

The paper's scenes use axis-aligned octaves at power-of-two frequencies, so a profile tuned on
them can fail elsewhere (amplitude or matrix bits that give identical images only because the
products are exact there). This generator draws, from a fixed seed, scenes with:
- 1-8 octaves whose matrices M_i are rotated (R diag(f) with a random rotation R), general
  affine (random entries), or axis-aligned at non-power-of-two frequencies (lacunarity drawn in
  [1.6, 2.6], never exactly 2), with non-integer offsets o_i and random amplitudes (decaying
  by a random gain, some negative);
- full quadrics with cross terms (B, C, F non-zero), or the paper's kinds (linear, radial,
  none);
- colour maps of 2-8 random keys, step or smooth (linear), taken mod or clamped;
- every filter kind (none, mip, mip_linear, sat, box, trapezoid), on every mesh (sphere, cube, plane,
  torus, teapot) seen from a random camera.

Every fourth training scene (index 3, 7, 11, ...) is a step-sensitive one: a step colour map
taken mod, unfiltered, nearest-level MIP or summed-area table. There a tiny change of f (or of W,
for the table) moves whole pixels across a colour step or a wrap, so a precision cut that a smooth
texture hides shows there; the walks over full's formats found such cuts only on validation
textures of this kind (valid_004 unfiltered and mod, valid_008 SAT). This generator's "valid"
set stays a plain random draw (scripts/gen_scenes.py --valid); the search and scripts/validate.py
judge on the held-out set of valset.py instead (every stratum, its own seed range: see
TRAIN_SEED_END).

The categorical features are stratified (each set walks a shuffled list of each feature), so a
set of >= 8 scenes holds every octave count 1..8, every filter, wrap, interpolation, matrix kind
and mesh; the numbers are drawn. A scene is a function of (seed, set name, index) alone:
training and validation sets come from different streams, and scene k of a set does not
change when the set grows. Values are kept inside both named profiles' input formats (|M| < 48,
|s| < 12, |quadric| < 4, |a| < 1): the hardware must not saturate its inputs on them.
"""
import hashlib
import json
import math
import random

FILTERS = ["none", "mip", "mip_linear", "sat", "box", "trapezoid"]
WRAPS = ["mod", "clamp"]
INTERPS = ["linear", "step"]
MATRIX_KINDS = ["rotated", "general", "axis"]
QUADRIC_KINDS = ["full", "full", "linear", "radial", "none"]     # full cross terms twice as often
MESHES = ["sphere", "cube", "plane", "torus", "teapot"]
OCTAVE_COUNTS = list(range(1, 9))
MAX_FREQ = 48.0           # largest |M| entry (reduced's matrix format holds |m| < 64)
SET_NAMES = ("train", "valid")
# Seeds of this generator (the search's training scenes and its own "valid" stream): below
# TRAIN_SEED_END. The held-out validation set (valset.py) takes its seeds from
# [TRAIN_SEED_END, 2 * TRAIN_SEED_END) and refuses these: no scene of it can be a training scene.
TRAIN_SEED_END = 1_000_000


def check_training_seed(seed: int) -> int:
    """SEED if it is a training seed, else ValueError (what the command lines print)."""
    if not isinstance(seed, int) or not 0 <= seed < TRAIN_SEED_END:
        raise ValueError(f"--seed: training seeds are 0..{TRAIN_SEED_END - 1} (the validation set's "
                         f"are {TRAIN_SEED_END}..{2 * TRAIN_SEED_END - 1}), got {seed}")
    return seed
STEP_FILTERS = ["none", "mip", "sat"]     # the filters that keep a step map's steps (see above)


def step_sensitive(set_name: str, index: int) -> bool:
    """Scene INDEX of SET_NAME is one of the training set's step-sensitive scenes."""
    return set_name == "train" and index % 4 == 3


def _rng(seed: int, *parts) -> random.Random:
    """A stream of its own per (seed, parts): sha256 of the text, the same on every platform."""
    h = hashlib.sha256(("/".join([str(seed), *map(str, parts)])).encode()).digest()
    return random.Random(int.from_bytes(h[:8], "little"))


def _num(x: float) -> str:
    """A TOML float with a decimal point or an exponent (6 significant digits)."""
    s = repr(float(f"{x:.6g}"))
    return "0.0" if s == "-0.0" else s


def _vec(v) -> str:
    return "[" + ", ".join(_num(x) for x in v) + "]"


def _stratum(seed: int, set_name: str, feature: str, values: list, index: int):
    """The INDEX-th value of a shuffled walk through VALUES (a new shuffle per pass)."""
    n = len(values)
    order = list(values)
    _rng(seed, set_name, "strata", feature, index // n).shuffle(order)
    return order[index % n]


def _rotation(r: random.Random):
    """A uniformly random 3x3 rotation (Shoemake's quaternion method), rows as lists."""
    u1, u2, u3 = r.random(), r.random(), r.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    x, y = a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2)
    z, w = b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def _is_pow2(x: float) -> bool:
    if x <= 0:
        return False
    e = math.log2(x)
    return abs(e - round(e)) < 1e-9


def octaves(r: random.Random, count: int, kind: str) -> tuple:
    """COUNT octaves (dicts: matrix rows, offset, amplitude) of matrix KIND and their features."""
    f0 = r.uniform(0.7, 3.0)
    lac = r.uniform(1.6, 2.6)
    if count > 1 and f0 * lac ** (count - 1) > MAX_FREQ / 1.25:
        lac = (MAX_FREQ / 1.25 / f0) ** (1.0 / (count - 1))     # the top octave stays inside
    if abs(lac - 2.0) < 0.03:
        lac = 1.97                     # never the paper's exact 2 (nor within 1.5 % of it)
    gain = r.uniform(0.4, 0.65)
    a0 = r.uniform(0.25, 0.8)
    out = []
    for i in range(count):
        f = f0 * lac ** i
        if kind == "rotated":
            rot = _rotation(r)
            aniso = [f * r.uniform(0.8, 1.25) for _ in range(3)]
            m = [[rot[row][col] * aniso[col] for col in range(3)] for row in range(3)]
        elif kind == "general":
            m = [[r.uniform(-1.0, 1.0) * f for _ in range(3)] for _ in range(3)]
            for k in range(3):          # keep it well conditioned: a dominant diagonal
                m[k][k] = math.copysign(f * r.uniform(0.9, 1.25), r.uniform(-1, 1))
        else:
            m = [[0.0] * 3 for _ in range(3)]
            for k in range(3):
                m[k][k] = f * r.uniform(0.85, 1.2)
        m = [[max(-MAX_FREQ, min(MAX_FREQ, v)) for v in row] for row in m]
        amp = a0 * gain ** i * (-1.0 if r.random() < 0.2 else 1.0)
        offset = [r.uniform(-40.0, 40.0) for _ in range(3)]
        out.append({"matrix": m, "offset": offset, "amplitude": amp})
    diag = [[m["matrix"][k][k] for k in range(3)] for m in out]
    feats = {
        "octaves": count, "matrix_kind": kind, "lacunarity": lac, "base_frequency": f0,
        "rotated": any(abs(v) > 1e-9 for o in out for i, row in enumerate(o["matrix"])
                       for j, v in enumerate(row) if i != j),
        "non_power_of_two": any(not _is_pow2(abs(v)) for d in diag for v in d),
        "offsets": any(abs(v) > 0 for o in out for v in o["offset"]),
        "max_matrix": max(abs(v) for o in out for row in o["matrix"] for v in row),
    }
    return out, feats


QUADRIC_KEYS = "ABCDEFGHIJ"


def quadric(r: random.Random, kind: str) -> dict:
    """Coefficients A..J (eq. 3) of KIND; full has every one, cross terms B, C, F included."""
    if kind == "none":
        return {}
    if kind == "linear":         # marble-like: a ramp along a random direction
        d = [r.uniform(-1, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in d)) or 1.0
        g = r.uniform(0.3, 1.5) / n
        return {"D": d[0] * g / 2, "G": d[1] * g / 2, "I": d[2] * g / 2, "J": r.uniform(-1, 1)}
    if kind == "radial":         # wood-like: rings about an axis
        k = r.uniform(1.0, 3.5)
        return {"A": k, "E": k * r.uniform(0.7, 1.3)}
    q = {c: r.uniform(-1.0, 1.0) for c in QUADRIC_KEYS}
    for c in "BCF":             # cross terms clearly non-zero
        q[c] = math.copysign(r.uniform(0.2, 1.0), q[c])
    scale = r.uniform(0.6, 2.5)
    return {c: v * scale for c, v in q.items()}


def colormap(r: random.Random, wrap: str, interp: str) -> dict:
    keys = r.randint(2, 8)
    pos = sorted(r.random() for _ in range(keys - 2))
    pos = [0.0] + pos + [1.0]
    ramp = [[p] + [r.random() for _ in range(3)] for p in pos]
    if wrap == "mod" and r.random() < 0.5:
        ramp[-1][1:] = ramp[0][1:]     # seamless, like the paper's mod maps
    return {"size": 256, "wrap": wrap, "interp": interp, "ramp": ramp}


def camera_and_object(r: random.Random, mesh: str) -> tuple:
    """Camera (eye, target, fovy) and the object's table (mesh parameters, placement, texture space)."""
    obj = {"mesh": mesh}
    if mesh == "plane":
        hs = r.uniform(2.0, 6.0)
        obj.update(half_size=hs, divisions=4)
        elev = r.uniform(8.0, 40.0)              # low: the plane runs to the horizon
        dist = r.uniform(2.0, 4.0)
        target = [0.0, 0.0, 0.0]
        tex_scale = r.uniform(0.6, 10.0 / hs)
    else:
        if mesh == "teapot":
            obj["subdiv"] = 3
        elif mesh == "sphere":
            obj.update(slices=24, stacks=12)
        elif mesh == "torus":
            obj.update(major_radius=1.0, minor_radius=0.4, segments=24)
        obj["rotate"] = [r.uniform(-30, 30), r.uniform(0, 360), r.uniform(-30, 30)]
        elev = r.uniform(-20.0, 50.0)
        dist = r.uniform(3.0, 5.5)
        target = [0.0, 0.0, 0.0]
        tex_scale = r.uniform(0.5, 2.5)
    az = r.uniform(0, 2 * math.pi)
    e = math.radians(elev)
    eye = [dist * math.cos(e) * math.sin(az), dist * math.sin(e), dist * math.cos(e) * math.cos(az)]
    obj["tex_scale"] = tex_scale
    obj["tex_rotate"] = [r.uniform(0, 360) for _ in range(3)]
    obj["tex_offset"] = [r.uniform(-3, 3) for _ in range(3)]
    return {"eye": eye, "target": target, "fovy": r.uniform(35.0, 50.0)}, obj


def scene_toml(header: list, size: int, background, cam: dict, quad: dict, filt: str, cmap: dict, octs: list,
               obj: dict) -> str:
    """The TOML text of a one-texture, one-object scene: HEADER (comment and title lines), a SIZE x
    SIZE image, the camera (eye, target, fovy; near when given), texture "t" and the object."""
    tex = "t"
    lines = [*header, "",
             "[image]", f"width = {size}", f"height = {size}", f"background = {_vec(background)}", "",
             "[camera]", f"eye = {_vec(cam['eye'])}", f"target = {_vec(cam['target'])}", f"fovy = {_num(cam['fovy'])}"]
    if "near" in cam:
        lines.append(f"near = {_num(cam['near'])}")
    lines += ["", f"[textures.{tex}]"]
    if quad:
        lines.append("quadric = { " + ", ".join(f"{k} = {_num(v)}" for k, v in quad.items()) + " }")
    lines.append(f'filter = "{filt}"')
    ramp = ",\n".join("  " + _vec(k) for k in cmap["ramp"])
    lines.append(f'colormap = {{ size = {cmap["size"]}, wrap = "{cmap["wrap"]}", interp = "{cmap["interp"]}", '
                 f'ramp = [\n{ramp} ] }}')
    for o in octs:
        lines += ["", f"[[textures.{tex}.octaves]]", f"amplitude = {_num(o['amplitude'])}",
                  "matrix = [" + ", ".join(_vec(row) for row in o["matrix"]) + "]",
                  f"offset = {_vec(o['offset'])}"]
    lines += ["", "[[objects]]", f'mesh = "{obj["mesh"]}"', f'texture = "{tex}"']
    for k, v in obj.items():
        if k == "mesh":
            continue
        if isinstance(v, list):
            lines.append(f"{k} = {_vec(v)}")
        elif isinstance(v, int):
            lines.append(f"{k} = {v}")
        else:
            lines.append(f"{k} = {_num(v)}")
    return "\n".join(lines) + "\n"


def scene(seed: int, set_name: str, index: int) -> tuple:
    """(file name, TOML text, features) of scene INDEX of set SET_NAME (SEED a training seed)."""
    check_training_seed(seed)
    pick = lambda feat, vals: _stratum(seed, set_name, feat, vals, index)   # noqa: E731
    count = pick("octaves", OCTAVE_COUNTS)
    mkind = pick("matrix", MATRIX_KINDS)
    if step_sensitive(set_name, index):
        filt = _stratum(seed, set_name, "step_filter", STEP_FILTERS, index // 4)
        wrap, interp = "mod", "step"
    else:       # the other scenes walk the strata without gaps (training: 3 of every 4 scenes)
        j = index - index // 4 if set_name == "train" else index
        filt = _stratum(seed, set_name, "filter", FILTERS, j)
        wrap = _stratum(seed, set_name, "wrap", WRAPS, j)
        interp = _stratum(seed, set_name, "interp", INTERPS, j)
    qkind = pick("quadric", QUADRIC_KINDS)
    mesh = pick("mesh", MESHES)
    r = _rng(seed, set_name, "scene", index)
    octs, ofeat = octaves(r, count, mkind)
    quad = quadric(r, qkind)
    cmap = colormap(r, wrap, interp)
    cam, obj = camera_and_object(r, mesh)
    name = f"{set_name}_{index:03d}"
    header = [f"# Random scene {name} (scripts/gen_scenes.py, seed {seed}): {count} octave(s), {mkind} matrices,",
              f"# {qkind} quadric, {interp} colour map ({wrap}), filter {filt}, mesh {mesh}.",
              f'title = "random {name} (seed {seed})"']
    text = scene_toml(header, 512, [r.uniform(0, 0.25) for _ in range(3)], cam, quad, filt, cmap, octs, obj)
    feats = dict(ofeat, name=name, set=set_name, filter=filt, wrap=wrap, interp=interp, quadric=qkind,
                 cross_terms=qkind == "full", mesh=mesh, ramp_keys=len(cmap["ramp"]),
                 step_sensitive=step_sensitive(set_name, index))
    return f"{name}.toml", text, feats


def generate(seed: int, counts: dict) -> dict:
    """Set name -> list of (file name, text, features), COUNTS: set name -> number of scenes."""
    return {s: [scene(seed, s, i) for i in range(n)] for s, n in counts.items()}


def write(out, seed: int, counts: dict) -> dict:
    """Writes OUT/<set>/<name>.toml and OUT/manifest.json; returns the manifest."""
    from .. import atomic
    sets = generate(seed, counts)
    manifest = {"seed": seed, "generator": "scripts/gen_scenes.py", "sets": {}}
    for s, scenes in sets.items():
        d = out / s
        d.mkdir(parents=True, exist_ok=True)
        for old in d.glob(f"{s}_*.toml"):          # a smaller set replaces a larger one
            if old.name not in {f for f, _, _ in scenes}:
                old.unlink()
        for fname, text, _ in scenes:
            atomic.write_if_changed(d / fname, text)
        manifest["sets"][s] = [feats for _, _, feats in scenes]
    atomic.write_text(out / "manifest.json", json.dumps(manifest, indent=1) + "\n")
    return manifest

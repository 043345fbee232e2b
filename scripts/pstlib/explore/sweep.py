"""The sweep strategy: one knob at a time around a base profile. The knobs (one profile change
each), the points' profiles and the scene copies they render."""
import copy
import pathlib
import re
import tomllib

from .. import atomic, tomledit
from ..contract import ENUMS, RANGES, validate
from .point import Point, text_key

DEFAULT_SCENES = ["wood_teapot", "marble", "seascape", "fire", "planet", "zoneplate"]
QUICK = {"base": "reduced", "knobs": "coord_frac,octaves,hash", "scenes": "marble,zoneplate", "size": 64,
         "truth": 2, "rtl_subset": 0, "values": ["coord_frac=8,10,16", "octaves=2,8"]}


# ----------------------------------------------------------------------------------------------
# Knobs: name -> (what it changes, default values, apply(doc, value) -> None, base(doc) -> value)

def _set_format_frac(*names):
    def apply(doc, v):
        for n in names:
            doc["formats"][n]["frac"] = v
    return apply


def _apply_octaves(doc, v):
    pipe = doc["pipeline"]
    units = pipe["noise_units"]
    if units == pipe["octaves"]:
        units = v                      # one pass per pixel stays one pass per pixel
    else:
        units = max(d for d in range(1, units + 1) if v % d == 0)   # the most units <= the base's
    pipe["octaves"] = v
    pipe["noise_units"] = units


def _apply_key(section, key):
    def apply(doc, v):
        doc[section][key] = v
    return apply


def _get(section, key):
    return lambda d: d[section][key]


def _knob(desc, values, section, key):
    return (desc, values, _apply_key(section, key), _get(section, key))


# The noise unit's basis: its interp / corner / hash triple (rtl/contract.toml allows
# perlin2002's only whole), or a worley unit (noise.worley_search, the perm256 cube hash).
# rayshade sets the paper's triple; worley the octant search (worley_points, worley_order as
# the base has them).
BASIS_NOISE = {"rayshade": {"interp": "scurve", "corner": "value_gradient", "hash": "rayshade",
                            "worley_search": "none"},
               "perlin2002": {"interp": "quintic", "corner": "grad12", "hash": "perlin256",
                              "worley_search": "none"},
               "worley": {"interp": "linear", "corner": "value", "hash": "perm256",
                          "worley_search": "octant"}}


def basis_of(doc: dict) -> str:
    """The basis a profile's noise unit computes (the golden model's hardwareBasis and
    Profile::noise.basis)."""
    if doc["noise"].get("worley_search", "none") != "none":
        return "worley"
    return "perlin2002" if doc["noise"]["corner"] == "grad12" else "rayshade"


def worley_keys(doc: dict) -> dict:
    """The texture noise keys of the variant a profile's worley unit computes."""
    n = doc["noise"]
    return {"basis": "worley", "search": n["worley_search"], "max_points": n["worley_points"],
            "cubes": "rom256"}


def _apply_basis(doc, v):
    doc["noise"].update(BASIS_NOISE[v])


def _format_frac(d, *names):
    """The common fraction of several formats, None when they differ."""
    fr = {d["formats"][n]["frac"] for n in names}
    return fr.pop() if len(fr) == 1 else None


KNOBS = {
    "coord_frac": ("formats.coord.frac", [6, 8, 10, 12, 14, 16, 20],
                   _set_format_frac("coord"), lambda d: _format_frac(d, "coord")),
    "jacobian_frac": ("formats.jacobian.frac", [8, 10, 12, 16, 24],
                      _set_format_frac("jacobian"), lambda d: _format_frac(d, "jacobian")),
    "noise_value_frac": _knob("noise.value_frac", [4, 5, 7, 9, 11, 15], "noise", "value_frac"),
    "lattice_frac": _knob("noise.lattice_frac", [4, 6, 8, 10, 12, 16], "noise", "lattice_frac"),
    "out_frac": _knob("noise.out_frac (noise value / weight-product bits)", [6, 8, 10, 12, 16],
                      "noise", "out_frac"),
    "guard_bits": _knob("noise.guard_bits (noise node fraction bits below out_frac)", [1, 2, 3, 4, 6],
                        "noise", "guard_bits"),
    "noise_grad_frac": _knob("noise.grad_frac (the noise unit's derivative lanes, the noise gradient only; "
                             ">= out_frac + guard_bits keeps every node bit)", [8, 10, 12, 14, 16, 20],
                             "noise", "grad_frac"),
    "amp_frac": ("formats.amplitude.frac = grad_matrix.frac = matrix.frac", [6, 8, 10, 12, 16],
                 _set_format_frac("amplitude", "grad_matrix", "matrix"),
                 lambda d: _format_frac(d, "amplitude", "grad_matrix", "matrix")),
    "colour_bits": _knob("pipeline.colour_bits", [5, 6, 7, 8], "pipeline", "colour_bits"),
    "octaves": ("pipeline.octaves (noise_units: all of them if the base has one pass, else the "
                "largest divisor)", [1, 2, 3, 4, 6, 8], _apply_octaves, _get("pipeline", "octaves")),
    "interp": _knob("noise.interp", ENUMS[("noise", "interp")], "noise", "interp"),
    "hash": _knob("noise.hash", ENUMS[("noise", "hash")], "noise", "hash"),
    "corner": _knob("noise.corner", ENUMS[("noise", "corner")], "noise", "corner"),
    "norm": _knob("filter.norm", ENUMS[("filter", "norm")], "filter", "norm"),
    "datapath": _knob("pipeline.datapath (gates and cycles only: the images are the same bit for bit)",
                      ENUMS[("pipeline", "datapath")], "pipeline", "datapath"),
    "noise_steps": _knob("pipeline.noise_steps (gates and cycles only: the images are the same bit for bit)",
                         list(RANGES[("pipeline", "noise_steps")]), "pipeline", "noise_steps"),
    "basis": ("noise.interp / corner / hash / worley_search of the noise unit's basis (rayshade: the "
              "paper's scurve, value_gradient, rayshade; perlin2002: quintic, grad12, perlin256; worley: "
              "a worley unit, octant search, perm256 cube hash); the scene copies' textures ask for it "
              "(worley: F1 unless a texture has coefficients)", list(BASIS_NOISE), _apply_basis, basis_of),
    "filter": ("every texture's filter (scene copies; not a profile key)", ["none", "mip", "mip_linear", "sat"],
               None, lambda d: None),
}


def parse_values(spec: str):
    """(knob, values) of a --values KNOB=V1,V2 argument; ValueError saying what is wrong."""
    m = re.fullmatch(r"(\w+)=([\w,]+)", spec.strip())
    if not m or m.group(1) not in KNOBS:
        raise ValueError(f"expected KNOB=V1,V2,... with a known knob, got {spec!r}")
    k = m.group(1)
    known = KNOBS[k][1]
    vals = []
    for v in m.group(2).split(","):
        if isinstance(known[0], int):
            if not v.isdigit():
                raise ValueError(f"{k} takes integers, got {v!r}")
            vals.append(int(v))
        else:
            if v not in known:
                raise ValueError(f"{k} takes {', '.join(known)}, got {v!r}")
            vals.append(v)
    return k, vals


# ----------------------------------------------------------------------------------------------
# Points

def ident(s: str) -> str:
    """S as a C identifier (the name of a point, a profile, a verilated model)."""
    s = re.sub(r"[^A-Za-z0-9_]", "_", s)
    return s if re.match(r"[A-Za-z_]", s) else "p_" + s


def point_name(base: str, knob: str, value) -> str:
    return ident(f"{base}_{knob}_{value}")


def point_profile(base_doc: dict, knob: str, value):
    """The base profile with one knob set (a new document) and what it violates (empty: valid)."""
    doc = copy.deepcopy(base_doc)
    KNOBS[knob][2](doc, value)
    return doc, validate(doc)


def set_texture_keys(text: str, keys: dict) -> str:
    """The scene with KEYS (name -> value) set in every [textures.NAME] table."""
    names = tomllib.loads(text).get("textures", {})
    return tomledit.set_values(text, {("textures", t, k): v for t in names for k, v in keys.items()})


def variant_keys(doc: dict) -> dict:
    """The texture keys that make the reference use a profile's noise variant and |grad| norm
    (perlin2002's variant is its basis: the scenes name the basis, not the triple)."""
    n = doc["noise"]
    if basis_of(doc) == "worley":
        return {"noise": worley_keys(doc), "norm": doc["filter"]["norm"]}
    if basis_of(doc) != "rayshade":
        return {"noise": {"basis": basis_of(doc)}, "norm": doc["filter"]["norm"]}
    return {"noise": {"interp": n["interp"], "corner": n["corner"], "hash": n["hash"]},
            "norm": doc["filter"]["norm"]}


def basis_keys(doc: dict) -> dict:
    """The texture keys a profile needs of any scene: its basis, unless the default rayshade
    (a profile runs only textures of its own basis)."""
    b = basis_of(doc)
    if b == "worley":
        return {"noise": worley_keys(doc)}
    return {} if b == "rayshade" else {"noise": {"basis": b}}


def point_scenes(scene_files: dict, pdir: pathlib.Path, name: str, keys: dict):
    """Scene copies with texture keys set (points/<name>/<scene>.toml), or the scenes themselves;
    and the copies' text (it is part of the point's content hash)."""
    if not keys:
        return dict(scene_files), ""
    files, texts = {}, []
    for s, f in scene_files.items():
        text = set_texture_keys(f.read_text(), keys)
        p = pdir / name / f"{s}.toml"
        atomic.write_if_changed(p, text)
        files[s] = p
        texts.append(text)
    return files, "".join(texts)


def base_values(base_doc: dict, scene_files: dict) -> dict:
    """Each knob's value in the base (None: none, or several, like the scenes' filters)."""
    values = {k: KNOBS[k][3](base_doc) for k in KNOBS}
    kinds = {t.get("filter", "sat") for f in scene_files.values()
             for t in tomllib.loads(f.read_text()).get("textures", {}).values()}
    values["filter"] = kinds.pop() if len(kinds) == 1 else None
    return values


def make_points(s, out: pathlib.Path):
    """The base point, the knob points, the skipped values (knob, value, why) and the base's
    knob values. S: the sweep's settings (sweep_run.SweepSettings: base_path, base_doc, base_name, knob_list,
    value_lists, scene_files, match_variant). Writes points/<name>.toml (and the scene copies)
    where they changed."""
    points, skipped = [], []
    pdir = out / "points"
    base_text = s.base_path.read_text()
    base_keys = variant_keys(s.base_doc) if s.match_variant else basis_keys(s.base_doc)
    try:
        files, extra = point_scenes(s.scene_files, pdir, s.base_name, base_keys)
    except (ValueError, KeyError, tomllib.TOMLDecodeError) as e:
        raise SystemExit(f"error: --match-variant: {e}")
    base = Point(s.base_name, s.base_doc, base_text, text_key(base_text + extra), s.base_path, "base", "base", "-",
                 files, s.base_name, True)
    bvalues = base_values(s.base_doc, s.scene_files)
    for k in s.knob_list:
        desc = KNOBS[k][0]
        for v in s.value_lists[k]:
            name = point_name(s.base_name, k, v)
            if v == bvalues[k]:
                continue
            if k == "filter":
                path, text, synth_name, doc = s.base_path, base_text, s.base_name, s.base_doc
                keys = dict(base_keys, filter=v)
            else:
                doc, bad = point_profile(s.base_doc, k, v)
                if bad:
                    skipped.append((k, v, "; ".join(bad)))
                    continue
                change = f"{k} = {v} ({desc})"
                if k == "octaves":
                    change += f"; noise_units = {doc['pipeline']['noise_units']}"
                body = tomledit.without_leading_comment(base_text)
                text = tomledit.with_comment(
                    "\n" + tomledit.set_values(body, tomledit.changes_between(s.base_doc, doc)),
                    f"Sweep point {name}: profile {s.base_name} ({s.base_path.name}) with\n{change}.\n"
                    f"Written by scripts/sweep.py; see {s.base_path.name} for the keys.")
                path = pdir / f"{name}.toml"
                atomic.write_if_changed(path, text)
                synth_name = name
                keys = variant_keys(doc) if s.match_variant else basis_keys(doc)
                if k == "basis" and not keys:
                    keys = {"noise": {"basis": v}}
            try:
                files, extra = point_scenes(s.scene_files, pdir, name, keys)
            except (ValueError, KeyError, tomllib.TOMLDecodeError) as e:
                skipped.append((k, v, f"scene copies: {e}"))
                continue
            points.append(Point(name, doc, text, text_key(text + extra), path, f"{k} = {v}", k, v, files, synth_name))
    return base, points, skipped, bvalues

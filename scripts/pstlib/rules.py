"""The hardware profile's rules as the scripts check them: what model/golden/profile.cpp and the
RTL's assertions would reject. (To be replaced by pstlib.contract, generated from the one
description of the hardware contract.)"""

ENUMS = {("pipeline", "datapath"): ["parallel", "serial"], ("noise", "interp"): ["scurve", "linear"],
         ("noise", "corner"): ["value_gradient", "value"], ("noise", "hash"): ["rayshade", "perm256"],
         ("filter", "norm"): ["euclid", "max_half_min", "l1"]}
FORMAT_MAX = {"coord": 40, "jacobian": 40, "matrix": 32, "offset": 32, "amplitude": 32, "grad_matrix": 32,
              "quadric": 32, "f": 48, "grad": 48}


def validate(doc: dict) -> list:
    """What model/golden/profile.cpp and the RTL's assertions would reject (empty: valid)."""
    bad = []

    def rng(sec, key, lo, hi):
        v = doc.get(sec, {}).get(key)
        if not isinstance(v, int) or not lo <= v <= hi:
            bad.append(f"{sec}.{key} = {v} outside [{lo}, {hi}]")
    for key, lo, hi in [("octaves", 1, 16), ("noise_units", 1, 16), ("log2_clut", 1, 11), ("colour_bits", 1, 8)]:
        rng("pipeline", key, lo, hi)
    for key, lo, hi in [("value_frac", 1, 15), ("lattice_frac", 1, 20), ("out_frac", 1, 24), ("guard_bits", 1, 8)]:
        rng("noise", key, lo, hi)
    rng("filter", "recip_frac", 4, 24)
    rng("formats", "width_frac", 0, 24)
    for (sec, key), choices in ENUMS.items():
        if doc.get(sec, {}).get(key) not in choices:
            bad.append(f"{sec}.{key} not one of {', '.join(choices)}")
    p = doc.get("pipeline", {})
    if not bad and p["octaves"] % p["noise_units"]:
        bad.append("pipeline.noise_units must divide pipeline.octaves")
    if p.get("noise_steps") not in (1, 2, 4, 8):
        bad.append("pipeline.noise_steps must be 1, 2, 4 or 8")
    elif p.get("datapath") == "serial" and p["noise_steps"] < 4:
        bad.append("pipeline.datapath = serial needs pipeline.noise_steps >= 4")
    fm = doc.get("formats", {})
    for name, mx in FORMAT_MAX.items():
        f = fm.get(name, {})
        i, fr = f.get("int"), f.get("frac")
        if not isinstance(i, int) or not isinstance(fr, int) or not 1 <= i <= 62 or not 0 <= fr <= 62:
            bad.append(f"formats.{name} must have int in [1, 62] and frac in [0, 62]")
        elif i + fr > mx:
            bad.append(f"formats.{name}: int + frac = {i + fr} > {mx}")
    if not bad:
        acc = fm["matrix"]["frac"] + fm["coord"]["frac"]
        if acc < doc["noise"]["lattice_frac"]:
            bad.append(f"matrix.frac + coord.frac = {acc} < noise.lattice_frac (pst_octave_transform)")
        if acc < fm["offset"]["frac"]:
            bad.append(f"matrix.frac + coord.frac = {acc} < offset.frac (pst_octave_transform)")
        if p["log2_clut"] - 1 + fm["width_frac"] < 1:
            bad.append("log2_clut - 1 + width_frac must be >= 1 (pst_clut_filter)")
    return bad

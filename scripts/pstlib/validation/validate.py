"""Profiles judged on the held-out validation set (scripts/validate.py): every scene of
valset.py rendered through the golden model of each profile and of full_exact, PSNR against the
double reference, and the rule of acceptance.py against full_exact scene by scene.

Outputs (OUT, default out/validate): scenes/ (the set, manifest.json), renders/SCENE/PROFILE/
(`pst render` outputs: golden.png, reference.png, difference.png, summary.json),
validate.json and validate.md (per profile: worst and median PSNR, worst loss against
full_exact and that scene's features, the worst scene by PSNR, per-stratum worst loss,
pass/fail)."""
import concurrent.futures
import json
import pathlib
import statistics
import time

from . import acceptance, valset
from .. import atomic
from ..explore.results import psnr as summary_psnr
from ..fmt import tail
from ..paths import CONFIGS, profile_path
from ..procs import run as run_cmd

REFERENCE = "full_exact"


def known_profiles() -> list:
    return sorted(p.stem for p in CONFIGS.glob("*.toml"))


def resolve_profiles(names: list) -> list:
    """[(name, path)]: full_exact first (the rule's reference), then each profile named once, a
    name (rtl/configs/NAME.toml) or a .toml file. ValueError for an unknown one."""
    out = {}
    for n in [REFERENCE, *names]:
        p = profile_path(n)
        if not p.is_file():
            raise ValueError(f"unknown profile {n!r} (known: {', '.join(known_profiles())}, or a .toml file)")
        name = p.stem
        if name in out and out[name].resolve() != p.resolve():
            raise ValueError(f"two profiles named {name!r}: {out[name]} and {p}")
        out[name] = p
    return list(out.items())


def render_scene(pst: str, scene: pathlib.Path, profiles: list, size: int, rdir: pathlib.Path) -> dict:
    """Profile name -> PSNR (dB, capped at 100) of its golden render against the reference on one
    scene (one `pst render`: the reference is drawn once); RuntimeError on a failed render."""
    cmd = [pst, "render", str(scene), "--model", "golden", "--size", str(size), "-o", str(rdir), "-q", "-j", "1"]
    for _, p in profiles:
        cmd += ["--profile", str(p)]
    rc, so, se = run_cmd(cmd)
    out = {}
    for name, _ in profiles:
        sj = (rdir if len(profiles) == 1 else rdir / name) / "summary.json"
        if rc != 0 or not sj.exists():
            raise RuntimeError(f"pst render {scene.stem} exited {rc}:\n{tail(se or so)}")
        out[name] = summary_psnr(json.loads(sj.read_text()).get("vs_reference"))
    return out


def judge_profiles(psnrs: dict, features: dict, tolerance: float = acceptance.TOLERANCE_DB) -> dict:
    """PSNRS: scene -> profile -> dB. Profile -> summary: worst and median PSNR, the verdict of the
    rule against full_exact (acceptance.judge) with the worst scene's features, worst loss per
    stratum."""
    ref = {s: v[REFERENCE] for s, v in psnrs.items()}
    names = list(next(iter(psnrs.values())))
    out = {}
    for n in names:
        got = {s: v[n] for s, v in psnrs.items()}
        vals = [x for x in got.values() if x is not None]
        v = acceptance.judge(ref, got, tolerance, features)
        losses = acceptance.scene_losses(ref, got)
        strata = {}
        for s, loss in losses.items():
            st = features[s]["stratum"]
            if st not in strata or loss > strata[st]["worst_loss"]:
                strata[st] = {"worst_loss": loss, "scene": s}
        out[n] = dict(v, worst_psnr=min(vals) if vals else None, median_psnr=statistics.median(vals) if vals else None,
                      median_loss=statistics.median(losses.values()) if losses else None,
                      failing_count=len(v["failing"]), strata=dict(sorted(strata.items())))
    return out


def run(profile_names: list, count: int, size: int, seed: int, out: pathlib.Path, pst: str, jobs: int = 1,
        say=print, split: valset.Split = valset.HOLDOUT) -> int:
    """Renders the set through every profile, writes validate.json and validate.md; exit status 0
    (every named profile passes), 1 (one fails the rule, or a render failed). Bad input
    (ValueError) is raised before anything is written."""
    profiles = resolve_profiles(profile_names)
    valset.check(seed, count, size, split)   # before anything is written
    t0 = time.time()
    sdir = out / "scenes"
    manifest = valset.write(sdir, seed, count, size, split)
    features = {f["name"]: f for f in manifest["scenes"]}
    say(f"validate: {count} {split.name} scenes (seed {seed}) at {size} x {size}, profiles {', '.join(n for n, _ in profiles)} "
        f"-> {out}")

    def one(name):
        return name, render_scene(pst, sdir / f"{name}.toml", profiles, size, out / "renders" / name)

    psnrs, errors = {}, []
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as ex:
        for fut in concurrent.futures.as_completed([ex.submit(one, n) for n in features]):
            try:
                name, p = fut.result()
                psnrs[name] = p
            except RuntimeError as e:
                errors.append(str(e))
            done = len(psnrs) + len(errors)
            if done % 16 == 0 and done < len(features):
                say(f"  {done}/{len(features)} scenes rendered ({time.time() - t0:.0f} s)")
    if errors:
        say("FAILED: " + errors[0])
        return 1
    psnrs = dict(sorted(psnrs.items()))
    wall = time.time() - t0
    res = judge_profiles(psnrs, features)
    doc = {"seed": seed, "count": count, "size": size, "split": split.name, "reference": REFERENCE, "tolerance_db": acceptance.TOLERANCE_DB,
           "wall_s": round(wall, 1), "jobs": jobs, "profiles": {n: str(p) for n, p in profiles},
           "command": command(profile_names, count, size, seed, split),
           "results": res, "psnr": psnrs, "features": features}
    atomic.write_text(out / "validate.json", json.dumps(doc, indent=1) + "\n")
    atomic.write_text(out / "validate.md", markdown(doc))
    for n, r in res.items():
        say(f"  {n}: worst {r['worst_psnr']:.2f} dB, median {r['median_psnr']:.2f} dB, worst loss vs {REFERENCE} "
            f"{r['worst_loss']:+.2f} dB ({r['worst_loss_scene']}), {'PASS' if r['passed'] else 'FAIL'}")
    say(f"wrote {out / 'validate.md'} and validate.json ({wall:.0f} s)")
    return 0 if all(r["passed"] for r in res.values()) else 1


def command(profile_names, count, size, seed, split=valset.HOLDOUT) -> str:
    return (f"scripts/validate.py {' '.join(map(str, profile_names))}{' --train' if split is valset.TRAINING else ''}"
            f" --count {count} --size {size} --seed {seed}")


def _f(v, fmt="{:.2f}"):
    if v is None:
        return "-"
    t = fmt.format(v)
    return t[1:] if t.startswith("-") and not t.strip("-0.") else t      # no "-0.00"


def markdown(doc: dict) -> str:
    res, feats = doc["results"], doc["features"]
    held = doc.get("split", valset.HOLDOUT.name) == valset.HOLDOUT.name
    L = [f"# {'Validation' if held else 'Training strata'}: {doc['count']} {'held-out' if held else 'training'} scenes at {doc['size']} x {doc['size']} (seed {doc['seed']})\n",
         f"`{doc['command']}`, {doc['wall_s']:.0f} s wall ({doc['jobs']} job(s)). Golden model of each profile "
         f"against the double reference (PSNR, dB); the rule (scripts/pstlib/validation/acceptance.py): every scene "
         f"within {doc['tolerance_db']:g} dB of {doc['reference']}'s PSNR on the same scene. Scenes: "
         "scripts/pstlib/validation/valset.py (eight strata, " + ("seeds apart from training" if held else
                                                       "training seeds: for choosing, not for judging") + ").\n",
         f"| profile | worst dB | median dB | worst loss vs {doc['reference']} dB | scenes over "
         f"{doc['tolerance_db']:g} dB | worst-loss scene | its features | rule |",
         "|---|---:|---:|---:|---:|---|---|---|"]
    for n, r in res.items():
        s = r["worst_loss_scene"]
        L.append(f"| {n} | {_f(r['worst_psnr'])} | {_f(r['median_psnr'])} | {_f(r['worst_loss'])} | "
                 f"{r['failing_count']} / {r['scenes']} | {s} ({_f(r['worst_loss_psnr'])} vs "
                 f"{_f(r['worst_loss_ref_psnr'])}) | {valset.describe(feats[s])} | "
                 f"{'pass' if r['passed'] else '**FAIL**'} |")
    L.append("")
    L.append("Worst scene by PSNR: " + "; ".join(
        f"{n} {r['worst_psnr_scene']} {_f(r['worst_psnr'])} dB ({valset.describe(feats[r['worst_psnr_scene']])})"
        for n, r in res.items()) + ".\n")
    strata = sorted({st for r in res.values() for st in r["strata"]})
    L.append(f"Worst loss against {doc['reference']} per stratum, dB (scene):\n")
    L.append("| profile | " + " | ".join(strata) + " |")
    L.append("|---|" + "---:|" * len(strata))
    for n, r in res.items():
        L.append(f"| {n} | " + " | ".join(
            f"{_f(r['strata'][st]['worst_loss'])} ({r['strata'][st]['scene']})" if st in r["strata"] else "-"
            for st in strata) + " |")
    L.append("")
    L.append("Every scene, PSNR dB:\n")
    names = list(res)
    L.append("| scene | features | " + " | ".join(names) + " |")
    L.append("|---|---|" + "---:|" * len(names))
    for s, v in doc["psnr"].items():
        L.append(f"| {s} | {valset.describe(feats[s])} | " + " | ".join(_f(v[n]) for n in names) + " |")
    return "\n".join(L) + "\n"

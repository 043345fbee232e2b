"""The rule of acceptance for any format cut, search point or profile, in one place.

A candidate is judged scene by scene against a reference profile on the same scenes (full_exact
for a named profile, the class's start profile in the search): each scene's PSNR of the golden
render against the double reference, and the candidate passes when on EVERY scene it loses at
most TOLERANCE_DB against the reference's PSNR there. The worst case (the scene that loses
most) is what is reported, with its features.

It replaces "every validation texture >= 45 dB or within 3 dB of full" (the rule balanced was
accepted by) and the search's "validation worst no more than 3 dB under training worst" flag:
a worst-scene or an absolute floor lets a cut spoil a texture whose own PSNR is high (a step map
losing 15 dB to 50 dB passed), and a set-wide worst hides which scene moved.
"""
import math

TOLERANCE_DB = 1.0


def scene_losses(ref: dict, got: dict, missing=math.inf) -> dict:
    """Scene -> dB lost by GOT (scene -> PSNR) against REF on every scene REF scored; a scene GOT
    lacks (or has as None) counts as MISSING dB (None: left out)."""
    out = {}
    for s, p0 in ref.items():
        if p0 is None:
            continue
        v = got.get(s)
        loss = p0 - v if v is not None else missing
        if loss is not None:
            out[s] = loss
    return out


def scene_loss(ref: dict, got: dict, missing=math.inf):
    """The largest loss, dB, of GOT against REF on any one scene (0.0 when there is none; with
    MISSING None, None when no scene is left)."""
    losses = scene_losses(ref, got, missing)
    if missing is None:
        return max(losses.values()) if losses else None
    return max(losses.values(), default=0.0)


def passes(loss, tolerance: float = TOLERANCE_DB) -> bool:
    """One scene's loss within the tolerance (a loss of exactly TOLERANCE passes)."""
    return loss is not None and loss <= tolerance


def judge(ref: dict, got: dict, tolerance: float = TOLERANCE_DB, features: dict | None = None) -> dict:
    """The verdict on GOT (scene -> PSNR) against REF (scene -> PSNR): passed (every scene of REF
    within TOLERANCE dB; a missing scene fails), the worst scene by loss and by PSNR, the failing
    scenes (worst first), and FEATURES (scene -> dict) of the worst ones when given."""
    losses = scene_losses(ref, got)
    if not losses:
        return {"passed": None, "tolerance_db": tolerance, "scenes": 0, "worst_loss": None, "worst_loss_scene": None,
                "failing": []}
    order = sorted(losses)          # ties: the first scene by name
    worst = max(order, key=lambda s: losses[s])
    scored = {s: got[s] for s in order if got.get(s) is not None}
    low = min(scored, key=lambda s: scored[s]) if scored else None
    failing = sorted((s for s, v in losses.items() if not passes(v, tolerance)), key=lambda s: -losses[s])
    out = {"passed": not failing, "tolerance_db": tolerance, "scenes": len(losses),
           "worst_loss": losses[worst], "worst_loss_scene": worst,
           "worst_loss_psnr": got.get(worst), "worst_loss_ref_psnr": ref[worst],
           "worst_psnr": scored.get(low), "worst_psnr_scene": low, "failing": failing}
    if features is not None:
        out["worst_loss_features"] = features.get(worst)
        out["worst_psnr_features"] = features.get(low)
    return out

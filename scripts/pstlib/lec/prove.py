"""ABC on one miter (yosys-abc, the ABC Yosys ships): `iprove` for a combinational miter (SAT
sweeping with fraiging, which decides the multipliers a plain SAT call times out on) and
`dprove` for a sequential one (the designs from all-zero flip-flops, induction). Results:
"proven", "differs" (ABC found an input sequence with a different output), "undecided" (ABC
ended without a verdict) or "timeout"."""
import re
import subprocess
import time

ABC = "yosys-abc"


def prove(aig, sequential: bool, timeout: float, abc: str = ABC) -> tuple:
    """(result, seconds, ABC's last line) for the miter in AIG."""
    cmd = f"read {aig}; strash; {'dprove' if sequential else 'iprove'}"
    t0 = time.time()
    try:
        r = subprocess.run([abc, "-c", cmd], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout", time.time() - t0, f"no verdict in {timeout:g} s"
    text = r.stdout + r.stderr
    lines = [l.strip() for l in text.splitlines() if l.strip()]
    last = lines[-1] if lines else ""
    if re.search(r"\bUNSATISFIABLE\b|Networks are equivalent|Property proved|proved", text):
        verdict = "proven"
    elif re.search(r"\bSATISFIABLE\b|NOT EQUIVALENT|not equivalent|Networks are NOT|Output .* asserted|falsified|CEX",
                   text, re.I):
        verdict = "differs"
    else:
        verdict = "undecided"
    return verdict, time.time() - t0, last

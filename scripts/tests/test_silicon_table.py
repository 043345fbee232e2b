"""The README's silicon table is the one scripts/silicon_table.py generates from the committed
baseline and derate (a change of either regenerates it in the same commit)."""
import subprocess

from pstlib import silicon_table
from pstlib.paths import PY, ROOT


def test_readme_table_is_generated():
    r = subprocess.run([PY, str(ROOT / "scripts" / "silicon_table.py"), "--check"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def profile(**kw):
    p = {"profile": "x", "logic_ge": 1000, "memory_ge": 500, "total_ge": 1500, "flip_flops": 10, "fmax_mhz": 100.0,
         "signoff_sdc": True, "post_route_mhz": None, "derate": None, "clocks_per_pixel": 2,
         "worst_psnr": ("planet", 41.04), "worst_path": None, "paper_gates": None}
    p.update(kw)
    return p


def test_clock_is_post_route_else_derated_else_pre_layout():
    rows = {r[0]: r[1:] for r in silicon_table.rows([profile(), profile(derate=0.9), profile(post_route_mhz=80.0, derate=0.9)])}
    assert rows["Fmax post-route, or pre-layout x derate"] == ["100.0 MHz (pre-layout)", "90.0 MHz (derated x 0.900)",
                                                              "80.0 MHz (post-route)"]
    assert rows["Mpixel/s at that clock"] == ["50.00", "45.00", "40.00"]
    assert rows["meets 36.9 Mpixel/s"] == ["yes", "yes", "yes"]
    assert rows["logic GE x clocks per pixel"] == ["2,000"] * 3
    assert rows["worst paper scene"] == ["planet 41.0 dB"] * 3

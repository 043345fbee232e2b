"""pstlib.validation.coverage: Verilator .dat points read and summarised (line, user, toggle)."""
from pstlib.validation import coverage


def dat(tmp_path, rows):
    p = tmp_path / "c.dat"
    lines = ["# SystemC::Coverage-3"]
    for keys, n in rows:
        lines.append("C '" + "".join(f"\x01{k}\x02{v}" for k, v in keys.items()) + f"' {n}")
    p.write_text("\n".join(lines) + "\n")
    return p


def test_line_user_toggle(tmp_path):
    p = dat(tmp_path, [
        (dict(f="rtl/a.sv", l=7, page="v_line/a", o="block", S="7-9", h="TOP.a"), 3),
        (dict(f="rtl/a.sv", l=12, page="v_line/a", o="block", S="12", h="TOP.a"), 0),
        (dict(f="rtl/a.sv", l=12, page="v_line/a", o="block", S="12", h="TOP.b"), 0),
        (dict(f="rtl/a.sv", l=20, page="v_branch/a", o="if", S="20", h="TOP.a"), 1),
        (dict(f="rtl/a.sv", l=30, page="v_user/a", o="Hit", h="TOP.a.Hit"), 4),
        (dict(f="rtl/a.sv", l=31, page="v_user/a", o="Miss", h="TOP.a.Miss"), 0),
        (dict(f="rtl/a.sv", l=2, page="v_toggle/a", o="x[0]", h="TOP.a"), 2),
        (dict(f="rtl/a.sv", l=2, page="v_toggle/a", o="x[1]", h="TOP.a"), 0),
        (dict(f="/usr/share/verilator/x.v", l=1, page="v_line/x", o="block", S="1", h="TOP.x"), 0),
    ])
    pts = coverage.read_points(p)
    assert len(pts) == 9
    lc = coverage.line_coverage(pts, lambda f: "rtl/" in f)
    assert lc == {"rtl/a.sv": (4, 5, [12])}     # 7, 8, 9, 20 hit; 12 never
    assert coverage.user_points(pts) == [("TOP.a.Hit", "rtl/a.sv:30", 4), ("TOP.a.Miss", "rtl/a.sv:31", 0)]
    assert coverage.toggle_coverage(pts, lambda f: "rtl/" in f) == {"rtl/a.sv": (1, 2)}
    text, lines, users = coverage.report(p)
    assert lines == (4, 5) and users == (1, 2)
    assert "`TOP.a.Miss` (rtl/a.sv:31)" in text

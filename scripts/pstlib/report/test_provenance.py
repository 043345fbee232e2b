"""pstlib.report.provenance: commit (dirty flag, outside git), tool versions, command line, schema."""
import re
import subprocess

from pstlib.report import provenance


def test_fields_present():
    p = provenance.collect(schema=3, argv=["scripts/report.py", "out", "--md", "a b.md"])
    assert p["schema"] == 3
    assert set(p["tools"]) == {"verilator", "yosys", "opensta", "python"}
    assert all(isinstance(v, str) and v for v in p["tools"].values())
    assert p["tools"]["python"].startswith("Python 3.")
    assert p["command"] == "scripts/report.py out --md 'a b.md'"
    assert re.fullmatch(r"[0-9a-f]{40}(-dirty)?|unknown", p["commit"])
    line = provenance.line(p)
    assert p["commit"] in line and "schema 3" in line and "yosys" in line


def test_commit_outside_git_is_unknown(tmp_path):
    assert provenance.commit(tmp_path) == "unknown"


def test_commit_dirty_flag(tmp_path):
    def git(*a):
        subprocess.run(["git", "-C", str(tmp_path), *a], check=True, capture_output=True)
    git("init", "-q")
    (tmp_path / "f").write_text("1")
    git("add", "f")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "x")
    head = subprocess.run(["git", "-C", str(tmp_path), "rev-parse", "HEAD"], capture_output=True,
                          text=True).stdout.strip()
    assert provenance.commit(tmp_path) == head
    (tmp_path / "f").write_text("2")
    assert provenance.commit(tmp_path) == head + "-dirty"


def test_missing_tool_is_not_found(monkeypatch):
    provenance.tool_versions.cache_clear()
    monkeypatch.setitem(provenance.TOOLS, "yosys", ["/nonexistent/yosys", "-V"])
    try:
        assert provenance.tool_versions()["yosys"] == provenance.NOT_FOUND
    finally:
        provenance.tool_versions.cache_clear()

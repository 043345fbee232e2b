import os

import pytest

from pstlib import atomic


def test_write_text_creates_folders_and_leaves_no_temporary(tmp_path):
    p = tmp_path / "a" / "b" / "x.json"
    atomic.write_text(p, "one\n")
    assert p.read_text() == "one\n"
    assert sorted(os.listdir(p.parent)) == ["x.json"]


def test_failed_write_keeps_the_old_file_and_removes_the_temporary(tmp_path):
    p = tmp_path / "x.png"
    p.write_text("old")

    def half_then_fail(tmp):
        assert tmp.parent == p.parent and tmp.suffix == ".png" and tmp.name != p.name
        tmp.write_text("half")
        raise RuntimeError("disk full")
    with pytest.raises(RuntimeError):
        atomic.write_with(p, half_then_fail)
    assert p.read_text() == "old"
    assert os.listdir(tmp_path) == ["x.png"]


def test_write_if_changed_keeps_mtime_of_same_text(tmp_path):
    p = tmp_path / "p.toml"
    assert atomic.write_if_changed(p, "a = 1\n")
    os.utime(p, (1000, 1000))
    assert not atomic.write_if_changed(p, "a = 1\n")
    assert p.stat().st_mtime == 1000
    assert atomic.write_if_changed(p, "a = 2\n")
    assert p.read_text() == "a = 2\n" and p.stat().st_mtime != 1000

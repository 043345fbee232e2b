"""The result store and its one reuse rule (pstlib.explore.store), and the sweep's settings
(pstlib.explore.sweep_run.settings) refusing bad values with the flag's name."""
import sys

import pytest

from pstlib.explore import store, sweep_run

OK = {"profile_sha": "k", "size": 32, "status": "ok", "train": {"a": 40.0, "b": 41.0}, "logic_ge": 5}


def never(r):
    raise AssertionError("not asked")


def test_put_then_get_and_missing_or_broken_files(tmp_path):
    s = store.Store(tmp_path)
    assert s.get("p") is None
    s.put("p", {"x": 1})
    assert s.get("p") == {"x": 1} and s.path("p") == tmp_path / "results" / "p.json"
    s.path("q").write_text("{")
    assert s.get("q") is None


def test_the_reuse_rule():
    same = {"size": 32}
    scenes = {"train": ["a", "b"]}
    assert store.reusable(OK, "k", same, scenes, False, lambda r: False)
    assert not store.reusable(None, "k", same, scenes, False, never)
    assert not store.reusable(OK, "other", same, scenes, False, never)
    assert not store.reusable(OK, "k", {"size": 64}, scenes, False, never)
    assert not store.reusable(OK, "k", same, {"train": ["a", "c"]}, False, never)
    assert not store.reusable(OK, "k", same, scenes, False, lambda r: True)          # area missing
    failed = {"profile_sha": "k", "size": 32, "status": "failed"}
    assert store.reusable(failed, "k", same, scenes, False, never)                    # kept ...
    assert not store.reusable(failed, "k", same, scenes, True, never)                 # ... unless retried


@pytest.mark.parametrize("kw, flag", [({"size": 0}, "--size"), ({"truth": 65}, "--truth"), ({"jobs": 0}, "--jobs"),
                                      ({"knobs": "nosuch"}, "--knobs"), ({"scenes": "nosuch"}, "--scenes"),
                                      ({"base": "nosuch"}, "--base"), ({"values": ["hash=nosuch"]}, "--values"),
                                      ({"pst": "/nonexistent/pst"}, "--pst")])
def test_sweep_settings_name_the_bad_flag(kw, flag):
    args = dict({"pst": sys.executable}, **kw)
    with pytest.raises(ValueError, match=f"^{flag}: "):
        sweep_run.settings(**args)


def test_sweep_settings_quick_defaults_and_explicit_values():
    s = sweep_run.settings(quick=True, size=32, pst=sys.executable)
    assert s.base_name == "reduced" and s.knob_list == ["coord_frac", "octaves", "hash"]
    assert s.scene_names == ["marble", "zoneplate"] and s.size == 32 and s.rtl_subset == 0
    assert s.value_lists["coord_frac"] == [8, 10, 16] and s.out.name == "reduced_quick"

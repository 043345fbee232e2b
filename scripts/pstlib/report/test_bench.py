from pstlib.report import bench

SCENE = {"profile": "full", "scene": "scenes/marble.toml", "width": 256, "height": 256, "fragments": 1000,
         "cycles": 1004, "seconds": {"rtl": 0.5, "golden": 0.01, "reference": 0.001},
         "assertions_verilated": False}
RANDOM = {"profile": "reduced", "seed": 1, "fragments": 2000, "cycles": 64000, "rtl_seconds": 0.02,
          "golden_seconds": 0.01, "seconds": 0.05}


def test_scene_row_rates_from_each_models_own_seconds():
    r = bench.scene_row(SCENE)
    assert r["rtl_pixels_per_s"] == 2000 and r["golden_pixels_per_s"] == 100000
    assert r["rtl_cycles_per_s"] == 2008 and r["rtl_over_golden"] == 0.02


def test_random_row_uses_rtl_and_golden_seconds_not_the_wall_clock():
    r = bench.random_row(RANDOM)
    assert r["rtl_cycles_per_s"] == 3.2e6 and r["rtl_pixels_per_s"] == 1e5 and r["golden_pixels_per_s"] == 2e5
    assert r["rtl_over_golden"] == 0.5


def test_table_gives_the_ratio_as_a_fraction_and_survives_a_zero_time():
    t = bench.table([bench.scene_row(SCENE), bench.random_row(dict(RANDOM, golden_seconds=0))])
    assert "| full | no | marble 256x256 | 2,008 | 2,000 | 100,000 | 1/50.0 |" in t
    assert "| reduced | ? | random 2000 seed 1 |" in t   # a record from before the field
    assert t.strip().endswith("| - |")


def test_profiles_from_the_list_output():
    assert bench.verilated_profiles("profile full\nprofile reduced\nsegment 0\n") == ["full", "reduced"]

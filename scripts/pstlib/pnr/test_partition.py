"""Tests of the block cut (pstlib/pnr/partition.py)."""
from pstlib.pnr import partition


def names(spec: dict) -> list:
    """{'u_a.u_b': 3} -> ['u_a.u_b._0_', 'u_a.u_b._1_', 'u_a.u_b._2_']."""
    return [f"{p}._{i}_" if p else f"_{i}_" for p, k in spec.items() for i in range(k)]


def test_parent_and_counts():
    assert partition.parent("u_a.g[0].u_b._3_") == "u_a.g[0].u_b"
    assert partition.parent("_3_") == ""
    n = partition.subtree_counts(names({"u_a": 2, "u_a.u_b": 3, "": 1}))
    assert n[""] == 6 and n["u_a"] == 5 and n["u_a.u_b"] == 3


def test_small_instances_stay_in_top_and_large_ones_are_cut():
    cells = names({"u_big": 10, "u_big.u_x": 30, "u_big.u_y": 5, "u_mid": 20, "u_tiny": 3, "": 4})
    blocks = partition.choose(cells, limit=25, min_cells=10)
    # u_big has 45 cells > 25: its largest child (30) is pulled out, the rest (15) stays.
    assert blocks == ["u_big", "u_big.u_x", "u_mid"]
    parts = partition.assign(cells, blocks)
    assert {k: len(v) for k, v in parts.items()} == {"u_big": 15, "u_big_u_x": 30, "u_mid": 20, "top": 7}


def test_every_cell_in_exactly_one_block():
    cells = names({"u_a": 40, "u_a.g[0].u_n": 60, "u_a.g[0].u_n.u_m": 50, "u_b": 12, "": 2})
    blocks = partition.choose(cells, limit=55, min_cells=5)
    # u_n keeps its own 60 cells (more than the limit: a module is not split); the generate
    # scope u_a.g[0] holds no cell of its own and is no block.
    assert blocks == ["u_a", "u_a.g[0].u_n", "u_a.g[0].u_n.u_m", "u_b"]
    parts = partition.assign(cells, blocks)
    assert sorted(c for v in parts.values() for c in v) == sorted(cells)
    assert {k: len(v) for k, v in parts.items()} == {"u_a": 40, "u_a_g_0_u_n": 60, "u_a_g_0_u_n_u_m": 50,
                                                     "u_b": 12, "top": 2}


def test_block_name():
    assert partition.block_name("u_octave.g_noise[0].g_lattice.u_noise") == "u_octave_g_noise_0_g_lattice_u_noise"

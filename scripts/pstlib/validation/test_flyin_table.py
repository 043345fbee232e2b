

def test_inputs_key_follows_binary_and_profiles(tmp_path):
    """A run is reused only while the pst binary and the profile files are the same."""
    import os
    from pstlib.validation import flyin_table
    pst = tmp_path / "pst"
    pst.write_bytes(b"binary one")
    k1 = flyin_table.inputs_key(pst, ["reduced_worley", "full"])
    assert "reduced_worley.toml:" in k1 and "missing" not in k1     # a test profile is found too
    pst.write_bytes(b"binary two")
    os.utime(pst, ns=(1, 1))
    assert flyin_table.inputs_key(pst, ["reduced_worley", "full"]) != k1

"""The commands of scripts/*.py: each scripts/NAME.py is a thin wrapper calling pstlib.cli.NAME.main
(argument parsing, then the library). scripts/synth.py and scripts/profile.py are not here: the
silicon baseline digests them as they are (pstlib/synth/inputs.py, record.py)."""

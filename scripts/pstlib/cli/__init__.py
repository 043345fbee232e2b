"""The commands of scripts/*.py: each scripts/NAME.py is a thin wrapper calling pstlib.cli.NAME.main
(argument parsing, then the library). scripts/synth.py, scripts/profile.py and scripts/mul_proof.py are
not here: the silicon baseline and the multiplier proof digest them as they are."""

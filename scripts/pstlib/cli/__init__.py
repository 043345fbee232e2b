"""The commands of scripts/*.py: each scripts/NAME.py is a thin wrapper calling pstlib.cli.NAME.main
(argument parsing, then the library). scripts/synth.py and scripts/profile.py are not here: the
silicon baseline digests them as they are (pstlib/synth/inputs.py, record.py)."""
import os


def check_pst(pst) -> None:
    """--pst, the built tool a command runs: ValueError (for argparse's error) unless executable."""
    if not os.access(pst, os.X_OK):
        raise ValueError(f"--pst: {pst}: not an executable (cmake --build build --target pst)")

"""The commands of scripts/*.py: each scripts/NAME.py is a thin wrapper calling pstlib.cli.NAME.main
(argument parsing, then the library). scripts/synth.py and scripts/profile.py are not here: the
silicon baseline digests them as they are (pstlib/synth/inputs.py, record.py)."""
import os


def check_pst(a) -> None:
    """--pst (a.pst), the built tool a command runs unless it only writes its scenes (a.scenes_only):
    ValueError (for argparse's error) when it is not an executable."""
    if not a.scenes_only and not os.access(a.pst, os.X_OK):
        raise ValueError(f"--pst: {a.pst}: not an executable (cmake --build build --target pst)")

"""pytest setup: pstlib is imported from scripts/ (the scripts run with scripts/ on sys.path)."""
import pathlib
import sys

SCRIPTS = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(SCRIPTS))
from pstlib.paths import ROOT  # noqa: E402,F401  (the tests' `from conftest import ROOT`)

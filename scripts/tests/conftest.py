"""pytest setup: pstlib is imported from scripts/ (the scripts run with scripts/ on sys.path)."""
import pathlib
import sys

SCRIPTS = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(SCRIPTS))
ROOT = SCRIPTS.parent

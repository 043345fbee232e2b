#!/usr/bin/python3
"""Random textures and scenes for judging profiles on textures they were not tuned on.

The command's code: pstlib/cli/gen_scenes.py (`python3 -m pstlib.cli.gen_scenes` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.gen_scenes import main

if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Turns a hardware profile (rtl/configs/NAME.toml) into SystemVerilog top-level parameters.

A thin CLI over pstlib.contract: the profile schema (keys, ranges, enums, cross-constraints)
and the parameter-naming rule live in rtl/contract.toml; the profile is checked against it
before anything is printed. Enumerations become their index (pst_pkg's localparams).

  profile.py PROFILE.toml --verilator   one -GName=value per line
  profile.py PROFILE.toml --yosys       chparam -set Name value ... (one line per parameter)
  profile.py PROFILE.toml --list        Name value per line
  ... --only Name1,Name2                 restrict the output to these parameters (a unit-test
                                         top that declares only some of them)
"""
import sys

from pstlib import contract

FORMATS = {"--verilator": "-G{}={}", "--yosys": "chparam -set {} {}", "--list": "{} {}"}


def main() -> int:
    args = sys.argv[1:]
    only = None
    if len(args) == 4 and args[2] == "--only":
        only = set(args[3].split(","))
        args = args[:2]
    if len(args) != 2 or args[1] not in FORMATS:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        params = contract.parameters(contract.read_profile(args[0]))
    except contract.ProfileError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if only is not None:
        unknown = only - {n for n, _ in params}
        if unknown:
            print(f"error: {args[0]}: --only names unknown parameters: {', '.join(sorted(unknown))}", file=sys.stderr)
            return 2
        params = [(n, v) for n, v in params if n in only]
    for name, value in params:
        print(FORMATS[args[1]].format(name, value))
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Turns a hardware profile (rtl/configs/NAME.toml) into SystemVerilog top-level parameters.

The profile is the one place where the hardware's widths live; the C++ golden model reads the
same file (model/golden/profile.cpp). Parameter names follow one rule:
  [pipeline] key        -> UpperCamel(key)                 octaves -> Octaves
  [noise] key           -> "Noise" + UpperCamel(key)       out_frac -> NoiseOutFrac
  [filter] key          -> "Filter" + UpperCamel(key)      norm -> FilterNorm
  [formats] name.int    -> UpperCamel(name) + "Int"        coord.int -> CoordInt
  [formats] name_frac   -> UpperCamel(name_frac)           width_frac -> WidthFrac
Enumerations become their index in ENUMS (the order of the C++ enums in model/*.h).

  profile.py PROFILE.toml --verilator   one -GName=value per line
  profile.py PROFILE.toml --yosys       chparam -set Name value ... (one line per parameter)
  profile.py PROFILE.toml --list        Name value per line
  ... --only Name1,Name2                 restrict the output to these parameters (a unit-test
                                         top that declares only some of them)
"""
import sys
import tomllib

ENUMS = {
    ("pipeline", "datapath"): ["parallel", "serial"],
    ("noise", "interp"): ["scurve", "linear"],
    ("noise", "corner"): ["value_gradient", "value"],
    ("noise", "hash"): ["rayshade", "perm256"],
    ("filter", "norm"): ["euclid", "max_half_min", "l1"],
}
PREFIX = {"pipeline": "", "noise": "Noise", "filter": "Filter"}


def camel(key: str) -> str:
    return "".join(part[:1].upper() + part[1:] for part in key.split("_"))


def fail(path: str, field: str, what: str) -> None:
    print(f"error: {path}: {field}: {what}", file=sys.stderr)
    sys.exit(2)


def parameters(path: str) -> list[tuple[str, int]]:
    try:
        with open(path, "rb") as f:
            doc = tomllib.load(f)
    except OSError as e:
        fail(path, "file", str(e))
    except tomllib.TOMLDecodeError as e:
        fail(path, "syntax", str(e))
    out = []
    for section, prefix in PREFIX.items():
        for key, value in doc.get(section, {}).items():
            if (section, key) in ENUMS:
                choices = ENUMS[(section, key)]
                if value not in choices:
                    fail(path, f"{section}.{key}", f"unknown value {value!r} (expected {', '.join(choices)})")
                value = choices.index(value)
            if not isinstance(value, int) or isinstance(value, bool) or value < 0:
                fail(path, f"{section}.{key}", "expected a non-negative integer")
            out.append((prefix + camel(key), value))
    for name, value in doc.get("formats", {}).items():
        if isinstance(value, dict):
            for part in ("int", "frac"):
                v = value.get(part)
                if not isinstance(v, int) or v < 0:
                    fail(path, f"formats.{name}.{part}", "expected a non-negative integer")
                out.append((camel(name) + camel(part), v))
        else:
            if not isinstance(value, int) or value < 0:
                fail(path, f"formats.{name}", "expected a non-negative integer")
            out.append((camel(name), value))
    return out


def main() -> int:
    args = sys.argv[1:]
    only = None
    if len(args) == 4 and args[2] == "--only":
        only = set(args[3].split(","))
        args = args[:2]
    if len(args) != 2 or args[1] not in ("--verilator", "--yosys", "--list"):
        print(__doc__, file=sys.stderr)
        return 2
    params = parameters(args[0])
    if only is not None:
        unknown = only - {n for n, _ in params}
        if unknown:
            print(f"error: {args[0]}: --only names unknown parameters: {', '.join(sorted(unknown))}", file=sys.stderr)
            return 2
        params = [(n, v) for n, v in params if n in only]
    for name, value in params:
        if args[1] == "--verilator":
            print(f"-G{name}={value}")
        elif args[1] == "--yosys":
            print(f"chparam -set {name} {value}")
        else:
            print(f"{name} {value}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

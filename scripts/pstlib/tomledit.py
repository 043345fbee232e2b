"""The one way the scripts change a TOML file (a hardware profile, a scene): set values by their
key path in the text, keeping its comments, order and layout, and check the result by parsing it.

    set_values(text, {("formats", "coord", "frac"): 8, ("noise", "hash"): "perm256"})

A path names a key of a [table] (("noise", "hash")), or a key inside an inline table written on
the key's line (("formats", "coord", "frac") in `coord = { int = 12, frac = 20 }`: the inline
table is written again, its line's comment kept). A key missing from an existing table is added
under the table's header. What this cannot do (a value over several lines, a dotted key, a table
that does not exist) raises ValueError: the result is always parsed and compared with the
document the changes should give.
"""
import copy
import json
import re
import tomllib

HEADER = re.compile(r"\s*\[\s*([A-Za-z0-9_\-]+(?:\s*\.\s*[A-Za-z0-9_\-]+)*)\s*\]\s*(#.*)?$")
KEY = re.compile(r"(\s*)([A-Za-z0-9_\-]+)(\s*=\s*)(.*)$")


def value_text(v) -> str:
    """TOML text of a value: booleans, integers, strings and inline tables of them."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {value_text(x)}" for k, x in v.items()) + " }"
    raise ValueError(f"cannot write {v!r} to TOML")


def split_value(rest: str):
    """(value text, what follows it: spaces and comment) of the text after `key =`; None when no
    prefix of the line is one whole value (a value continued on the next lines)."""
    for cut in [m.start() for m in re.finditer("#", rest)] + [len(rest)]:
        v = rest[:cut].rstrip()
        try:
            tomllib.loads(f"x = {v}")
        except tomllib.TOMLDecodeError:
            continue
        return v, rest[len(v):]
    return None


def set_path(doc: dict, path: tuple, value) -> None:
    for i, k in enumerate(path[:-1]):
        doc = doc.setdefault(k, {})
        if not isinstance(doc, dict):
            raise ValueError(f"{'.'.join(path)}: {'.'.join(path[:i + 1])} is not a table")
    doc[path[-1]] = value


def set_values(text: str, changes: dict) -> str:
    """TEXT with every CHANGES path (a tuple of keys) set to its value; ValueError if it cannot."""
    try:
        want = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ValueError(f"not TOML: {e}") from None
    for path, v in changes.items():
        set_path(want, tuple(path), copy.deepcopy(v))
    todo = {tuple(p): v for p, v in changes.items()}
    lines = text.splitlines()
    out, headers = [], {}
    section = ()
    for line in lines:
        h = HEADER.match(line)
        if h:
            section = tuple(part.strip() for part in h.group(1).split("."))
            headers[section] = len(out)
            out.append(line)
            continue
        if re.match(r"\s*\[", line):
            section = None                      # [[array of tables]]: not edited
            out.append(line)
            continue
        m = KEY.match(line)
        mine = section is not None and m and {p: v for p, v in todo.items()
                                              if p[:len(section) + 1] == section + (m.group(2),)}
        if not mine:
            out.append(line)
            continue
        parts = split_value(m.group(4))
        if parts is None:
            raise ValueError(f"{'.'.join(section + (m.group(2),))}: a value over several lines")
        value = tomllib.loads(f"x = {parts[0]}")["x"]
        for p, v in mine.items():
            sub = p[len(section) + 1:]
            if not sub:
                value = copy.deepcopy(v)
            elif isinstance(value, dict):
                set_path(value, sub, copy.deepcopy(v))
            else:
                raise ValueError(f"{'.'.join(p)}: {'.'.join(p[:len(section) + 1])} is not a table")
            del todo[p]
        out.append(f"{m.group(1)}{m.group(2)}{m.group(3)}{value_text(value)}{parts[1]}")
    # Keys not found: under their table's header (the last key of the path), in the given order.
    added = {}
    for p, v in todo.items():
        if p[:-1] not in headers:
            raise ValueError(f"{'.'.join(p)}: no table [{'.'.join(p[:-1])}]")
        added.setdefault(headers[p[:-1]], []).append(f"{p[-1]} = {value_text(v)}")
    for at in sorted(added, reverse=True):
        out[at + 1:at + 1] = added[at]
    new = "\n".join(out) + "\n"
    try:
        got = tomllib.loads(new)
    except tomllib.TOMLDecodeError as e:
        raise ValueError(f"could not set {', '.join('.'.join(p) for p in changes)}: {e}") from None
    if got != want:
        raise ValueError(f"could not set {', '.join('.'.join(p) for p in changes)}")
    return new


def changes_between(old: dict, new: dict, path: tuple = ()) -> dict:
    """The leaf paths whose values differ from OLD to NEW (keys of NEW; a key only in OLD is an
    error: set_values cannot remove keys)."""
    gone = set(old) - set(new)
    if gone:
        raise ValueError(f"cannot remove {', '.join('.'.join(path + (k,)) for k in sorted(gone))}")
    out = {}
    for k, v in new.items():
        if isinstance(v, dict) and isinstance(old.get(k), dict):
            out.update(changes_between(old[k], v, path + (k,)))
        elif k not in old or old[k] != v or type(old[k]) is not type(v):
            out[path + (k,)] = v
    return out


def without_leading_comment(text: str) -> str:
    """TEXT without the comment lines (and blank lines) before its first key or table."""
    lines = text.splitlines(keepends=True)
    i = 0
    while i < len(lines) and (not lines[i].strip() or lines[i].lstrip().startswith("#")):
        i += 1
    return "".join(lines[i:])


def with_comment(text: str, comment: str) -> str:
    """TEXT under COMMENT's lines as # comments."""
    return "".join(f"# {line}\n" if line else "#\n" for line in comment.splitlines()) + text

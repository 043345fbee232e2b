"""Number formats of the tables and logs."""


def fnum(v, digits=2, none="-"):
    return none if v is None else f"{v:.{digits}f}"


def cnt(v):
    return "-" if v is None else f"{v:,}"


def kge(v):
    return "-" if v is None else f"{v / 1000:.1f}k"


def tail(text: str, n: int = 25) -> str:
    """The last N lines of a command's output."""
    return "\n".join((text or "").strip().splitlines()[-n:])

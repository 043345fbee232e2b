"""Atomic file writes: every output is written to a temporary name in its folder and renamed into
place, so a reader (or an interrupted run) never sees half a file."""
import os
import pathlib
import threading


def temp_name(path: pathlib.Path) -> pathlib.Path:
    """A hidden name beside PATH, unique per process and thread, with PATH's suffix (so a writer
    that picks the format from the name, like OpenImageIO, still sees .png)."""
    return path.with_name(f".{path.stem}.{os.getpid()}.{threading.get_ident()}.tmp{path.suffix}")


def write_with(path, write) -> None:
    """Calls write(tmp) to make the file under a temporary name, then renames it to PATH. The
    temporary file is removed when write raises."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temp_name(path)
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def write_text(path, text: str) -> None:
    write_with(path, lambda tmp: tmp.write_text(text))


def write_if_changed(path, text: str) -> bool:
    """Writes PATH unless it already holds TEXT (its mtime then stays: the synthesis cache compares
    it). True when it wrote."""
    path = pathlib.Path(path)
    if path.exists() and path.read_text() == text:
        return False
    write_text(path, text)
    return True

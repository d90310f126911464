"""What every file node shares: length units, where a relative path points, file errors.

Units are named as in the ``.graph`` file's ``"units"`` field: ``mm``, ``cm``, ``m``,
``in`` and ``ft`` (a few spelled-out synonyms are accepted). A relative path is taken
from the current working directory (where ``torsal run`` or the app was started), as a
shell would; ``~`` is expanded.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from engine.node import NodeError

#: Length of one unit in metres.
METRES: dict[str, float] = {"mm": 0.001, "cm": 0.01, "m": 1.0, "in": 0.0254, "ft": 0.3048}

_SYNONYMS = {
    "millimeter": "mm", "millimeters": "mm", "millimetre": "mm", "millimetres": "mm",
    "centimeter": "cm", "centimeters": "cm", "centimetre": "cm", "centimetres": "cm",
    "meter": "m", "meters": "m", "metre": "m", "metres": "m",
    "inch": "in", "inches": "in", '"': "in",
    "foot": "ft", "feet": "ft", "'": "ft",
}


class FileFailure(ValueError):
    """A file that cannot be read or written; the message is one plain sentence."""


def unit_name(text: str | None, what: str = "Units") -> str:
    """The canonical name (``mm``, ``cm``, ``m``, ``in``, ``ft``) of a unit, or FileFailure."""
    key = (text or "").strip().lower()
    key = _SYNONYMS.get(key, key)
    if key not in METRES:
        raise FileFailure(
            f"{what} {text!r} is not a length unit Torsal knows: use mm, cm, m, in or ft"
        )
    return key


def unit_scale(source: str, target: str) -> float:
    """The factor that turns lengths in ``source`` units into ``target`` units."""
    return METRES[unit_name(source)] / METRES[unit_name(target)]


def resolve(path: str | os.PathLike[str] | None, what: str = "Path") -> Path:
    """An absolute path: ``~`` expanded, a relative path taken from the working directory."""
    text = os.fspath(path).strip() if path is not None else ""
    if not text:
        raise FileFailure(f"{what} is empty: give a file name")
    return Path(os.path.abspath(os.path.expanduser(text)))


def readable(path: Path, kind: str) -> Path:
    """``path`` if it is a non-empty file, else a FileFailure saying what is wrong."""
    if not path.exists():
        raise FileFailure(f"There is no file {path}")
    if path.is_dir():
        raise FileFailure(f"{path} is a folder, not a {kind} file")
    if path.stat().st_size == 0:
        raise FileFailure(f"{path} is empty (0 bytes), so it holds no {kind} data")
    return path


def writable(path: Path) -> Path:
    """``path`` with its folder created, or a FileFailure (a folder in the way, no permission)."""
    if path.is_dir():
        raise FileFailure(f"{path} is a folder: give a file name")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise FileFailure(f"Cannot create the folder {path.parent}: {exc.strerror or exc}") from None
    return path


def numbered(path: Path, count: int) -> list[Path]:
    """``[path]`` for one file, else ``stem-1.ext`` … ``stem-N.ext`` beside it, the numbers
    zero-padded to the same width (``stem-01`` … ``stem-12``) so they sort."""
    if count <= 1:
        return [path]
    width = len(str(count))
    return [path.with_name(f"{path.stem}-{i:0{width}d}{path.suffix}") for i in range(1, count + 1)]


@contextmanager
def file_errors() -> Iterator[None]:
    """Turn a :class:`FileFailure` (or an OS error) into a :class:`~engine.node.NodeError`:
    a file that cannot be read or written puts the node in error with the reason."""
    try:
        yield
    except FileFailure as exc:
        raise NodeError(str(exc).rstrip(".")) from None
    except OSError as exc:
        where = f" {exc.filename}" if exc.filename else ""
        raise NodeError(f"Cannot use the file{where}: {exc.strerror or exc}") from None

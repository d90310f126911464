"""The example graphs that ship with Torsal, found through :mod:`importlib.resources`.

They live in the ``torsal.resources.examples`` package (``torsal/resources/examples/*.graph`` in a
checkout), so an installed wheel finds them as well as an editable install does.
``torsal examples`` lists them; ``torsal gui --example NAME`` opens one.
"""

from __future__ import annotations

import json
from importlib.resources import files
from pathlib import Path

from torsal.app.headless import UsageError

PACKAGE = "torsal.resources.examples"
#: What ``torsal gui`` opens when it is given no file.
DEFAULT = "kaohsiung-stadium"
SUFFIX = ".graph"


def names() -> list[str]:
    """The examples' names (file names without ``.graph``), sorted."""
    return sorted(
        entry.name[: -len(SUFFIX)] for entry in files(PACKAGE).iterdir()
        if entry.name.endswith(SUFFIX) and entry.is_file()
    )


def path(name: str) -> Path:
    """A file path for the example called ``name`` (``.graph`` optional).

    Raises :class:`UsageError` naming the examples there are when there is no such one.
    """
    stem = name[: -len(SUFFIX)] if name.endswith(SUFFIX) else name
    resource = files(PACKAGE) / f"{stem}{SUFFIX}"
    if not stem or "/" in stem or not resource.is_file():
        raise UsageError(f"there is no example {name!r}; the examples are: {', '.join(names())}")
    if isinstance(resource, Path):
        return resource
    # Not on the file system (e.g. imported from a zip): a copy in the user's private
    # scratch folder (never a shared /tmp path), written without following a link.
    from torsal.engine.write_path import scratch_folder, write_file

    scratch = scratch_folder()
    return write_file(scratch / "examples" / f"{stem}{SUFFIX}", resource.read_bytes(), base=scratch,
                      backup=False)


def choose(file: Path | None, example: str | None, command: str) -> Path:
    """The graph a command works on: its FILE argument or the example ``--example NAME`` names."""
    if file is not None and example is not None:
        raise UsageError("give either a FILE or --example NAME, not both")
    if file is None and example is None:
        raise UsageError(f"torsal {command} needs a FILE.graph or --example NAME (see torsal examples)")
    return file if file is not None else path(example or "")


def description(name: str) -> str:
    """The example's one-line description (its ``meta.description``), or ``""``."""
    try:
        meta = json.loads((files(PACKAGE) / f"{name}{SUFFIX}").read_text(encoding="utf-8")).get("meta", {})
    except (OSError, ValueError):
        return ""
    text = meta.get("description", "") if isinstance(meta, dict) else ""
    return text if isinstance(text, str) else ""

"""What every node that writes a file shares: the write rules and file errors.

A file a node *writes* must lie inside the graph's folder and needs the user's consent
(:mod:`torsal.engine.writes`): :func:`write_target` and :func:`may_write` are the two questions a
writing node asks. Every file written goes through the one write path
(:func:`replacing`, :mod:`torsal.engine.write_path`): atomically, never through a link,
the first write of a run keeping the user's original as ``<name>.bak``. The io palette's
file nodes, the display palette's Plot and the analysis palette's charts all write
through here.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from torsal.engine.node import Node
from torsal.engine.solve_context import active
from torsal.engine.write_path import Produce, write_file
from torsal.engine.writes import WriteAccess


class FileFailure(ValueError):
    """A file that cannot be read or written; the message is one plain sentence."""


def write_target(node: Node, path: object, what: str = "Path") -> Path:
    """The file ``node`` is asked to write, inside the graph's folder, or a NodeError that
    says why not (outside the folder, ``~``, an absolute path, a ``.graph`` file)."""
    return node.files.target(path, what)


def may_write(node: Node, paths: Sequence[Path]) -> bool:
    """Whether ``node`` may write ``paths`` now; if the user has not allowed this graph to
    write files, the node warns (naming the files) and the request waits for consent."""
    if node.files.permit(tuple(paths)):
        return True
    folder = node.files.folder
    names = ", ".join(_shown(p, folder) for p in paths)
    node.warn(
        f"Nothing written to {names}: this graph writes files only with your consent "
        "(torsal run or sweep --allow-writes; in the app, answer Allow when it asks)"
    )
    return False


def _shown(path: Path, folder: Path | None) -> str:
    try:
        return str(path.relative_to(os.path.realpath(folder))) if folder is not None else str(path)
    except ValueError:
        return str(path)


def replacing(path: Path, write: Produce) -> Path:
    """Write ``path`` through ``write`` (bytes, text, or a callable writing the file name it
    is given) and swap it in atomically (:func:`torsal.engine.write_path.write_file`).

    Inside a node's solve, a path in the graph's write folder is a node's export: the
    folders below the write folder are walked without following links, the file gets mode
    0644 (less the umask; never executable), and only the run's first write to it keeps
    the user's original as ``<name>.bak``. Any other path is the user's own choice of
    file (``--export``, Export…, Bake): its folder is created and resolved once, and the
    file it replaces is kept as ``.bak``. An OS error becomes a FileFailure naming ``path``.
    """
    try:
        base = _node_base(path)
        if base is not None:
            home, identity, access = base
            return write_file(path, write, base=home, identity=identity, backup=access.first_write(path))
        parent = Path(os.path.abspath(path)).parent
        try:
            parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise FileFailure(f"Cannot create the folder {parent}: {exc.strerror or exc}") from None
        return write_file(path, write)
    except OSError as exc:
        raise FileFailure(f"Cannot write {path}: {exc.strerror or exc}") from None


def _node_base(path: Path) -> tuple[Path, tuple[int, int] | None, WriteAccess] | None:
    """The write folder of the node being solved, if ``path`` lies in it."""
    context = active()
    files = context.files if context is not None else None
    if files is None or files.folder is None:
        return None
    found = files.access.base()
    if found is None:
        return None
    home, identity = found
    return (home, identity, files.access) if Path(os.path.abspath(path)).is_relative_to(home) else None


def writable(path: Path) -> Path:
    """``path``, or a FileFailure if a folder is in the way (the folders leading to it are
    made by the write itself, without following links)."""
    if path.is_dir():
        raise FileFailure(f"{path} is a folder: give a file name")
    return path

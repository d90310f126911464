"""Where a graph may write files: nowhere until the user consents, and only in its own folder.

A ``.graph`` file is data, and data must not be able to write ``~/.bashrc``. So a node
that writes files (the io palette's exporters) asks its :class:`NodeFiles` twice:

1. :meth:`NodeFiles.target` turns the node's Path into a file inside the *write folder*
   (the graph's own folder, or the folder given with ``torsal run --out``), or refuses
   it with a :class:`WriteRefused` naming the input: an absolute path, ``~``, a ``..``
   or a symlink that leads out of the folder, and any ``.graph`` file (a node never
   overwrites a graph, its own or another).
2. :meth:`NodeFiles.permit` says whether the user has allowed this document to write.
   Until they have (``torsal run --allow-writes``; in the app, a question asked once per
   document that lists the files), nothing is written: the request is recorded with the
   node's id and target paths, so that a front-end can ask and then solve those nodes
   again.

``--export`` on the command line and the app's Export… and Bake are the user's own
choice of file, made outside the graph, and do not go through here.

The check resolves symlinks as they are when the node runs; a folder swapped for a
symlink between the check and the write is outside what this guards against (the user
would have to be racing their own files).
"""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath, PureWindowsPath

from torsal.engine.errors import NodeError

#: File types a node may never write, whatever the folder (lower case).
PROTECTED_SUFFIXES = (".graph",)


class WriteRefused(NodeError):
    """A node's target path is outside what the graph may write (a plain sentence)."""


@dataclass(frozen=True)
class WriteRequest:
    """What one node wanted to write while writes were not allowed."""

    node_id: str
    paths: tuple[Path, ...]


@dataclass
class WriteAccess:
    """The write policy of one document or run.

    ``folder`` is the write folder (relative paths start there); ``None`` for a graph
    that has no file yet, which may write nothing. ``allowed`` is the user's consent.
    ``read_folder`` is where a file a node *reads* is looked for: the graph's own folder,
    which ``--out`` does not change (``None``: the write folder).
    """

    folder: Path | None = None
    allowed: bool = False
    requests: dict[str, WriteRequest] = field(default_factory=dict)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False, compare=False)
    read_folder: Path | None = None

    def for_node(self, node_id: str) -> NodeFiles:
        return NodeFiles(self, node_id)

    def pending(self) -> list[WriteRequest]:
        """The requests made while writes were not allowed, in the order they came."""
        with self._lock:
            return list(self.requests.values())

    def clear_requests(self) -> None:
        with self._lock:
            self.requests.clear()

    def _record(self, request: WriteRequest) -> None:
        with self._lock:
            self.requests[request.node_id] = request

    def _forget(self, node_id: str) -> None:
        with self._lock:
            self.requests.pop(node_id, None)


@dataclass(frozen=True)
class NodeFiles:
    """One node's view of its document's :class:`WriteAccess`."""

    access: WriteAccess
    node_id: str

    @property
    def folder(self) -> Path | None:
        return self.access.folder

    @property
    def read_folder(self) -> Path | None:
        """Where a relative path a node reads starts: the graph's folder, even with ``--out``."""
        access = self.access
        return access.read_folder if access.read_folder is not None else access.folder

    def target(self, text: object, what: str = "Path") -> Path:
        """The absolute file ``text`` names inside the write folder, or :class:`WriteRefused`.

        >>> files = WriteAccess(Path("/work/roof")).for_node("cut")
        >>> str(files.target("sheets/roof.dxf"))
        '/work/roof/sheets/roof.dxf'
        >>> try:
        ...     files.target("~/.bashrc")
        ... except WriteRefused as refusal:
        ...     print(str(refusal)[:51])
        Path '~/.bashrc' starts with ~: a graph writes only
        """
        raw = "" if text is None else os.fspath(text) if isinstance(text, os.PathLike) else str(text)
        name = raw.strip()
        if not name:
            raise WriteRefused(f"{what} is empty: give a file name, e.g. roof.dxf")
        folder = self.access.folder
        if folder is None:
            raise WriteRefused(
                f"{what} {name!r}: this graph has no folder yet, so it cannot write files; "
                "save it first (files are written next to the .graph file)"
            )
        hint = f"a graph writes only in its own folder ({folder}); give a path relative to it, " \
               "e.g. roof.dxf or out/roof.dxf"
        if name.startswith("~"):
            raise WriteRefused(f"{what} {name!r} starts with ~: {hint}")
        if PurePosixPath(name).is_absolute() or PureWindowsPath(name).drive or name.startswith("\\"):
            raise WriteRefused(f"{what} {name!r} is an absolute path: {hint}")
        if "\0" in name:
            raise WriteRefused(f"{what} {name!r} holds a NUL character, which no file name may")
        home = Path(os.path.realpath(folder))
        path = Path(os.path.realpath(home / name))
        if not path.is_relative_to(home) or path == home:
            raise WriteRefused(f"{what} {name!r} leads out of the graph's folder ({home}): {hint}")
        if path.name.lower().endswith(PROTECTED_SUFFIXES):
            raise WriteRefused(
                f"{what} {name!r} is a .graph file: a node never writes graphs; choose another name"
            )
        return path

    def permit(self, paths: list[Path] | tuple[Path, ...]) -> bool:
        """Whether the user allows this document to write; if not, the request is kept."""
        if self.access.allowed:
            self.access._forget(self.node_id)
            return True
        self.access._record(WriteRequest(self.node_id, tuple(paths)))
        return False

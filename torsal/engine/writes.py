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

Beyond the folder, a node never writes into a dot-folder (``.git/``, ``.hg/``, …) or a
dot-file (``.envrc``, ``.bashrc``), never onto a ``.bak`` (where a replaced file is kept),
never through a symlink inside the folder, and never on a path another node of the same
solve writes. The write itself (:mod:`torsal.engine.write_path`) holds the folder open by
descriptor, so a folder swapped for a symlink during the run is refused, not followed;
:meth:`WriteAccess.first_write` makes only the run's first write to a file keep the
user's original as ``.bak``. See ``docs/write-consent.md``.
"""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath, PureWindowsPath

from torsal.engine.errors import NodeError
from torsal.engine.write_path import folder_identity

#: File types a node may never write, whatever the folder (lower case).
PROTECTED_SUFFIXES = (".graph",)
#: Where a replaced file is kept: a node never writes such a name.
BACKUP_SUFFIXES = (".bak",)


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
    _identity: tuple[Path, tuple[int, int] | None] | None = field(default=None, repr=False, compare=False)
    _claims: dict[Path, str] = field(default_factory=dict, repr=False, compare=False)
    _claims_solve: object = field(default=None, repr=False, compare=False)
    _written: set[Path] = field(default_factory=set, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.base()  # the folder as it is when the run starts

    @classmethod
    def held(cls, folder: Path, identity: tuple[int, int], allowed: bool = False) -> WriteAccess:
        """An access to ``folder`` (a resolved path) known by its (device, inode) when the
        caller made it (:func:`torsal.engine.write_path.make_folders`)."""
        access = cls(None, allowed)
        access.folder = folder
        access._identity = (Path(os.path.abspath(folder)), identity)
        return access

    def base(self) -> tuple[Path, tuple[int, int] | None] | None:
        """The write folder resolved, with its (device, inode) as first seen: a folder
        swapped for another or a link later is refused by the write, not followed."""
        if self.folder is None:
            return None
        with self._lock:
            if self._identity is None or self._identity[0] != Path(os.path.abspath(self.folder)):
                home = Path(os.path.realpath(self.folder))
                self._identity = (Path(os.path.abspath(self.folder)), folder_identity(home))
            return Path(os.path.realpath(self._identity[0])), self._identity[1]

    def first_write(self, path: Path) -> bool:
        """Whether this is the run's first write to ``path`` (then the file it replaces, the
        user's original, is kept as ``.bak``; later writes of the run leave that ``.bak``)."""
        with self._lock:
            if path in self._written:
                return False
            self._written.add(path)
            return True

    def claim(self, node_id: str, paths: tuple[Path, ...], solve: object) -> None:
        """Record that ``node_id`` writes ``paths`` in the solve ``solve`` (its cancel token);
        :class:`WriteRefused` if another node of that solve writes one of them."""
        with self._lock:
            if solve is not self._claims_solve:
                self._claims_solve, self._claims = solve, {}
            for path in paths:
                other = self._claims.get(path)
                if other is not None and other != node_id:
                    raise WriteRefused(
                        f"{path.name} is also written by node {other!r} in this solve: two nodes never "
                        "write one file (the second would destroy the first's); give each its own Path"
                    )
            for path in paths:
                self._claims[path] = node_id

    def for_node(self, node_id: str, solve: object = None) -> NodeFiles:
        """The files of node ``node_id`` in the solve ``solve`` (its cancel token: what two
        nodes of one solve write is told apart from what the next solve writes)."""
        return NodeFiles(self, node_id, solve)

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
    solve: object = None

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
        if path != Path(os.path.normpath(home / name)):
            raise WriteRefused(f"{what} {name!r} leads through a symbolic link: a graph writes only into "
                               f"real files and folders inside {home}")
        if path.name.lower().endswith(PROTECTED_SUFFIXES):
            raise WriteRefused(
                f"{what} {name!r} is a .graph file: a node never writes graphs; choose another name"
            )
        if path.name.lower().endswith(BACKUP_SUFFIXES):
            raise WriteRefused(f"{what} {name!r} ends in .bak, where Torsal keeps the file a write "
                               "replaced: choose another name")
        hidden = [part for part in path.relative_to(home).parts if part.startswith(".")]
        if hidden:
            raise WriteRefused(f"{what} {name!r} is in or is a hidden (dot) file or folder ({hidden[0]}): "
                               "a graph never writes into .git, .hg or other dot-folders, nor dot-files")
        return path

    def permit(self, paths: list[Path] | tuple[Path, ...]) -> bool:
        """Whether the user allows this document to write; if not, the request is kept."""
        if self.access.allowed:
            self.access._forget(self.node_id)
            self.access.claim(self.node_id, tuple(paths), self.solve)
            return True
        self.access._record(WriteRequest(self.node_id, tuple(paths)))
        return False

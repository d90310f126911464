"""Data trees: what flows on a wire, as in Grasshopper.

A tree maps *paths* (tuples of non-negative integers, written ``{0;2}``) to *branches*
(lists of items), kept in path order. A plain value is the tree ``{0}: [value]``.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from typing import Any

Path = tuple[int, ...]


def format_path(path: Path) -> str:
    """``(0, 2)`` → ``'{0;2}'``."""
    return "{" + ";".join(str(i) for i in path) + "}"


def parse_path(text: str) -> Path:
    """``'{0;2}'`` → ``(0, 2)``; raises ``ValueError`` with a readable message."""
    body = text.strip()
    if not (body.startswith("{") and body.endswith("}")):
        raise ValueError(f"a path is written like {{0;1}}, not {text!r}")
    try:
        path = tuple(int(part) for part in body[1:-1].split(";"))
    except ValueError:
        raise ValueError(f"a path is written like {{0;1}}, not {text!r}") from None
    if not path or any(i < 0 for i in path):
        raise ValueError(f"a path needs non-negative indices: {text!r}")
    return path


class DataTree:
    """An ordered mapping from paths to lists of items."""

    __slots__ = ("_branches",)

    def __init__(self, branches: dict[Path, list[Any]] | None = None) -> None:
        self._branches: dict[Path, list[Any]] = {}
        if branches:
            for path in sorted(branches):
                self._branches[path] = list(branches[path])

    # -- construction -------------------------------------------------------------
    @classmethod
    def from_value(cls, value: Any) -> DataTree:
        """A single value becomes ``{0}: [value]``; a list becomes ``{0}: items``."""
        if isinstance(value, DataTree):
            return value
        tree = cls()
        tree._branches[(0,)] = list(value) if isinstance(value, list) else [value]
        return tree

    @classmethod
    def from_branches(cls, branches: Iterable[list[Any]], prefix: Path = ()) -> DataTree:
        """Branches numbered ``{prefix;0}``, ``{prefix;1}`` ... in order."""
        tree = cls()
        for i, items in enumerate(branches):
            tree._branches[(*prefix, i)] = list(items)
        return tree

    @classmethod
    def _sorted(cls, branches: dict[Path, list[Any]]) -> DataTree:
        tree = cls()
        tree._branches = dict(sorted(branches.items())) if len(branches) > 1 else branches
        return tree

    # -- access -------------------------------------------------------------------
    @property
    def paths(self) -> list[Path]:
        return list(self._branches)

    @property
    def branches(self) -> list[list[Any]]:
        return list(self._branches.values())

    def items(self) -> Iterator[tuple[Path, list[Any]]]:
        return iter(self._branches.items())

    def branch(self, path: Path) -> list[Any]:
        return self._branches[path]

    def all_items(self) -> list[Any]:
        """Every item, branch after branch in path order."""
        return [item for branch in self._branches.values() for item in branch]

    @property
    def branch_count(self) -> int:
        return len(self._branches)

    @property
    def item_count(self) -> int:
        return sum(len(b) for b in self._branches.values())

    def is_empty(self) -> bool:
        return not any(self._branches.values())

    def first(self) -> Any:
        """The first item of the first non-empty branch (``None`` if there is none)."""
        for branch in self._branches.values():
            if branch:
                return branch[0]
        return None

    def append(self, path: Path, item: Any) -> None:
        self._branches.setdefault(path, []).append(item)

    def extend(self, path: Path, items: Iterable[Any]) -> None:
        self._branches.setdefault(path, []).extend(items)

    def map(self, function: Callable[[Any], Any]) -> DataTree:
        """A tree of the same shape with ``function`` applied to every item."""
        return DataTree._sorted({p: [function(x) for x in b] for p, b in self._branches.items()})

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, DataTree):
            return NotImplemented
        return self._branches == other._branches

    def __len__(self) -> int:
        return len(self._branches)

    def __repr__(self) -> str:
        body = ", ".join(f"{format_path(p)}: {b!r}" for p, b in self._branches.items())
        return f"DataTree({body})"

    def to_dict(self) -> dict[str, list[Any]]:
        """``{'{0;1}': [...]}`` with the items as they are."""
        return {format_path(p): list(b) for p, b in self._branches.items()}

    # -- modifiers (Grasshopper's graft, flatten, simplify, reverse) -----------------------
    def grafted(self) -> DataTree:
        """Every item into its own branch: ``{p}:[a,b]`` → ``{p;0}:[a]``, ``{p;1}:[b]``.

        An empty branch stays an empty branch at ``{p}`` so no path is lost.
        """
        out: dict[Path, list[Any]] = {}
        for path, branch in self._branches.items():
            if not branch:
                out[path] = []
            for i, item in enumerate(branch):
                out[(*path, i)] = [item]
        return DataTree._sorted(out)

    def flattened(self) -> DataTree:
        """All items, in path order, into ``{0}``."""
        tree = DataTree()
        tree._branches[(0,)] = self.all_items()
        return tree

    def simplified(self) -> DataTree:
        """Remove the leading path indices that every path shares.

        At least one index is kept, so ``{0;0;3}`` alone becomes ``{3}``. Paths of
        different lengths are simplified over their common prefix only.
        """
        paths = list(self._branches)
        if not paths:
            return DataTree()
        shortest = min(len(p) for p in paths)
        shared = 0
        while shared < shortest - 1 and len({p[shared] for p in paths}) == 1:
            shared += 1
        if len(paths) == 1:
            shared = len(paths[0]) - 1
        return DataTree._sorted({p[shared:]: list(b) for p, b in self._branches.items()})

    def reversed(self) -> DataTree:
        """Reverse every branch's list."""
        return DataTree._sorted({p: b[::-1] for p, b in self._branches.items()})


MODIFIERS: dict[str, Callable[[DataTree], DataTree]] = {
    "graft": DataTree.grafted,
    "flatten": DataTree.flattened,
    "simplify": DataTree.simplified,
    "reverse": DataTree.reversed,
}


def apply_modifiers(tree: DataTree, modifiers: Iterable[str]) -> DataTree:
    """Apply input modifiers in the order given (unknown names raise ``KeyError``)."""
    for name in modifiers:
        tree = MODIFIERS[name](tree)
    return tree

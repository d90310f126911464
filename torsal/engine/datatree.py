"""Data trees: what flows on a wire, as in Grasshopper.

A tree maps *paths* (tuples of non-negative integers, written ``{0;2}``) to *branches*
(lists of items), kept in path order. A plain value is the tree ``{0}: [value]``. A branch
of numbers, integers or booleans may be stored as a numpy array (see :class:`DataTree`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from typing import Any

import numpy as np

Path = tuple[int, ...]


class Triples:
    """A branch of points or vectors held as one read-only ``(n, 3)`` float64 array.

    ``item_class`` (:class:`~torsal.engine.values.Point` or :class:`~torsal.engine.values.Vector`) is
    what an item is when the branch is read item by item (indexing, ``tolist``).
    """

    __slots__ = ("array", "item_class")

    def __init__(self, array: np.ndarray, item_class: type) -> None:
        array = np.asarray(array, dtype=np.float64)
        if array.ndim != 2 or array.shape[1] != 3:
            raise ValueError(f"points and vectors are held as an (n, 3) array, not {array.shape}")
        if array.flags.writeable:
            array = array.view()
            array.flags.writeable = False
        self.array = array
        self.item_class = item_class

    def __len__(self) -> int:
        return len(self.array)

    def __getitem__(self, index: Any) -> Any:
        """One row as a Point or Vector; a slice, or an array of indices or of booleans
        (as numpy takes them), as Triples of the rows picked."""
        if isinstance(index, slice | np.ndarray | list):
            return Triples(self.array[index], self.item_class)
        return self.item_class(*self.array[index].tolist())

    def tolist(self) -> list[Any]:
        """The items as :attr:`item_class` values (three Python floats each)."""
        return self.item_class.many(self.array.tolist())

    def same_kind(self, other: object) -> bool:
        return isinstance(other, Triples) and other.item_class is self.item_class

    def __repr__(self) -> str:
        return f"Triples({self.item_class.__name__}, {len(self)})"


#: a branch as a tree stores it: a list of items, a read-only 1-D numpy array, or Triples
Branch = list[Any] | np.ndarray | Triples


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


def stored(items: Iterable[Any]) -> Branch:
    """``items`` as a branch is stored: a 1-D array of float64, int64 or bool as it is (made
    read-only, since trees share their branches), points or vectors as :class:`Triples`,
    anything else as a new list."""
    if isinstance(items, Triples):
        return items
    if isinstance(items, np.ndarray) and items.ndim == 1 and items.dtype in _ARRAY_DTYPES:
        if items.flags.writeable:
            items = items.view()
            items.flags.writeable = False
        return items
    return list(items)


def as_list(branch: Branch) -> list[Any]:
    """A branch as a list of Python values (an array's numbers as ``float``, ``int`` or
    ``bool``, points as points); a list branch is returned as it is."""
    return branch.tolist() if isinstance(branch, np.ndarray | Triples) else branch


def is_array(branch: Branch) -> bool:
    """Whether ``branch`` is held as an array (numbers, or :class:`Triples`)."""
    return isinstance(branch, np.ndarray | Triples)


def item_at(branch: Branch, index: int) -> Any:
    """The item at ``index`` as a Python value, whatever the branch is held as: an array's
    number as ``float``, ``int`` or ``bool`` (never a numpy scalar), a row of Triples as a
    point or vector, a list's item as it is."""
    item = branch[index]
    return item.item() if isinstance(item, np.generic) else item


def take(branch: Branch, indices: np.ndarray) -> Branch:
    """The items at ``indices`` (an integer array), in that order, held as ``branch`` is:
    an array or Triples gives an array or Triples, a list a list."""
    if is_array(branch):
        return branch[indices]
    return [branch[i] for i in indices.tolist()]


def concatenated(first: Branch, second: Branch) -> Branch:
    """Two branches end to end: one array when both are arrays of one kind, else a list."""
    if len(second) == 0 and is_array(first):
        return first
    if len(first) == 0 and is_array(second):
        return second
    if is_array(first) and same_array_kind(first, second):
        return _joined([first, second])
    return as_list(first) + as_list(second)


def same_array_kind(a: Branch, b: Branch) -> bool:
    """Whether two array branches can be joined into one array (same dtype, or same points)."""
    if isinstance(a, Triples):
        return a.same_kind(b)
    return isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.dtype == b.dtype


def _joined(branches: list[Branch]) -> Branch:
    if isinstance(branches[0], Triples):
        return Triples(np.concatenate([b.array for b in branches]), branches[0].item_class)
    return stored(np.concatenate(branches))


#: the dtypes a branch is kept in as an array: Number, Integer and Boolean items
_ARRAY_DTYPES = (np.dtype(np.float64), np.dtype(np.int64), np.dtype(np.bool_))


class DataTree:
    """An ordered mapping from paths to lists of items.

    A branch of numbers, integers or booleans may be held as a 1-D numpy array (a node
    that returns one from a list output, such as Series, makes one); it is handed out as
    a list of Python values by :attr:`branches`, :meth:`items`, :meth:`branch` and the
    other item-wise views, so a node sees the same items either way. The engine reads the
    arrays themselves through :attr:`raw_branches` and :meth:`raw_items` (casts, bounds,
    and list inputs declared ``In(..., arrays=True)``), never item by item.
    """

    __slots__ = ("_branches",)

    def __init__(self, branches: dict[Path, Iterable[Any]] | None = None) -> None:
        self._branches: dict[Path, Branch] = {}
        if branches:
            for path in sorted(branches):
                self._branches[path] = stored(branches[path])

    # -- construction -------------------------------------------------------------
    @classmethod
    def from_value(cls, value: Any) -> DataTree:
        """A single value becomes ``{0}: [value]``; a list (or a 1-D array) becomes ``{0}: items``."""
        if isinstance(value, DataTree):
            return value
        tree = cls()
        if isinstance(value, list) or (isinstance(value, np.ndarray) and value.ndim == 1):
            tree._branches[(0,)] = stored(value)
        else:
            tree._branches[(0,)] = [value]
        return tree

    @classmethod
    def from_branches(cls, branches: Iterable[Iterable[Any]], prefix: Path = ()) -> DataTree:
        """Branches numbered ``{prefix;0}``, ``{prefix;1}`` ... in order."""
        tree = cls()
        for i, items in enumerate(branches):
            tree._branches[(*prefix, i)] = stored(items)
        return tree

    @classmethod
    def _sorted(cls, branches: dict[Path, Branch]) -> DataTree:
        tree = cls()
        tree._branches = dict(sorted(branches.items())) if len(branches) > 1 else branches
        return tree

    # -- access -------------------------------------------------------------------
    @property
    def paths(self) -> list[Path]:
        return list(self._branches)

    @property
    def branches(self) -> list[list[Any]]:
        """Every branch as a list of items (an array branch converted)."""
        return [as_list(b) for b in self._branches.values()]

    @property
    def raw_branches(self) -> list[Branch]:
        """Every branch as it is stored: a list, or a read-only numpy array."""
        return list(self._branches.values())

    def items(self) -> Iterator[tuple[Path, list[Any]]]:
        return ((p, as_list(b)) for p, b in self._branches.items())

    def raw_items(self) -> Iterator[tuple[Path, Branch]]:
        """``(path, branch)`` with each branch as it is stored (see :attr:`raw_branches`)."""
        return iter(self._branches.items())

    def branch(self, path: Path) -> list[Any]:
        return as_list(self._branches[path])

    def all_items(self) -> list[Any]:
        """Every item, branch after branch in path order."""
        return [item for branch in self._branches.values() for item in as_list(branch)]

    @property
    def branch_count(self) -> int:
        return len(self._branches)

    @property
    def item_count(self) -> int:
        return sum(len(b) for b in self._branches.values())

    def is_empty(self) -> bool:
        return all(len(b) == 0 for b in self._branches.values())

    def first(self) -> Any:
        """The first item of the first non-empty branch (``None`` if there is none)."""
        for branch in self._branches.values():
            if len(branch):
                return branch[0].item() if isinstance(branch, np.ndarray) else branch[0]  # Triples: a Point
        return None

    def _list_at(self, path: Path) -> list[Any]:
        """The branch at ``path`` as a list this tree owns, to add to (an array is converted)."""
        branch = self._branches.get(path)
        if branch is None:
            branch = self._branches[path] = []
        elif is_array(branch):
            branch = self._branches[path] = branch.tolist()
        return branch

    def append(self, path: Path, item: Any) -> None:
        self._list_at(path).append(item)

    def extend(self, path: Path, items: Iterable[Any]) -> None:
        """Add ``items`` at the end of branch ``path``; an array into an empty (or an array)
        branch of the same dtype stays an array."""
        if path not in self._branches:  # a new branch: the items as a tree stores them
            self._branches[path] = stored(items)
            return
        if isinstance(items, Triples) or (
                isinstance(items, np.ndarray) and items.ndim == 1 and items.dtype in _ARRAY_DTYPES):
            branch = self._branches.get(path)
            if branch is None or len(branch) == 0:
                self._branches[path] = stored(items)
                return
            if same_array_kind(branch, items):
                self._branches[path] = _joined([branch, items])
                return
            items = items.tolist()
        self._list_at(path).extend(items)

    def map(self, function: Callable[[Any], Any]) -> DataTree:
        """A tree of the same shape with ``function`` applied to every item."""
        return DataTree._sorted({p: [function(x) for x in as_list(b)] for p, b in self._branches.items()})

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, DataTree):
            return NotImplemented
        if self._branches.keys() != other._branches.keys():
            return False
        for path, mine in self._branches.items():
            theirs = other._branches[path]
            if isinstance(mine, np.ndarray) and isinstance(theirs, np.ndarray):
                if mine.dtype != theirs.dtype or not np.array_equal(
                        mine, theirs, equal_nan=mine.dtype.kind == "f"):
                    return False
            elif isinstance(mine, Triples) and mine.same_kind(theirs):
                if not np.array_equal(mine.array, theirs.array, equal_nan=True):
                    return False
            elif as_list(mine) != as_list(theirs):
                return False
        return True

    def __len__(self) -> int:
        return len(self._branches)

    def __repr__(self) -> str:
        body = ", ".join(f"{format_path(p)}: {as_list(b)!r}" for p, b in self._branches.items())
        return f"DataTree({body})"

    def to_dict(self) -> dict[str, list[Any]]:
        """``{'{0;1}': [...]}`` with the items as they are."""
        return {format_path(p): list(as_list(b)) for p, b in self._branches.items()}

    # -- modifiers (Grasshopper's graft, flatten, simplify, reverse) -----------------------
    def grafted(self) -> DataTree:
        """Every item into its own branch: ``{p}:[a,b]`` → ``{p;0}:[a]``, ``{p;1}:[b]``.

        An empty branch stays an empty branch at ``{p}`` so no path is lost.
        """
        out: dict[Path, Branch] = {}
        for path, branch in self._branches.items():
            if not len(branch):
                out[path] = []
            for i, item in enumerate(as_list(branch)):
                out[(*path, i)] = [item]
        return DataTree._sorted(out)

    def flattened(self) -> DataTree:
        """All items, in path order, into ``{0}``."""
        tree = DataTree()
        branches = list(self._branches.values())
        if branches and is_array(branches[0]) and all(same_array_kind(branches[0], b) for b in branches):
            tree._branches[(0,)] = _joined(branches)  # arrays of one kind: one array
        else:
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
        return DataTree._sorted({p[shared:]: stored(b) for p, b in self._branches.items()})

    def reversed(self) -> DataTree:
        """Reverse every branch's list."""
        return DataTree._sorted({p: stored(b[::-1]) for p, b in self._branches.items()})


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

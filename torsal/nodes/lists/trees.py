"""Data-tree structure: flatten, graft, merge and partition branches."""

from __future__ import annotations

from itertools import cycle

import numpy as np

from torsal.engine.datatree import DataTree, format_path
from torsal.engine.node import TREE, In, Node, Out
from torsal.engine.types import GENERIC, INTEGER


class Flatten(Node):
    """Put every item of a tree into one list, branch after branch in path order.

    {0;0}: [a], {0;1}: [b, c] becomes {0}: [a, b, c].
    """

    type_id = "lists.Flatten"
    nickname, aliases = "Flat", ("Flatten Tree",)
    inputs = (In("Tree", GENERIC, "T", "The tree to flatten.", access=TREE),)
    outputs = (Out("Tree", GENERIC, "T", "All the items in the single branch {0}.", access=TREE),)

    def solve(self, tree: DataTree) -> DataTree:
        return tree.flattened()


class Graft(Node):
    """Put every item of a tree into a branch of its own.

    {0}: [a, b] becomes {0;0}: [a], {0;1}: [b]; use it to make a node treat each
    item separately, e.g. to pair every point with every number.
    """

    type_id = "lists.Graft"
    nickname, aliases = "Graft", ("Graft Tree",)
    inputs = (In("Tree", GENERIC, "T", "The tree to graft.", access=TREE),)
    outputs = (Out("Tree", GENERIC, "T", "One branch per item, one path level deeper.",
                   access=TREE),)

    def solve(self, tree: DataTree) -> DataTree:
        return tree.grafted()


class Merge(Node):
    """Join two data streams: branches with the same path are put end to end.

    {0}: [1, 2] merged with {0}: [3] and {1}: [4] gives {0}: [1, 2, 3], {1}: [4].
    Either input may be left empty.
    """

    type_id = "lists.Merge"
    nickname, aliases = "Merge", ("Entwine", "combine", "join lists")
    inputs = (
        In("D1", GENERIC, "D1", "The first data; its items come first.", access=TREE,
           optional=True),
        In("D2", GENERIC, "D2", "The second data, added after D1's items.", access=TREE,
           optional=True),
    )
    outputs = (Out("Result", GENERIC, "R", "D1 and D2 together, path by path.", access=TREE),)

    def solve(self, first: DataTree, second: DataTree) -> DataTree:
        merged = DataTree()
        for tree in (first, second):
            for path, branch in tree.raw_items():  # arrays of one kind join into one array
                merged.extend(path, branch)
        return DataTree(dict(merged.raw_items()))  # in path order


class Partition(Node):
    """Cut each list into chunks of Size items; each chunk gets its own branch.

    {0}: [a, b, c, d, e] with Size 2 gives {0;0}: [a, b], {0;1}: [c, d], {0;2}: [e].
    Several sizes are used in turn ([1, 2] gives chunks of 1, 2, 1, 2 … items). Sizes
    match the list's branches as usual: a tree of sizes gives each branch its own. A
    list whose sizes include one below 1 or an empty one is not cut (it gets one empty
    branch {p;0}) and the node warns naming Size; the other lists are cut.
    """

    type_id = "lists.Partition"
    nickname, aliases = "Part", ("Partition List", "chunk", "split list")
    inputs = (
        In("List", GENERIC, "L", "The list to cut up.", access=TREE),
        In("Size", INTEGER, "S", "How many items go in each chunk (1 or more).", access=TREE,
           default=1),
    )
    outputs = (Out("Chunks", GENERIC, "C", "The chunks, one branch {p;i} each.", access=TREE),)

    def solve(self, tree: DataTree, sizes: DataTree) -> DataTree:
        size_branches = sizes.branches or [[1]]
        size_paths = sizes.paths or [(0,)]
        refused = [self._refusal(branch, path, len(size_branches) > 1)
                   for branch, path in zip(size_branches, size_paths, strict=True)]
        chunks = DataTree()
        # Branches match as for list access: the list's b-th branch takes the sizes'
        # b-th branch, or their last one when there are fewer.
        for b, (path, items) in enumerate(tree.raw_items()):  # an array's chunks stay arrays
            which = min(b, len(size_branches) - 1)
            if refused[which]:  # a size it cannot cut by: this list gets no chunks, the others do
                self.warn(refused[which])
                chunks.extend((*path, 0), [])
                continue
            pattern = size_branches[which] or [1]
            start = 0
            for i, size in enumerate(cycle(pattern)):
                if start >= len(items):
                    break
                chunks.extend((*path, i), items[start:start + size])
                start += size
        return chunks

    @staticmethod
    def _refusal(sizes: list | np.ndarray, path: tuple[int, ...], several: bool) -> str:
        """The warning refusing a branch of sizes ("" when every size is 1 or more)."""
        where = f" (Size branch {format_path(path)})" if several else ""
        if isinstance(sizes, np.ndarray):  # an array has no nulls: its least size tells
            sizes = [sizes.min()] if len(sizes) and sizes.min() < 1 else []
        for size in sizes:
            if size is None:
                return f"Size has an empty (null) item{where}: the list it cuts gets no chunks"
            if size < 1:
                return f"Size must be at least 1, not {size}{where}: the list it cuts gets no chunks"
        return ""

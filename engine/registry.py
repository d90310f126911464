"""The node registry: node types by ``type`` id, from ``nodes`` and from plug-ins.

Plug-ins publish node classes through the ``torsal.nodes`` entry-point group; an entry
point may name a module (every :class:`Node` subclass with a ``type_id`` in it is
registered), a single class, or a callable returning classes.
"""

from __future__ import annotations

import importlib
import inspect
from collections.abc import Iterator
from importlib.metadata import entry_points
from types import ModuleType
from typing import Any

from engine.node import Node

ENTRY_POINT_GROUP = "torsal.nodes"


class Registry:
    """Node classes by ``type_id`` (``<palette>.<NodeName>``)."""

    def __init__(self) -> None:
        self._types: dict[str, type[Node]] = {}
        self._lazy: dict[str, list[str]] = {}  # palette → modules not imported yet
        self.problems: list[str] = []

    def register_lazy(self, palette: str, module_name: str) -> None:
        """Promise that ``module_name`` holds node types of ``palette``; it is imported the
        first time a type of that palette is asked for (or the catalogue is listed)."""
        self._lazy.setdefault(palette, []).append(module_name)

    def _load_palette(self, palette: str) -> None:
        for module_name in self._lazy.pop(palette, []):
            self.register_module(importlib.import_module(module_name))

    def load_all(self) -> None:
        """Import every promised module (for listing the whole catalogue)."""
        for palette in list(self._lazy):
            self._load_palette(palette)

    def register(self, cls: type[Node]) -> type[Node]:
        type_id = cls.type_id
        palette, _, name = type_id.partition(".")
        if not (palette and name and palette.isidentifier() and name.isidentifier()):
            raise ValueError(f"{cls.__name__}.type_id must be '<palette>.<NodeName>', not {type_id!r}")
        self._types[type_id] = cls
        return cls

    def register_module(self, module: ModuleType) -> None:
        for cls in classes_in(module):
            self.register(cls)

    def get(self, type_id: str) -> type[Node] | None:
        if type_id not in self._types and isinstance(type_id, str):
            self._load_palette(type_id.partition(".")[0])
        return self._types.get(type_id)

    def create(self, type_id: str, settings: dict[str, Any] | None = None) -> Node:
        cls = self.get(type_id)
        if cls is None:
            raise KeyError(f"no node type {type_id!r} is installed")
        return cls(settings)

    def palettes(self) -> list[str]:
        """Every palette with node types, registered or promised, without importing any."""
        return sorted({t.partition(".")[0] for t in self._types} | set(self._lazy))

    def types_in(self, palette: str) -> list[type[Node]]:
        """The node types of one palette, sorted by id; imports only that palette's modules."""
        self._load_palette(palette)
        return sorted((c for c in self._types.values() if c.palette() == palette), key=lambda c: c.type_id)

    def __contains__(self, type_id: object) -> bool:
        return isinstance(type_id, str) and self.get(type_id) is not None

    def __iter__(self) -> Iterator[type[Node]]:
        self.load_all()
        return iter(sorted(self._types.values(), key=lambda c: c.type_id))

    def __len__(self) -> int:
        self.load_all()
        return len(self._types)

    def load_entry_points(self) -> None:
        """Register third-party node types; a broken plug-in is reported, not fatal."""
        for entry in entry_points(group=ENTRY_POINT_GROUP):
            try:
                loaded = entry.load()
                if isinstance(loaded, ModuleType):
                    self.register_module(loaded)
                elif inspect.isclass(loaded) and issubclass(loaded, Node):
                    self.register(loaded)
                elif callable(loaded):
                    for cls in loaded():
                        self.register(cls)
            except Exception as exc:  # a plug-in's bug must not stop Torsal starting
                self.problems.append(f"plug-in {entry.name!r} could not be loaded: {exc}")


def classes_in(module: ModuleType) -> list[type[Node]]:
    """Node subclasses defined in ``module`` that carry a ``type_id``."""
    return [
        obj
        for obj in vars(module).values()
        if inspect.isclass(obj)
        and issubclass(obj, Node)
        and obj.type_id
        and obj.__module__ == module.__name__
    ]

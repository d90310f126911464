"""The registry: node types by ``type`` id and value types by name, from palettes and plug-ins.

A *palette package* declares what it holds in its ``__init__``, as plain data::

    NODE_TYPES = ("primitives", "splines")   # modules holding the palette's node types
    VALUE_TYPES = ("values",)                # modules defining value types (optional)
    PALETTE = "curves"                       # optional: its name (by default the package's)

Module names are relative to the package. :meth:`Registry.discover` finds the palette
packages inside a library package (Torsal's ``nodes``) by walking its sub-packages and
reading only those declarations: a palette's node modules are imported the first time
one of its types is asked for, so opening a graph imports only the palettes it uses.

A library may also declare an index of where each of its node types lives::

    NODE_INDEX = "node_index"   # a module whose MODULES maps "curves.Line" → "curves.primitives"

Then asking for a type imports only the module the index names (opening a graph imports
only the modules of the node types it holds); a type the index does not name, or that
the named module does not define (a stale index), loads its whole palette as before, so
an index can make loading slower when out of date, never wrong. Listing a palette
(:meth:`Registry.types_in`) or the catalogue imports every module it promises.

Plug-ins publish through the ``torsal.nodes`` entry-point group; an entry point may name
a palette package (declared as above), a module (every :class:`Node` subclass with a
``type_id`` in it is registered), a single class, or a callable returning classes. A
plug-in's node modules are imported when the registry loads it (not lazily like Torsal's
own palettes), so that every command can check it whole: a plug-in that cannot be imported,
or whose type ids are already taken (by Torsal or by a plug-in loaded before it, in the
order of the distributions' names), is refused as a whole and named in
:attr:`Registry.problems`; :func:`provider` tells which distribution a node class came from
(the ``.graph`` file records it beside the node: docs/plugins.md).

The registry owns the value types too (:attr:`Registry.value_types`, the process's
:class:`~torsal.engine.types.TypeTable`): the palettes' declared modules, and the type of every
port of every node type it registers.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
from collections.abc import Iterator
from importlib.metadata import entry_points
from types import ModuleType
from typing import Any

from torsal.engine.node import Node
from torsal.engine.types import TYPES, TypeTable

ENTRY_POINT_GROUP = "torsal.nodes"
#: The distribution that provides Torsal's own node types.
BUILT_IN = "torsal"
#: Plug-in node classes → the distribution (pip's package name) that installed them.
_PROVIDERS: dict[type, str] = {}


def provider(cls: type) -> str | None:
    """The distribution a plug-in's node class came from (None for Torsal's own)."""
    return _PROVIDERS.get(cls)


def _names(module: ModuleType, attribute: str) -> tuple[str, ...]:
    """A package's declared module names (``NODE_TYPES`` or ``VALUE_TYPES``), made absolute."""
    declared = vars(module).get(attribute, ())
    if isinstance(declared, str) or not all(isinstance(n, str) for n in declared):
        raise TypeError(f"{module.__name__}.{attribute} must be a tuple of module names")
    return tuple(f"{module.__name__}.{name}" for name in declared)


def declares_palette(module: ModuleType) -> bool:
    """Whether ``module`` is a palette package (its ``__init__`` declares ``NODE_TYPES``)."""
    return hasattr(module, "__path__") and "NODE_TYPES" in vars(module)


class Registry:
    """Node classes by ``type_id`` (``<palette>.<NodeName>``), and the value types."""

    def __init__(self, value_types: TypeTable | None = None) -> None:
        self._types: dict[str, type[Node]] = {}
        self._lazy: dict[str, list[str]] = {}  # palette → modules not imported yet
        self._palette_types: dict[str, list[str]] = {}  # palette → its value-type modules
        self._where: dict[str, str] = {}  # type id → the module holding it (a library's index)
        self.value_types = TYPES if value_types is None else value_types
        self.problems: list[str] = []

    # -- palettes ---------------------------------------------------------------------
    def discover(self, library: str) -> None:
        """Add every palette package inside the package ``library`` (and the value types
        the library itself declares), importing only the packages' ``__init__`` files."""
        package = importlib.import_module(library)
        for module_name in _names(package, "VALUE_TYPES"):
            self.value_types.declare(module_name)
        index = vars(package).get("NODE_INDEX")
        if index is not None:
            modules = vars(importlib.import_module(f"{library}.{index}")).get("MODULES", {})
            self.add_index({type_id: f"{library}.{name}" for type_id, name in modules.items()})
        for info in pkgutil.iter_modules(package.__path__, prefix=f"{library}."):
            if info.ispkg:
                sub = importlib.import_module(info.name)
                if declares_palette(sub):
                    self.add_palette(sub)

    def add_palette(self, package: ModuleType) -> str:
        """Add the palette ``package`` declares (see the module's docstring); returns its name.
        Nothing but the package's ``__init__`` is imported."""
        palette = vars(package).get("PALETTE") or package.__name__.rpartition(".")[2]
        for module_name in _names(package, "NODE_TYPES"):
            self.register_lazy(palette, module_name)
        for module_name in _names(package, "VALUE_TYPES"):
            self.value_types.declare(module_name)
            self._palette_types.setdefault(palette, []).append(module_name)
        return palette

    def add_index(self, modules: dict[str, str]) -> None:
        """Say which module holds each of these type ids (absolute module names): asking
        for one imports only that module, if it is one a palette promised."""
        self._where.update(modules)

    def register_lazy(self, palette: str, module_name: str) -> None:
        """Promise that ``module_name`` holds node types of ``palette``; it is imported the
        first time a type of that palette is asked for (or the catalogue is listed)."""
        self._lazy.setdefault(palette, []).append(module_name)

    def _load_palette(self, palette: str) -> None:
        for module_name in self._palette_types.pop(palette, []):
            self.value_types.load(module_name)
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
        for port in (*cls.inputs, *cls.outputs):
            self.value_types.learn(port.type)
        return cls

    def register_module(self, module: ModuleType) -> None:
        for cls in classes_in(module):
            self.register(cls)

    def _load_type(self, type_id: str) -> None:
        """Import the module the index names for ``type_id`` (with its palette's value
        types); if that does not define it, the whole palette."""
        palette = type_id.partition(".")[0]
        pending = self._lazy.get(palette, [])
        module_name = self._where.get(type_id)
        if module_name in pending:
            for value_module in self._palette_types.pop(palette, []):
                self.value_types.load(value_module)
            pending.remove(module_name)
            if not pending:
                del self._lazy[palette]
            self.register_module(importlib.import_module(module_name))
        if type_id not in self._types:
            self._load_palette(palette)

    def get(self, type_id: str) -> type[Node] | None:
        if type_id not in self._types and isinstance(type_id, str):
            self._load_type(type_id)
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
        """Register third-party node types. A plug-in that cannot be loaded, or that reuses a
        type id already registered, is refused whole and reported in :attr:`problems`."""
        found = sorted(entry_points(group=ENTRY_POINT_GROUP), key=lambda e: (_distribution(e), e.name))
        for entry in found:
            package = _distribution(entry)
            try:
                classes = self._plugin_classes(entry.load())
            except Exception as exc:  # a plug-in's bug must not stop Torsal starting
                self.problems.append(f"plug-in {package!r} (entry point {entry.name!r}) could not be loaded: "
                                     f"{type(exc).__name__}: {exc}")
                continue
            clash = self._clash(classes, package, entry.name)
            if clash is not None:
                self.problems.append(clash)
                continue
            for cls in classes:
                self.register(cls)
                _PROVIDERS[cls] = package

    def _plugin_classes(self, loaded: Any) -> list[type[Node]]:
        """The node classes an entry point offers (a palette package's modules imported now)."""
        if isinstance(loaded, ModuleType) and declares_palette(loaded):
            for module_name in _names(loaded, "VALUE_TYPES"):
                self.value_types.load(module_name)
            modules = [importlib.import_module(name) for name in _names(loaded, "NODE_TYPES")]
            classes = [cls for module in modules for cls in classes_in(module)]
        elif isinstance(loaded, ModuleType):
            classes = classes_in(loaded)
        elif inspect.isclass(loaded):
            classes = [loaded]
        elif callable(loaded):
            classes = list(loaded())
        else:
            raise TypeError(f"it names a {type(loaded).__name__}, not a module, a node class or a factory")
        for cls in classes:
            if not (inspect.isclass(cls) and issubclass(cls, Node)):
                raise TypeError(f"{cls!r} is not a torsal.api.Node subclass")
            palette, _, name = cls.type_id.partition(".")
            if not (palette and name and palette.isidentifier() and name.isidentifier()):
                raise ValueError(f"{cls.__name__}.type_id must be '<palette>.<NodeName>', "
                                 f"not {cls.type_id!r}")
        return classes

    def _clash(self, classes: list[type[Node]], package: str, entry: str) -> str | None:
        """Why a plug-in's classes cannot be registered (a type id taken), or None."""
        mine: dict[str, type[Node]] = {}
        for cls in classes:
            other = mine.get(cls.type_id) or self.get(cls.type_id)  # loads a built-in palette of that name
            if other is not None and other is not cls:
                owner = package if cls.type_id in mine else (provider(other) or BUILT_IN)
                return (f"plug-in {package!r} (entry point {entry!r}) is refused: its node type "
                        f"{cls.type_id!r} is already provided by {owner!r}; the plug-in must give its "
                        f"node types ids of their own (its palette name is the part before the dot)")
            mine[cls.type_id] = cls
        return None


def _distribution(entry: Any) -> str:
    """The name of the distribution that declares an entry point (pip's package name)."""
    dist = getattr(entry, "dist", None)
    name = getattr(dist, "name", None) if dist is not None else None
    return name or str(getattr(entry, "value", entry.name)).split(":")[0].split(".")[0]


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

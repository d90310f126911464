"""Value types, the casts between them, and their JSON encoding.

A :class:`ValueType` names what flows on a wire (Number, Point, Curve ...). The engine
registers the plain types here; ``nodes`` registers geometry types (Curve, Surface,
Mesh ...) with :func:`register_type` and :func:`register_cast`. A failed cast raises
:class:`CastError` with a sentence a designer can act on.
"""

from __future__ import annotations

import importlib
import math
import sys
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from torsal.engine.values import Domain, Plane, Point, Triple, Vector


class CastError(ValueError):
    """A value could not be turned into the type a port needs."""


Encoder = Callable[[Any], Any]
Decoder = Callable[[dict], Any]


@dataclass(eq=False)
class ValueType:
    """A kind of value: its name, the Python class(es) that hold it and how it is written.

    ``encode`` turns a value into JSON data that ``decode`` reads back (for persistent
    input values); ``summarize`` describes a value in ``torsal run --json`` results and
    defaults to ``encode``.
    """

    name: str
    classes: tuple[type, ...]
    description: str = ""
    encode: Encoder | None = None
    decode: Decoder | None = None
    summarize: Encoder | None = None
    casts: dict[str, Callable[[Any], Any]] = field(default_factory=dict)

    def __repr__(self) -> str:
        return f"<type {self.name}>"

    def accepts(self, value: Any) -> bool:
        return isinstance(value, self.classes)


class TypeTable:
    """Value types by name: the engine's own, and those the node library and plug-ins declare.

    A package declares the modules that define its value types in its ``__init__``
    (``VALUE_TYPES = ("values",)``, names relative to the package); every
    :class:`ValueType` at module level in them is a value type. The node registry
    (:class:`torsal.engine.registry.Registry`) reads the declarations of the palettes it finds
    and hands them to its table with :meth:`declare`; nothing is registered as a side
    effect of importing a node module. A declared module is loaded (imported) the first
    time a type is asked for by a name the table does not know yet (a value in a file);
    a value of a type the table has not met makes it load the declared modules that are
    already imported, and read the declarations of packages imported since (a node used
    on its own, without a registry).
    """

    def __init__(self) -> None:
        self._types: dict[str, ValueType] = {}
        self._declared: dict[str, None] = {}  # modules a registry declared, not loaded yet
        self._seen_declared: dict[str, None] = {}  # declared by packages met in sys.modules
        self._loaded: set[str] = set()
        self._modules_seen = 0  # len(sys.modules) when declarations were last looked for

    # -- filling ------------------------------------------------------------------------
    def add(self, value_type: ValueType) -> ValueType:
        """Add ``value_type`` (replacing one of the same name)."""
        self._types[value_type.name] = value_type
        return value_type

    def learn(self, value_type: ValueType) -> None:
        """Add ``value_type`` unless one of its name is there (a port's type)."""
        if value_type.name not in self._types:
            self._types[value_type.name] = value_type

    def declare(self, module_name: str) -> None:
        """Promise that ``module_name`` defines value types; it is imported when needed."""
        if module_name not in self._loaded:
            self._declared[module_name] = None

    def load(self, module_name: str) -> None:
        """Import ``module_name`` and add every :class:`ValueType` defined at its top level."""
        self._declared.pop(module_name, None)
        self._seen_declared.pop(module_name, None)
        if module_name in self._loaded:
            return
        module = importlib.import_module(module_name)
        self._loaded.add(module_name)
        for value in vars(module).values():
            if isinstance(value, ValueType):
                self.learn(value)

    def _settle(self) -> None:
        """Load declared modules that are already imported (no import is made here), after
        reading the declarations of packages imported since the last look."""
        modules = sys.modules
        if len(modules) == self._modules_seen:
            return
        self._modules_seen = len(modules)
        for name, module in list(modules.items()):
            namespace = getattr(module, "__dict__", None)  # not getattr(module, ...): no lazy imports
            declared = namespace.get("VALUE_TYPES") if isinstance(namespace, dict) else None
            if isinstance(declared, tuple) and "__path__" in namespace:
                for relative in declared:
                    if f"{name}.{relative}" not in self._loaded:
                        self._seen_declared[f"{name}.{relative}"] = None
        for module_name in (*self._declared, *self._seen_declared):
            module = modules.get(module_name)
            if module is None:
                continue
            if getattr(module.__spec__, "_initializing", False):
                self._modules_seen = 0  # still being imported: look again next time
                continue
            self.load(module_name)

    # -- looking up ---------------------------------------------------------------------
    def find(self, name: str) -> ValueType | None:
        """The type called ``name``, loading declared modules if it is not known yet."""
        found = self._types.get(name)
        if found is None and isinstance(name, str):
            self._settle()
            for module_name in list(self._declared):
                found = self._types.get(name)
                if found is not None:
                    break
                self.load(module_name)
            found = self._types.get(name)
        return found

    def values(self) -> Iterable[ValueType]:
        """Every type loaded so far (with those of modules already imported)."""
        self._settle()
        return self._types.values()

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and self.find(name) is not None


#: The value types of this process: the engine's own below, and what registries declare.
TYPES = TypeTable()


def register_type(value_type: ValueType) -> ValueType:
    """Add ``value_type`` to the table at once (for a plug-in that does not declare its
    types in ``VALUE_TYPES``); Torsal's own packages declare theirs."""
    return TYPES.add(value_type)


def get_type(name: str) -> ValueType:
    found = TYPES.find(name)
    if found is None:
        raise KeyError(f"unknown value type {name!r}")
    return found


def register_cast(source: ValueType, target: ValueType, cast: Callable[[Any], Any]) -> None:
    """Let values of ``source`` flow into ports of ``target`` through ``cast``."""
    target.casts[source.name] = cast


def type_of(value: Any) -> ValueType | None:
    """The most specific registered type whose classes hold ``value``."""
    best: ValueType | None = None
    for value_type in TYPES.values():
        if value_type is GENERIC or not value_type.accepts(value):
            continue
        # Prefer the type whose class is deepest in the MRO (Vector over Point).
        if best is None or _depth(value_type, value) < _depth(best, value):
            best = value_type
    return best


def _depth(value_type: ValueType, value: Any) -> int:
    mro = type(value).__mro__
    # a class that holds the value without being in its MRO (an abstract class's subclass
    # hook) ranks after every base
    return min((mro.index(c) for c in value_type.classes if c in mro), default=len(mro))


def can_cast(source: ValueType, target: ValueType) -> bool:
    """Whether a wire may run from a ``source`` output into a ``target`` input."""
    return (
        source is target
        or target is GENERIC
        or source is GENERIC
        or source.name in target.casts
        or (source.classes and all(issubclass(c, target.classes) for c in source.classes))
    )


def cast(value: Any, target: ValueType) -> Any:
    """Convert ``value`` for a port of type ``target`` or raise :class:`CastError`."""
    if target is GENERIC or type(value) in target.classes:
        return value
    if isinstance(value, target.classes) and not (isinstance(value, bool) and target is not BOOLEAN):
        return value
    source = type_of(value)
    if source is not None:
        converter = target.casts.get(source.name)
        if converter is not None:
            try:
                return converter(value)
            except CastError:
                raise
            except (TypeError, ValueError, OverflowError) as exc:
                raise CastError(f"could not convert {describe(value)} to {target.name}: {exc}") from None
    raise CastError(f"{describe(value)} cannot be used as {target.name}")


def describe(value: Any) -> str:
    """A short human description of a value for messages: ``Text 'abc'``, ``Number 2.5``."""
    value_type = type_of(value)
    name = value_type.name if value_type else type(value).__name__
    text = repr(value)
    if len(text) > 40:
        text = text[:37] + "..."
    return f"{name} {text}"


# --------------------------------------------------------------------------- JSON codecs

def _xyz(kind: str) -> Encoder:
    return lambda v: {"type": kind, "xyz": [_num(c) for c in v]}


def _num(x: float) -> float | int:
    """Write integral floats as they are; JSON has no inf/nan, so those become text."""
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    return x


def encode_value(value: Any) -> Any:
    """Encode one value (or a list of values) as JSON data, for files and results."""
    if isinstance(value, list | tuple) and not isinstance(value, Triple | Domain | Plane):
        return [encode_value(v) for v in value]
    value_type = type_of(value)
    if value_type is not None and value_type.encode is not None:
        return value_type.encode(value)
    if value is None or isinstance(value, bool | int | str):
        return value
    if isinstance(value, float):
        return _num(float(value))
    if callable(getattr(value, "tolist", None)):  # numpy scalars and arrays, duck-typed
        return encode_value(value.tolist())
    raise CastError(f"{describe(value)} cannot be written to a file")


def summarize_value(value: Any) -> Any:
    """Describe a value in ``torsal run --json`` output (geometry as key figures)."""
    value_type = type_of(value)
    if value_type is not None and value_type.summarize is not None:
        return value_type.summarize(value)
    try:
        return encode_value(value)
    except CastError:
        return {"type": value_type.name if value_type else type(value).__name__}


def decode_value(data: Any) -> Any:
    """Read JSON data written by :func:`encode_value` back into values."""
    if isinstance(data, list):
        return [decode_value(d) for d in data]
    if isinstance(data, dict):
        kind = data.get("type")
        value_type = TYPES.find(kind) if isinstance(kind, str) else None
        if value_type is None or value_type.decode is None:
            raise CastError(f"unknown value {{'type': {kind!r}}}")
        try:
            return value_type.decode(data)
        except (KeyError, TypeError, ValueError, OverflowError) as exc:  # OverflowError: 1e400 as int
            raise CastError(f"malformed {kind} value: {exc}") from None
    if data is None or isinstance(data, bool | int | float | str):
        return data
    raise CastError(f"cannot read value {data!r}")


def _read_xyz(cls: type) -> Decoder:
    def decode(data: dict) -> Any:
        xyz = data["xyz"]
        if not isinstance(xyz, list) or len(xyz) != 3:
            raise ValueError("'xyz' must be a list of three numbers")
        return cls(*(_finite(c) for c in xyz))

    return decode


def _finite(x: Any) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float):
        raise ValueError(f"{x!r} is not a number")
    value = float(x)
    if not math.isfinite(value):
        raise ValueError(f"{x!r} is not a finite number")
    return value


# --------------------------------------------------------------------------- built-in types

def _text_to_number(text: str) -> float:
    try:
        return float(text.strip())
    except ValueError:
        raise CastError(f"could not read Text {text!r} as a Number") from None


def _to_integer(x: float) -> int:
    if math.isnan(x):
        raise CastError("NaN is not a number, so it cannot be used as an Integer")
    if not math.isfinite(x):
        raise CastError(f"Number {x!r} cannot be used as an Integer")
    return round(x)


def _a_number(target: str, convert: Callable[[float], Any]) -> Callable[[float], Any]:
    """``convert``, refusing NaN (which ``bool`` would read as true)."""

    def checked(x: float) -> Any:
        if math.isnan(x):
            raise CastError(f"NaN is not a number, so it cannot be used as {target}")
        return convert(x)

    return checked


def _text_to_bool(text: str) -> bool:
    word = text.strip().lower()
    if word in ("true", "yes", "1", "on"):
        return True
    if word in ("false", "no", "0", "off"):
        return False
    raise CastError(f"could not read Text {text!r} as a Boolean (use true or false)")


def _text_to_point(cls: type) -> Callable[[str], Any]:
    def convert(text: str) -> Any:
        parts = text.strip().strip("{}()[]").replace(";", ",").split(",")
        try:
            return cls(*(float(p) for p in parts)) if len(parts) == 3 else _bad()
        except ValueError:
            raise CastError(f"could not read Text {text!r} as {cls.__name__} (write x, y, z)") from None

    def _bad() -> Any:
        raise ValueError

    return convert


def _plane_encode(p: Plane) -> dict:
    return {
        "type": "Plane",
        "origin": [_num(c) for c in p.origin],
        "x": [_num(c) for c in p.x],
        "y": [_num(c) for c in p.y],
    }


def _plane_decode(d: dict) -> Plane:
    def three(key: str) -> list[float]:
        v = d[key]
        if not isinstance(v, list) or len(v) != 3:
            raise ValueError(f"'{key}' must be a list of three numbers")
        return [_finite(c) for c in v]

    return Plane(Point(*three("origin")), Vector(*three("x")), Vector(*three("y")))


GENERIC = register_type(ValueType("Generic", (object,), "Any value."))
NUMBER = register_type(ValueType("Number", (float,), "A real number."))
INTEGER = register_type(ValueType("Integer", (int,), "A whole number."))
BOOLEAN = register_type(ValueType("Boolean", (bool,), "True or false."))
TEXT = register_type(ValueType("Text", (str,), "A piece of text."))
POINT = register_type(
    ValueType("Point", (Point,), "A location.", _xyz("Point"), _read_xyz(Point))
)
VECTOR = register_type(
    ValueType("Vector", (Vector,), "A direction.", _xyz("Vector"), _read_xyz(Vector))
)
DOMAIN = register_type(
    ValueType(
        "Domain",
        (Domain,),
        "An interval of numbers.",
        lambda d: {"type": "Domain", "min": _num(d.min), "max": _num(d.max)},
        lambda d: Domain(_finite(d["min"]), _finite(d["max"])),
    )
)
PLANE = register_type(ValueType("Plane", (Plane,), "An oriented plane.", _plane_encode, _plane_decode))

# bool is a subclass of int in Python; keep Booleans out of Integer/Number ports' fast path
INTEGER.classes = (int,)
register_cast(INTEGER, NUMBER, float)
register_cast(BOOLEAN, NUMBER, float)
register_cast(TEXT, NUMBER, _text_to_number)
register_cast(NUMBER, INTEGER, _to_integer)
register_cast(BOOLEAN, INTEGER, int)
register_cast(TEXT, INTEGER, lambda t: _to_integer(_text_to_number(t)))
register_cast(NUMBER, BOOLEAN, _a_number("a Boolean", bool))
register_cast(INTEGER, BOOLEAN, bool)
register_cast(TEXT, BOOLEAN, _text_to_bool)
for _t in (NUMBER, INTEGER, BOOLEAN, POINT, VECTOR, DOMAIN, PLANE):
    register_cast(_t, TEXT, lambda v: _format(v))
register_cast(VECTOR, POINT, lambda v: Point(*v))
register_cast(POINT, VECTOR, lambda p: Vector(*p))
register_cast(TEXT, POINT, _text_to_point(Point))
register_cast(TEXT, VECTOR, _text_to_point(Vector))
register_cast(NUMBER, DOMAIN, _a_number("a Domain", lambda x: Domain(0.0, float(x))))
register_cast(INTEGER, DOMAIN, lambda x: Domain(0.0, float(x)))
register_cast(POINT, PLANE, lambda p: Plane(p, Vector(1, 0, 0), Vector(0, 1, 0)))


def _format(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, Triple):
        return "{" + ", ".join(f"{c:g}" for c in value) + "}"
    return str(value)

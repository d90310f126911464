"""The node base class: ports declared once, one ``solve`` method, messages.

A node type is one class::

    class Add(Node):
        \"\"\"Add two numbers.\"\"\"

        type_id = "maths.Add"
        inputs = (In("A", NUMBER, "A", "First number.", default=0.0),
                  In("B", NUMBER, "B", "Second number.", default=0.0))
        outputs = (Out("Result", NUMBER, "R", "A + B."),)

        def solve(self, a: float, b: float) -> float:
            return a + b

``solve`` receives one argument per input, in order, shaped by the input's access
(an item, a list, or a whole :class:`~torsal.engine.datatree.DataTree`), and returns one value
per output (a tuple when there are several). It never touches the graph or a GUI. To
stop with a message it raises :class:`NodeError` or :class:`NodeWarning`; to say
something and go on it calls :meth:`Node.remark` or :meth:`Node.warn`.
"""

from __future__ import annotations

import enum
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

# the solve's exceptions, re-exported: nodes import them from here
from torsal.engine.errors import Cancelled as Cancelled
from torsal.engine.errors import NodeError as NodeError
from torsal.engine.errors import NodeWarning as NodeWarning
from torsal.engine.messages import CancelToken as CancelToken
from torsal.engine.messages import Level as Level
from torsal.engine.messages import Message as Message
from torsal.engine.solve_context import SolveContext, active
from torsal.engine.types import ValueType
from torsal.engine.widgets import Widget
from torsal.engine.writes import NodeFiles, WriteAccess


class Access(enum.Enum):
    """How much of an input tree one call of ``solve`` sees."""

    ITEM = "item"
    LIST = "list"
    TREE = "tree"


ITEM, LIST, TREE = Access.ITEM, Access.LIST, Access.TREE


_WORD_BREAK = re.compile(r"(?<=[a-z])(?=[A-Z0-9])|(?<=[A-Z])(?=[A-Z][a-z])|(?<=[0-9])(?=[A-Z])")


def words(name: str) -> str:
    """A CamelCase type name as words: ``DivideCurve`` → "Divide Curve", ``XYPlane`` →
    "XY Plane", ``Export3dm`` → "Export 3dm" (a name with spaces is left as it is)."""
    return name if " " in name else _WORD_BREAK.sub(" ", name)


_NO_DEFAULT = object()


@dataclass(frozen=True)
class In:
    """An input port.

    ``default`` is used when nothing is wired and no value is set; an input with no
    default and not ``optional`` must receive data. ``multiple`` lets an item-access
    input take several wires (list and tree inputs always may). ``min`` and ``max``
    bound a number input: the solver refuses a value outside them, naming the input
    (:mod:`torsal.engine.bounds`), and front-ends show them; ``choices`` make a whole-number
    input a value list (its numbers and their names), refused likewise. ``arrays=True`` on a list input:
    a branch of numbers, integers or booleans arrives as the read-only numpy array the
    tree holds (no conversion); points or vectors as their ``(n, 3)`` array into a Point
    or Vector input, as :class:`~torsal.engine.datatree.Triples` into any other; other branches
    (and any branch holding an empty item: arrays hold no nulls) as lists. A node that
    says so must treat its list as a sequence (``len``, slicing, ``numpy.asarray``, and
    :func:`~torsal.engine.datatree.item_at` for one item, never a numpy scalar), not call list
    methods.
    """

    name: str
    type: ValueType
    nickname: str = ""
    description: str = ""
    default: Any = _NO_DEFAULT
    access: Access = ITEM
    optional: bool = False
    multiple: bool = False
    min: float | None = None
    max: float | None = None
    arrays: bool = False
    #: a value list's choices, ``((0, "Beside model"), (1, "Origin"), ...)``: the solver
    #: refuses any other value, naming the input and the choices
    choices: tuple[tuple[int, str], ...] = ()

    @property
    def has_default(self) -> bool:
        return self.default is not _NO_DEFAULT

    @property
    def accepts_several_wires(self) -> bool:
        return self.multiple or self.access is not ITEM


@dataclass(frozen=True)
class Out:
    """An output port. ``access=LIST`` means each call returns a list of values.

    ``preview=False``: the viewport (and Bake) leave this output out even when the node's
    preview is on — for an output that repeats the node's geometry in another form (the
    sample points under an analysis's coloured mesh). It stays available to wire.
    """

    name: str
    type: ValueType
    nickname: str = ""
    description: str = ""
    access: Access = ITEM
    preview: bool = True


@dataclass(frozen=True)
class Setting:
    """A value a node keeps in the file's ``settings`` (a slider's value, an expression).

    ``kind`` is the JSON kind: ``float``, ``int``, ``bool``, ``str`` or ``list``.
    """

    name: str
    kind: type
    default: Any
    description: str = ""


#: The most calls of ``solve`` one solve of a node makes (item access over long lists, or
#: one call per branch). Series, Range and Random make up to 1,000,000 numbers, so a cheap
#: node follows any of them; a list wired by mistake cannot run a node past this.
MAX_CALLS = 1_000_000


class Node:
    """Base class of every node type. Subclasses set the class attributes and ``solve``."""

    type_id: ClassVar[str] = ""
    inputs: ClassVar[tuple[In, ...]] = ()
    outputs: ClassVar[tuple[Out, ...]] = ()
    settings_spec: ClassVar[tuple[Setting, ...]] = ()
    icon: ClassVar[str] = ""
    #: A short name for the canvas and search, as Grasshopper's nicknames ("Pt", "Div").
    nickname: ClassVar[str] = ""
    #: Other names a designer may type for this node: Grasshopper's name for the same
    #: thing first ("Construct Point"), then plain words ("unroll", "flat pattern").
    aliases: ClassVar[tuple[str, ...]] = ()
    #: How a front-end lets a designer set this node by hand (:mod:`torsal.engine.widgets`), if at all.
    widget: ClassVar[Widget | None] = None
    #: The most calls of ``solve`` in one solve of this node (the solver refuses more
    #: before the first, naming the input with the most values).
    max_calls: ClassVar[int] = MAX_CALLS
    #: For a node whose one call can take seconds: the most work, summed over a solve's
    #: calls by :meth:`call_work`, in the node's own unit (None: calls alone are counted).
    #: Caps limit one call; this limits what a list of values multiplies them into.
    max_work: ClassVar[int | None] = None
    #: What :meth:`call_work` counts, as the refusal names it ("grid samples").
    work_unit: ClassVar[str] = "units of work"

    def __init__(self, settings: dict[str, Any] | None = None) -> None:
        self.settings: dict[str, Any] = {s.name: s.default for s in self.settings_spec}
        if settings:
            self.settings.update(settings)
        self._own: SolveContext | None = None  # run state when used on its own, not by a solver

    # -- ports (instances may vary them with their settings, like Expression) -------------
    def input_ports(self) -> tuple[In, ...]:
        return self.inputs

    def output_ports(self) -> tuple[Out, ...]:
        return self.outputs

    def previewed_outputs(self) -> frozenset[str]:
        """Names of the outputs the viewport draws when the node's preview is on."""
        return frozenset(p.name for p in self.output_ports() if p.preview)

    def input_port(self, name: str) -> In | None:
        return next((p for p in self.input_ports() if p.name == name), None)

    def output_port(self, name: str) -> Out | None:
        return next((p for p in self.output_ports() if p.name == name), None)

    # -- run state (see engine.solve_context) -----------------------------------------------
    def context(self) -> SolveContext:
        """The run state of the solve of this node under way in this thread, or, when no
        solver is solving it, the node's own (made when first asked)."""
        current = active()
        if current is not None and current.node is self:
            return current
        return self.own_context()

    def own_context(self) -> SolveContext:
        """The run state of this node used on its own (a test or a script calling ``solve``)."""
        if self._own is None:
            self._own = SolveContext(self)
        return self._own

    @property
    def messages(self) -> list[Message]:
        """The messages of the solve under way (or of the node used on its own)."""
        return self.context().messages

    @property
    def run_state(self) -> dict[str, Any]:
        """Scratch for one solve, empty at its start: counts a node keeps across its calls
        and summarises in :meth:`after_solve`. Never kept on the node between solves."""
        return self.context().state

    # -- cancellation -----------------------------------------------------------------
    @property
    def token(self) -> CancelToken:
        """The running solve's cancel token. A node solved on its own gets a token of its
        own when first asked: nodes cost no token until then."""
        context = self.context()
        if context.token is None:
            context.token = CancelToken()
        return context.token

    # -- files ------------------------------------------------------------------------
    @property
    def files(self) -> NodeFiles:
        """Where this node may write files, and whether the user allows it (see
        :mod:`torsal.engine.writes`). The solver gives each solve its own; a node solved on its own
        has no folder and may write nothing."""
        context = self.context()
        if context.files is None:
            context.files = WriteAccess().for_node("")
        return context.files

    # -- progress -----------------------------------------------------------------------
    @property
    def on_progress(self) -> Callable[[float], None] | None:
        """Where :meth:`progress` reports go (the solver gives each solve its own)."""
        return self.context().on_progress

    @on_progress.setter
    def on_progress(self, listener: Callable[[float], None] | None) -> None:
        """For a node used on its own: hear its progress."""
        self.own_context().on_progress = listener

    # -- behaviour --------------------------------------------------------------------
    def solve(self, *args: Any) -> Any:
        raise NotImplementedError(f"{type(self).__name__} does not define solve()")

    def solve_many(self, *columns: Sequence[Any]) -> list[Any] | None:
        """All the calls of one solve at once, for a node whose calls vectorise: the list of
        what ``solve`` would return for each row of ``columns`` (one sequence per input, in
        port order, each as long as the number of calls, the rows of every branch one after
        the other), or None to have ``solve`` called row by row as usual.

        The solver asks only nodes that define it, and only for item-access calls (every
        branch iterated). It must give each row the very values ``solve`` gives it, bit for
        bit, and the messages ``solve`` would say, in the same order: each row's remarks and
        warnings (``self.remark``, ``self.warn``) one row after another; None and that
        row's warning where ``solve`` would raise :class:`NodeWarning` (see
        :meth:`refuse_row`); and where ``solve`` would raise :class:`NodeError` for a row,
        that error, raised after the messages of the rows before it and none of the rows
        after. When it returns None the solver forgets whatever it said, so the messages
        come from ``solve`` alone. It checks the token between its pieces of work
        (``self.token.check()``) as a long solve does: the solver checks it only before.
        (The solver calls this only on node types that override it.)"""
        return None

    def refuse_row(self, warning: NodeWarning) -> None:
        """In :meth:`solve_many`: what the solver does when ``solve`` raises ``warning`` for
        a row (the row's outputs are None; this says the warning in its place)."""
        self.warn(str(warning))

    def call_work(self, *args: Any) -> int:
        """How much work one call of ``solve`` with these arguments asks for, counted
        against :attr:`max_work` before any call is made (only nodes that set it define
        this). Values ``solve`` would refuse count as 1: its own message says why."""
        return 1

    def before_solve(self) -> None:
        """Called once before the iterations of a solve (start :attr:`run_state` counts here)."""

    def after_solve(self) -> None:
        """Called once after all iterations (summarise per-solve messages here)."""

    def match_outputs(self, trees: Sequence[Any]) -> dict[str, Any] | None:
        """The settings that fit this node's outputs to the input trees it last received
        (``trees``, one per input port): Grasshopper's *Match outputs*, which a front-end
        offers on the node's menu when a node type overrides this (Explode Tree gives itself
        one output per branch). None, the default: nothing to match."""
        return None

    # -- messages -----------------------------------------------------------------------
    def remark(self, text: str) -> None:
        self._say(Level.REMARK, text)

    def warn(self, text: str) -> None:
        self._say(Level.WARNING, text)

    def _say(self, level: Level, text: str) -> None:
        self.context().say(Message(level, text))

    @property
    def anytime(self) -> bool:
        """Whether the host improves this node's result after the solve (the app does;
        ``torsal run`` does not): a node may then answer at once and :meth:`improve_later`."""
        return self.context().anytime

    def improve_later(self, improver: Any) -> None:
        """Run ``improver`` after this solve, off the solve, when the host is :attr:`anytime`
        (torsal/engine/improve.py): it publishes better outputs as it finds them. Only for
        a node solved in one call (tree inputs); the first one asked for is kept."""
        context = self.context()
        if context.improver is None:
            context.improver = improver

    def check_cancelled(self) -> None:
        """Long-running nodes call this inside their loops so a solve can be stopped."""
        self.token.check()

    def progress(self, fraction: float) -> None:
        """Long-running nodes say how far they are, 0 to 1; the solver passes it on to
        the front-end (``torsal run``'s progress line, the app's progress bar)."""
        listener = self.context().on_progress
        if listener is not None:
            listener(fraction)

    # -- catalogue ---------------------------------------------------------------------
    @classmethod
    def palette(cls) -> str:
        return cls.type_id.split(".", 1)[0]

    @classmethod
    def name(cls) -> str:
        return cls.type_id.split(".", 1)[-1]

    def display_name(self) -> str:
        """The name as words, for a node's title: ``DivideCurve`` → "Divide Curve"."""
        return words(self.name())

    @classmethod
    def help(cls) -> str:
        return (cls.__doc__ or "").strip()

    @classmethod
    def catalogue_entry(cls) -> dict[str, Any]:
        """A JSON description of this node type, for ``torsal nodes --json``."""
        def port(p: In | Out) -> dict[str, Any]:
            entry = {
                "name": p.name,
                "nickname": p.nickname,
                "type": p.type.name,
                "access": p.access.value,
                "description": p.description,
            }
            if isinstance(p, In):
                entry["optional"] = p.optional or p.has_default
            return entry

        return {
            "type": cls.type_id,
            "palette": cls.palette(),
            "name": cls.name(),
            "help": cls.help(),
            "inputs": [port(p) for p in cls.inputs],
            "outputs": [port(p) for p in cls.outputs],
            "settings": [
                {"name": s.name, "default": s.default, "description": s.description}
                for s in cls.settings_spec
            ],
        }

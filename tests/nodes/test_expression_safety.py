"""The expression language of ``maths.Expression`` is safe: a hostile corpus is refused,
naming the construct, and neither it nor evaluation creates a file or spawns a process."""

from __future__ import annotations

import ast
import builtins
import os
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import torsal.nodes.expressions as expressions_module
from torsal.nodes.expressions import (
    ExpressionError,
    compile_expression,
)

# ---------------------------------------------------------------------- hostile corpus

HOSTILE = [
    "__import__('os').system('touch /tmp/pwned')",
    "().__class__.__bases__[0].__subclasses__()",
    "lambda: 1",
    "(lambda: 1)()",
    "f'{x}'",
    "'abc'",
    "b'abc'",
    "[x for x in y]",
    "(x for x in y)",
    "{x for x in y}",
    "{x: 1 for x in y}",
    "x.real",
    "x.__class__.__mro__",
    "x[0]",
    "x[0:1]",
    "open('f')",
    "exec('1')",
    "eval('1')",
    "compile('1', 'f', 'eval')",
    "globals()",
    "locals()",
    "vars()",
    "getattr(x, 'real')",
    "__builtins__",
    "(y:=1)",
    "{1:2}",
    "{1, 2}",
    "[1, 2]",
    "(1, 2)",
    "*x",
    "sin(*x)",
    "sin(**x)",
    "sin(x=1)",
    "max(x, y, key=abs)",
    "await x",
    "1j",
    "None",
    "...",
    "x if x else __import__('os')",
    "sin(x).__class__",
    "x; y",
    "import os",
    "x = 1",
]


@pytest.mark.parametrize("payload", HOSTILE)
def test_hostile_payload_is_refused(payload: str) -> None:
    with pytest.raises(ExpressionError):
        compile_expression(payload)


@pytest.mark.parametrize(
    ("payload", "named"),
    [
        ("__import__('os').system('ls')", ".system"),
        ("().__class__.__bases__[0].__subclasses__()", ".__subclasses__"),
        ("lambda: 1", "lambda"),
        ("f'{x}'", "f-strings"),
        ("'abc'", "Text"),
        ("[x for x in y]", "Comprehensions"),
        ("x.real", ".real"),
        ("x[0]", "Indexing"),
        ("open('f')", "Unknown function 'open'"),
        ("(y:=1)", ":="),
        ("{1:2}", "Dictionaries"),
        ("sin(x=1)", "can't be named"),
    ],
)
def test_refusal_names_the_construct(payload: str, named: str) -> None:
    with pytest.raises(ExpressionError) as error:
        compile_expression(payload)
    assert named in str(error.value)


def hostile_payloads_writing_to(folder: Path) -> list[str]:
    target = folder / "pwned"
    return [
        f"__import__('os').system('touch {target}')",
        f"__import__('subprocess').Popen(['touch', '{target}'])",
        f"open('{target}', 'w').write('x')",
        f"exec(\"open('{target}', 'w')\")",
        f"eval(\"__import__('os').system('touch {target}')\")",
        f"(lambda: __import__('os').system('touch {target}'))()",
        f"f\"{{__import__('os').system('touch {target}')}}\"",
        f"[c for c in ().__class__.__bases__[0].__subclasses__()"
        f" if c.__name__ == 'Popen'][0](['touch', '{target}'])",
        f"__builtins__['open']('{target}', 'w')",
        f"globals()['__builtins__'].open('{target}', 'w')",
        f"x if x else __import__('os').system('touch {target}')",
        f"sin(x) + __import__('os').system('touch {target}')",
        "__import__('os').fork()",
        f"__import__('os').execv('/bin/touch', ['touch', '{target}'])",
        f"(y := __import__('os').system('touch {target}'))",
    ]


_AUDITED = (
    "exec",
    "open",
    "import",
    "os.system",
    "os.exec",
    "os.fork",
    "os.forkpty",
    "os.posix_spawn",
    "os.spawn",
    "os.startfile",
    "os.remove",
    "os.rename",
    "os.mkdir",
    "subprocess.Popen",
    "socket.connect",
    "ctypes.dlopen",
)
_audit_log: list[str] | None = None
_audit_thread: int | None = None  # only the watching thread's events count


def _audit(event: str, args: tuple[object, ...]) -> None:
    if _audit_log is not None and event.startswith(_AUDITED) and threading.get_ident() == _audit_thread:
        _audit_log.append(event)


sys.addaudithook(_audit)  # hooks cannot be removed; it records only inside watching()


#: Standard-library modules that Python itself imports lazily while it shows a warning (a
#: SyntaxWarning from ast.parse of a hostile payload, under pytest's warning capture): not
#: the expression's doing, and no code of the payload's.
BENIGN_LAZY_IMPORTS = frozenset({"linecache", "tokenize", "traceback", "tracemalloc", "_colorize"})


@contextmanager
def watching() -> Iterator[list[str]]:
    """Record process spawns, file opens, imports and code execution, by patch and audit.

    Used around just the code under test, so pytest's own work is not recorded, and on
    its thread only: a thread another test left running (a dask cluster's event loop
    importing tornado lazily) is not the code under test.
    """
    global _audit_log, _audit_thread
    calls: list[str] = []
    owner = threading.get_ident()

    def recorder(name: str, original: Callable[..., Any]) -> Callable[..., Any]:
        def record(*args: Any, **kwargs: Any) -> Any:
            if threading.get_ident() != owner:
                return original(*args, **kwargs)
            if name == "__import__" and args and args[0] in BENIGN_LAZY_IMPORTS:
                return original(*args, **kwargs)  # the warnings machinery formatting a warning
            calls.append(f"__import__ {args[0]}" if name == "__import__" and args else name)
            return original(*args, **kwargs)

        return record

    real_compile = builtins.compile

    def compile_only_to_ast(*args: Any, **kwargs: Any) -> Any:
        flags = kwargs.get("flags", args[3] if len(args) > 3 else 0)
        if not flags & ast.PyCF_ONLY_AST and threading.get_ident() == owner:
            calls.append("compile to code")
        return real_compile(*args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:  # __import__ last: setattr itself imports
        patch.setattr(builtins, "compile", compile_only_to_ast)
        for module, names in [
            (os, ["system", "popen", "fork", "execv", "execve", "execvp", "spawnv", "posix_spawn"]),
            (subprocess, ["Popen", "run", "call", "check_call", "check_output"]),
            (builtins, ["open", "exec", "eval", "__import__"]),
        ]:
            for name in names:
                if hasattr(module, name):
                    patch.setattr(module, name, recorder(name, getattr(module, name)))
        _audit_log, _audit_thread = calls, owner
        try:
            yield calls
        finally:
            _audit_log, _audit_thread = None, None


def test_watching_sees_a_spawn() -> None:
    with watching() as calls:
        os.system("true")
    assert "system" in calls
    assert "os.system" in calls


def test_hostile_corpus_creates_no_file_and_spawns_nothing(tmp_path: Path) -> None:
    payloads = [*HOSTILE, *hostile_payloads_writing_to(tmp_path)]
    accepted = []
    with watching() as calls:
        for payload in payloads:
            try:
                compile_expression(payload)
            except ExpressionError:
                continue
            accepted.append(payload)
    assert accepted == []
    assert calls == []
    assert list(tmp_path.iterdir()) == []


def test_evaluation_creates_no_file_and_spawns_nothing() -> None:
    with watching() as calls:
        f = compile_expression("sqrt(x**2 + y**2) if x > y else clamp(x * 2 * pi, 0, 1)")
        f(x=np.linspace(0, 1, 50), y=0.5)
    assert calls == []


def test_module_never_names_eval_exec_or_compile() -> None:
    source = Path(expressions_module.__file__).read_text(encoding="utf-8")
    names = {node.id for node in ast.walk(ast.parse(source)) if isinstance(node, ast.Name)} | {
        node.attr for node in ast.walk(ast.parse(source)) if isinstance(node, ast.Attribute)
    }
    assert names.isdisjoint({"eval", "exec", "compile", "__import__", "getattr", "__builtins__"})

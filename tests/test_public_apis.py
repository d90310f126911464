"""No private API of numpy or scipy: nothing imports a name (module or attribute) that
starts with ``_`` from either. A private routine can vanish in any release; the public
call is the one with a promise."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LIBRARIES = ("numpy", "scipy")

#: Files still importing one, with what; the list is exact (a new one fails, and so does a
#: listed one that has gone). None left.
KNOWN: dict[str, set[str]] = {}


def private_imports(tree: ast.AST) -> set[str]:
    """Dotted names of private numpy/scipy modules or members that ``tree`` imports."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module] + [f"{node.module}.{alias.name}" for alias in node.names]
        else:
            continue
        for name in names:
            parts = name.split(".")
            if parts[0] in LIBRARIES and any(part.startswith("_") for part in parts[1:]):
                found.add(name)
    return found


def _project() -> dict[str, set[str]]:
    found = {}
    for folder in ("torsal", "tools", "tests"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            names = private_imports(ast.parse(path.read_text(encoding="utf-8")))
            if names:
                found[str(path.relative_to(ROOT))] = names
    return found


def test_no_private_numpy_or_scipy_import_beyond_the_known():
    assert _project() == KNOWN


def test_the_walker_sees_every_spelling():
    source = (
        "import numpy._core as c\nfrom numpy._core._multiarray_umath import c_einsum\n"
        "from scipy.interpolate import _dierckx\nfrom scipy.interpolate import BSpline\nimport numpy as np\n"
    )
    assert private_imports(ast.parse(source)) == {
        "numpy._core", "numpy._core._multiarray_umath", "numpy._core._multiarray_umath.c_einsum",
        "scipy.interpolate._dierckx",
    }

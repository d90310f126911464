"""The array type aliases and the dot helper each have one home in the project.

``FloatArray``, ``IntArray`` and ``BoolArray`` are defined in ``nodes/geometry/array_types.py``
and the row-wise dot product in ``nodes/geometry/vec_ops.py``; everything else imports them.
Definitions left in files this step did not reach are listed in :data:`KNOWN_COPIES`; the
list is exact for the files that exist, so a new copy fails and so does a listed one that
has gone (remove it from the list).
"""

from __future__ import annotations

import ast

import pytest

from tests.support.import_graph import PACKAGES, ROOT

ALIASES = ("FloatArray", "IntArray", "BoolArray")
DOT = ("dot", "_dot")
HOMES = {
    **{name: "torsal/nodes/geometry/array_types.py" for name in ALIASES},
    **{name: "torsal/nodes/geometry/vec_ops.py" for name in DOT},
}

#: Copies still to replace by an import: (file, name). None left.
KNOWN_COPIES: set[tuple[str, str]] = set()


def defined_names(tree: ast.Module) -> set[str]:
    """Names among :data:`ALIASES` and :data:`DOT` that ``tree`` defines, at any depth: an
    alias by an assignment, the dot helper by a ``def`` or a lambda (a variable called
    ``dot`` holding a result, an import or a bare annotation is no definition)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            found.update({node.name} & set(DOT))
            continue
        if isinstance(node, ast.Assign):
            targets = node.targets
        elif isinstance(node, ast.AnnAssign) and node.value is not None:
            targets = [node.target]
        else:
            continue
        names = {t.id for t in targets if isinstance(t, ast.Name)}
        found.update(names & set(ALIASES))
        if isinstance(node.value, ast.Lambda):
            found.update(names & set(DOT))
    return found


@pytest.fixture(scope="module")
def definitions() -> set[tuple[str, str]]:
    """(file, name) for every definition of an alias or a dot helper in the project."""
    found = set()
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            relative = path.relative_to(ROOT).as_posix()
            tree = ast.parse(path.read_text(encoding="utf-8"))
            found.update((relative, name) for name in defined_names(tree))
    return found


def test_each_alias_and_the_dot_helper_is_defined_in_its_home(definitions):
    for name, home in HOMES.items():
        if name != "_dot":
            assert (home, name) in definitions, (home, name)


def test_no_copy_of_an_alias_or_the_dot_helper_beyond_the_known_ones(definitions):
    copies = {(path, name) for path, name in definitions if HOMES[name] != path}
    new = sorted(copies - KNOWN_COPIES)
    assert not new, f"Defined again (import it from its home instead): {new}"


def test_every_known_copy_is_still_there(definitions):
    present = {(path, name) for path, name in KNOWN_COPIES if (ROOT / path).exists()}
    gone = sorted(present - definitions)
    assert not gone, f"Replaced by an import, remove from KNOWN_COPIES: {gone}"


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("FloatArray = NDArray[np.float64]\n", {"FloatArray"}),
        ("IntArray: TypeAlias = NDArray[np.intp]\n", {"IntArray"}),
        ("BoolArray = IntArray = NDArray[np.bool_]\n", {"BoolArray", "IntArray"}),
        ("def f():\n    def _dot(a, b):\n        return a @ b\n", {"_dot"}),
        ("_dot = lambda a, b: (a * b).sum(-1)\n", {"_dot"}),
        ("from torsal.nodes.geometry.array_types import FloatArray\nx: FloatArray\n", set()),
        ("def products(a, b):\n    dot = a @ b\n    return dot\n", set()),
    ],
    ids=["assignment", "annotated", "chained", "nested-def", "lambda", "import-and-annotation", "result"],
)
def test_a_definition_is_recognised_whatever_its_form(source, expected):
    assert defined_names(ast.parse(source)) == expected

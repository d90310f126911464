"""No import circles among the project's modules (engine, nodes, app, tools).

The graph is read statically (:mod:`tests.support.import_graph`): imports inside functions count,
and so do imports under ``if TYPE_CHECKING:`` (a type named both ways still ties two modules
together). Circles not yet untangled are listed in :data:`KNOWN_CIRCLES`; the list is
exact, so a new circle fails and so does a listed one that has gone (remove it from the list).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.support.import_graph import a_cycle, circles, import_graph

#: Circles still to untangle, each as its set of modules (none: keep it empty).
KNOWN_CIRCLES: set[frozenset[str]] = set()


@pytest.fixture(scope="module")
def graph() -> dict[str, set[str]]:
    return import_graph()


def _describe(graph: dict[str, set[str]], group: frozenset[str]) -> str:
    return f"{' -> '.join(a_cycle(graph, group))} (circle of {len(group)}: {', '.join(sorted(group))})"


def test_the_project_has_no_import_circle_beyond_the_known_ones(graph):
    new = [group for group in circles(graph) if group not in KNOWN_CIRCLES]
    assert not new, "Import circles: " + "; ".join(_describe(graph, group) for group in new)


def test_every_known_import_circle_is_still_there(graph):
    fixed = KNOWN_CIRCLES - set(circles(graph))
    assert not fixed, f"Untangled, remove from KNOWN_CIRCLES: {[sorted(group) for group in fixed]}"


def test_the_graph_reaches_every_layer(graph):
    expected = {
        "torsal.engine.solver", "torsal.nodes.geometry.curve_base", "torsal.app.cli", "tools.build_examples"
    }
    assert expected <= set(graph)
    assert "torsal.nodes.geometry.vec_ops" in graph["torsal.nodes.geometry.curve_base"]


# -- the walker itself, on a small package written for the purpose -----------------------


def _package(root: Path, files: dict[str, str]) -> dict[str, set[str]]:
    for name, text in files.items():
        path = root / "pkg" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return import_graph(root, ("pkg",))


def test_an_import_inside_a_function_closes_a_circle(tmp_path):
    graph = _package(tmp_path, {
        "__init__.py": "",
        "a.py": "from .b import f\n",
        "b.py": "def f():\n    from .a import g\n    return g\n",
    })
    assert circles(graph) == [frozenset({"pkg.a", "pkg.b"})]


def test_an_import_under_type_checking_counts_unless_asked_not_to(tmp_path):
    files = {
        "__init__.py": "",
        "a.py": "from .b import f\n",
        "b.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .a import g\n",
    }
    assert circles(_package(tmp_path, files)) == [frozenset({"pkg.a", "pkg.b"})]
    assert circles(import_graph(tmp_path, ("pkg",), type_checking=False)) == []


def test_importing_a_module_runs_its_package_init(tmp_path):
    # pkg.sub's __init__ imports pkg.a, which imports pkg.sub.c: a circle through the package
    graph = _package(tmp_path, {
        "__init__.py": "",
        "a.py": "from pkg.sub.c import x\n",
        "sub/__init__.py": "from .d import y\n",
        "sub/c.py": "x = 1\n",
        "sub/d.py": "from ..a import x\ny = x\n",
    })
    assert circles(graph) == [frozenset({"pkg.a", "pkg.sub", "pkg.sub.d"})]


def test_a_package_re_exporting_its_modules_is_no_circle(tmp_path):
    graph = _package(tmp_path, {
        "__init__.py": "",
        "sub/__init__.py": "from .c import x\n",
        "sub/c.py": "from . import d\nx = d.y\n",
        "sub/d.py": "y = 1\n",
    })
    assert circles(graph) == []


def test_the_message_names_one_loop_of_the_circle(tmp_path):
    graph = _package(tmp_path, {
        "__init__.py": "",
        "a.py": "import pkg.b\n",
        "b.py": "from pkg import c\n",
        "c.py": "from . import a\n",
    })
    (group,) = circles(graph)
    assert a_cycle(graph, group) == ["pkg.a", "pkg.b", "pkg.c", "pkg.a"]

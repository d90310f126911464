"""Bulk edits in the desktop app (``make bench``, under Xvfb): pasting 1,000 nodes into a
10,000-node graph, and deleting them again, each against the same edit of the engine's
graph alone (``add_node`` and ``connect``, ``remove_many``) timed in the same rounds: what
the window adds (canvas items, inspector, undo commands). The bars were absolute (half a
second each).

Run alone with::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python -m pytest tests/benchmarks/bench_gui_edits.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

Each figure is the best of three, measured in the real window (canvas, viewport and
inspector all listening), from the editor's call until the event loop has nothing
left to do, with the garbage collector paused; the solve the edit asks for runs on the
worker thread and is not counted.
``make test`` counts the node items the canvas builds (``tests/app/gui/canvas/test_canvas_scale.py``).
"""

from __future__ import annotations

import gc
import statistics
import time
from pathlib import Path

import pytest

from tests.app.gui.conftest import unavailable_reason

REASON = unavailable_reason()
if REASON:
    pytest.skip(REASON, allow_module_level=True)

from PySide6.QtWidgets import QApplication  # noqa: E402

from tests.benchmarks.timing import duration  # noqa: E402
from tests.support.fixtures_gui import *  # noqa: E402, F403 - the window, registry and dialog fixtures
from tests.support.fixtures_gui import wait_solved  # noqa: E402
from torsal.engine.graph import Graph  # noqa: E402
from torsal.engine.graphfile import write_graph  # noqa: E402
from torsal.engine.registry import Registry  # noqa: E402

NODES = 10_000
PASTED = 1_000
#: Bars, about twice the ratios measured on a loaded machine: paste 25–27× (0.36–1.2 s against
#: 14–41 ms), delete 18–44× (0.2–0.42 s against 4.5–23 ms: the engine's delete is so quick
#: that its ratio varies most).
PASTE_BAR, DELETE_BAR = 60.0, 90.0
ROUNDS = 3


def expression_chain(registry: Registry, count: int, columns: int = 100) -> Graph:
    """``count`` Expression nodes laid out in rows, each one's Result into the next one's x."""
    graph = Graph()
    for i in range(count):
        position = (200.0 * (i % columns), 120.0 * (i // columns))
        graph.add_node(registry.create("maths.Expression"), f"e{i}", position=position)
        if i:
            graph.connect(f"e{i - 1}", "Result", f"e{i}", "x")
    return graph


def open_big_graph(qtbot, window, registry: Registry, folder: Path) -> None:
    path = folder / "big.graph"
    write_graph(expression_chain(registry, NODES), path)
    window.doc.open(path)
    wait_solved(qtbot, window, timeout=120_000)


def timed(action) -> tuple[float, object]:
    """Wall time of ``action`` and the events it leaves. As in :mod:`tests.benchmarks.timing`
    the garbage collector is paused meanwhile: a full collection of the window's heap
    (half a second here) falls wherever earlier allocations make it due."""
    gc.collect()
    gc.disable()
    try:
        start = time.perf_counter()
        value = action()
        QApplication.processEvents()
        return time.perf_counter() - start, value
    finally:
        gc.enable()


def test_pasting_1000_nodes_into_10000_and_deleting_them_within_a_few_times_the_engine_edit(
    qtbot, window, registry, tmp_path
):
    open_big_graph(qtbot, window, registry, tmp_path)
    text = window.editor.copy([f"e{i}" for i in range(PASTED)])
    model = expression_chain(registry, NODES)  # the engine graph alone, no window
    pastes, deletes, model_pastes, model_deletes = [], [], [], []

    def paste() -> list[str]:  # as Edit ▸ Paste does: the pasted nodes end up selected
        ids = window.editor.paste(text, offset=(0.0, 20_000.0))
        window.scene.select_nodes(ids)
        return ids

    def model_paste() -> None:
        for i in range(PASTED):
            position = (200.0 * (i % 100), 20_000.0 + 120.0 * (i // 100))
            model.add_node(registry.create("maths.Expression"), f"p{i}", position=position)
            if i:
                model.connect(f"p{i - 1}", "Result", f"p{i}", "x")

    for _ in range(ROUNDS):
        seconds, ids = timed(paste)
        pastes.append(seconds)
        assert len(ids) == PASTED and len(window.doc.graph.nodes) == NODES + PASTED
        wait_solved(qtbot, window, timeout=60_000)
        model_pastes.append(timed(model_paste)[0])
        seconds, _ = timed(lambda ids=ids: window.editor.delete(ids))
        deletes.append(seconds)
        assert len(window.doc.graph.nodes) == NODES
        wait_solved(qtbot, window, timeout=60_000)
        model_deletes.append(timed(lambda: model.remove_many([f"p{i}" for i in range(PASTED)]))[0])
        assert len(model.nodes) == NODES
    undo, _ = timed(window.doc.undo_stack.undo)  # the last deletion, restored (not a bar)
    assert len(window.doc.graph.nodes) == NODES + PASTED
    paste_ratio = statistics.median(w / m for w, m in zip(pastes, model_pastes, strict=True))
    delete_ratio = statistics.median(w / m for w, m in zip(deletes, model_deletes, strict=True))
    print(
        f"\npaste {PASTED:,} nodes into {NODES:,}: best {duration(min(pastes))}, the engine's graph alone "
        f"{duration(min(model_pastes))}: ratio {paste_ratio:.2f}; "
        f"delete them: best {duration(min(deletes))}, alone {duration(min(model_deletes))}: "
        f"ratio {delete_ratio:.2f} (medians of {ROUNDS} pairs); "
        f"undo the deletion: {duration(undo)}"
    )
    assert paste_ratio <= PASTE_BAR
    assert delete_ratio <= DELETE_BAR

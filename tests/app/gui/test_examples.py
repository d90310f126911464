"""Each example opens, solves, fills the viewport with the expected actors, and is
photographed (PNG per example in tests/app/gui/screenshots/, to look at)."""

from __future__ import annotations

import itertools

import pytest
import trimesh
from PySide6.QtGui import QImage

from tests.support.fixtures_gui import EXAMPLES, FIXTURES, SCREENSHOTS, wait_solved
from torsal.app.gui.viewport.datasets import mesh_scalars
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.surface_base import Surface

#: How long to wait for an example's solve: a wait, not a timed assertion (the canopy's solve
#: takes ~21 CPU-s; beside the other half of the suite's workers on two cores it ran past 30 s).
SOLVE_BUDGET_MS = 120000
CASES = [*sorted(EXAMPLES.glob("*.graph")), FIXTURES / "showcase.graph"]
#: Counted by hand: first-steps makes only numbers; the showcase makes a curve (1), a ruled
#: surface (shaded + its rulings + the Rulings output: 3), a coloured mesh (1), points (1),
#: a vector (1).
KNOWN_ACTORS = {"first-steps.graph": 0, "showcase.graph": 7}


def expected_actors(doc) -> int:
    """Actors a graph should show, counted from its results by kernel type: one per kind of
    geometry per previewed node, surfaces with straight rulings adding their rulings, and
    one per mesh that carries colours. Outputs declared ``preview=False`` are not drawn."""
    count = 0
    for node_id, record in doc.graph.nodes.items():
        result = doc.results.get(node_id)
        if result is None or not (record.preview and record.enabled) or record.type_id == "params.Panel":
            continue
        kinds: set[str] = set()
        drawn = record.node.previewed_outputs()
        trees = (tree for port, tree in result.outputs.items() if port in drawn)
        for value in (v for tree in trees for v in tree.all_items()):
            if isinstance(value, Vector):
                kinds.add("vectors")
            elif isinstance(value, Point | Plane):
                kinds.add("points")
            elif isinstance(value, trimesh.Trimesh):
                if mesh_scalars(value) is not None:
                    count += 1
                else:
                    kinds.add("surfaces")
            elif isinstance(value, Surface):
                kinds.add("surfaces")
                if value.is_ruled:
                    kinds.add("rulings")
            elif hasattr(value, "to_mesh"):
                kinds.add("surfaces")
            elif isinstance(value, Curve):
                kinds.add("curves")
            elif hasattr(type(value), "preview_geometry"):  # draws itself (a cut sheets' Preview)
                drawn_by_itself = value.preview_geometry()
                kinds.update(kind for kind, items in (("curves", drawn_by_itself.polylines),
                                                      ("points", drawn_by_itself.points)) if len(items))
        count += len(kinds)
    return count


@pytest.mark.parametrize("path", CASES, ids=lambda p: p.name)
def test_example_opens_renders_its_actors_is_photographed_and_its_boxes_do_not_overlap(qtbot, window, path):
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window, timeout=SOLVE_BUDGET_MS)
    qtbot.wait(100)  # the canvas fits itself to the graph on the next turns
    outcome = window.doc.last_outcome
    assert outcome is not None and not outcome.cancelled
    assert outcome.count("error") == 0, window.log.node_rows
    expected = KNOWN_ACTORS.get(path.name, expected_actors(window.doc))
    assert window.viewport.preview_actor_count() == expected

    SCREENSHOTS.mkdir(exist_ok=True)
    shot = window.grab_window(SCREENSHOTS / f"{path.stem}.png")
    items = list(window.scene.nodes.values())
    for a, b in itertools.combinations(items, 2):
        overlap = (
            a.sceneBoundingRect()
            .adjusted(1, 1, -1, -1)
            .intersects(b.sceneBoundingRect().adjusted(1, 1, -1, -1))
        )
        assert not overlap, f"{a.node_id} overlaps {b.node_id}"
    groups = [g for g in window.scene.groups.values() if g.isVisible()]
    for a, b in itertools.combinations(groups, 2):  # the boxes as the canvas draws them
        assert not a.sceneBoundingRect().intersects(b.sceneBoundingRect()), (
            f"group {a.group_id} overlaps group {b.group_id}"
        )

    image = QImage(str(shot))
    assert image.width() >= 1200 and image.height() >= 800
    if expected:  # the viewport shows something besides its background
        interactor = window.viewport.interactor
        corner = interactor.mapTo(window, interactor.rect().topLeft())
        colours = {
            image.pixel(corner.x() + x, corner.y() + y)
            for x in range(20, interactor.width() - 20, 17)
            for y in range(20, interactor.height() - 20, 17)
        }
        assert len(colours) > 50

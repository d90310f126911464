"""ExportCutSheet looks at the cancel token inside its layout: before each panel's outline,
each label and, while the engraving font loads, every few ms (counted, not timed: the
50 ms figure is in tests/benchmarks/bench_cancel.py)."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import shapely
from shapely.ops import polylabel

from tests.support.cancelling import cancel_at_look
from tests.support.io_helpers import random_panels
from tests.support.node_helpers import tree
from torsal.engine.datatree import DataTree
from torsal.engine.node import Cancelled
from torsal.nodes.common.files import FileFailure
from torsal.nodes.geometry.watch import watched
from torsal.nodes.io.cutting import ExportCutSheet
from torsal.nodes.io.formats import cutfiles, labels


class Stop(Exception):
    """Raised by a test's check to say "cancelled here"."""


def _solve(node: ExportCutSheet, panels: list) -> tuple:
    empty = DataTree()
    return node.solve("", tree({(0,): panels}), empty, empty, 2500.0, 1250.0, 10.0, 0.0, 10.0, True, "m",
                      None, "Shelf", False, 10.0, 0, False, empty, 50.0, False)


@pytest.fixture
def font_loaded() -> None:
    labels._font()  # outside a watched block: waits for the font, so no look is spent on it


def test_lay_out_looks_once_before_each_outline_and_once_before_each_label(font_loaded):
    looks = []
    with watched(lambda: looks.append(1)):
        layout = cutfiles.lay_out(random_panels(5, seed=3), text_height=10.0)
    assert len(layout.parts) == 5
    assert len(looks) == 2 * 5


def test_a_cancel_from_the_layout_stops_the_node_at_that_look(font_loaded):
    node = ExportCutSheet()
    looks = cancel_at_look(node, 8)  # cancelled at its 8th look: the third label (after 6 outlines)
    with pytest.raises(Cancelled):
        _solve(node, random_panels(6, seed=1))
    assert len(looks) == 8


def test_the_font_load_looks_at_the_token_and_a_cancel_there_stops_it():
    labels._loading.cache_clear()  # the next call loads the font again, on its thread

    def check() -> None:
        raise Stop

    with pytest.raises(Stop), watched(check):
        labels._font()
    assert labels._font().get_text_glyph_paths("P", cap_height=1.0)  # the load went on


def test_a_label_that_fits_at_the_centroid_does_not_look_for_the_pole(monkeypatch):
    calls = []
    monkeypatch.setattr(labels, "polylabel", lambda *a, **k: calls.append(1) or polylabel(*a, **k))
    square = np.array([[0.0, 0.0], [200.0, 0.0], [200.0, 200.0], [0.0, 200.0]])
    outlines, size = labels.place_label("P-001", square, 10.0)
    assert size == 10.0 and outlines and not calls


def test_a_label_that_does_not_fit_at_the_centroid_is_centred_on_the_pole_of_inaccessibility():
    # a C shape: its centroid lies in the notch, outside the panel
    shape = np.array([[0.0, 0.0], [300.0, 0.0], [300.0, 60.0], [60.0, 60.0], [60.0, 240.0], [300.0, 240.0],
                      [300.0, 300.0], [0.0, 300.0]])
    polygon = shapely.Polygon(shape)
    assert not polygon.contains(polygon.centroid)
    outlines, size = labels.place_label("P-001", shape, 10.0)
    pole = np.asarray(polylabel(polygon, tolerance=1e-4 * np.sqrt(polygon.area)).coords[0])
    every = np.vstack(outlines)
    centre = (every.min(axis=0) + every.max(axis=0)) / 2
    assert size == 10.0
    assert np.allclose(centre, pole, atol=1e-6)


def test_the_font_is_found_in_matplotlib_without_importing_it():
    code = ("import sys; from torsal.nodes.io.formats.labels import font_file; "
            "print(font_file()); print('matplotlib' in sys.modules)")
    found, imported = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                     check=True).stdout.split()
    package = Path(importlib.util.find_spec("matplotlib").origin).parent
    assert Path(found) == package / "mpl-data" / "fonts" / "ttf" / "DejaVuSans.ttf"
    assert imported == "False"


def test_a_missing_font_says_what_to_install(monkeypatch):
    monkeypatch.setattr(labels.importlib.util, "find_spec", lambda name: None)
    with pytest.raises(FileFailure, match=r"matplotlib.*TextHeight"):
        labels.font_file()

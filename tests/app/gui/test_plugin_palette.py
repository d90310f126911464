"""The worked example plug-in (examples/plugin), installed as pip installs it, shows in the
app's palette as a tab of its own; clicking its button places the node, which solves."""

from __future__ import annotations

import importlib

import pytest
from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import close_window, make_window, wait_solved
from tests.support.plugin_install import EXAMPLE, install, write_plugin
from torsal.nodes.catalogue import default_registry


@pytest.fixture(scope="module")
def waves(tmp_path_factory):
    return install([EXAMPLE], tmp_path_factory.mktemp("plugins") / "waves")


def test_the_example_plugin_is_in_the_palette_and_places_a_working_node(qtbot, waves, config_folder,
                                                                        monkeypatch):
    monkeypatch.syspath_prepend(str(waves))
    importlib.invalidate_caches()
    registry = default_registry()
    assert registry.problems == []
    window = make_window(qtbot, registry, config_folder)
    try:
        palette = window.palette
        assert "waves" in palette.tab_palettes
        tabs = palette.tabBar()
        tab = tabs.tabRect(palette.tab_palettes.index("waves"))
        QTest.mouseClick(tabs, Qt.MouseButton.LeftButton, pos=tab.center())
        assert palette.tabText(palette.currentIndex()) == "Waves"
        button = palette.findChild(object, "palette:waves.Wave")
        assert button is not None and button.isVisible()
        QTest.mouseClick(button, Qt.MouseButton.LeftButton)
        wait_solved(qtbot, window)
        (node_id,) = [i for i, r in window.doc.graph.nodes.items() if r.type_id == "waves.Wave"]
        result = window.doc.solver.result(node_id)
        assert result.state == "ok"
        assert result.outputs["Height"].to_dict() == {"{0}": [0.0]}  # sin(2π · 0): X defaults to 0
    finally:
        close_window(window)


def test_a_broken_plugin_is_in_the_message_log(qtbot, tmp_path, config_folder, monkeypatch):
    broken = "raise RuntimeError('oops')\n"
    source = write_plugin(tmp_path / "broken", "torsal-broken", "torsal_broken", broken)
    monkeypatch.syspath_prepend(str(install([source], tmp_path / "site")))
    importlib.invalidate_caches()
    window = make_window(qtbot, default_registry(), config_folder)
    try:
        logged = [text for _, level, text in window.log.app_messages if level == "warning"]
        assert len(logged) == 1 and "'torsal-broken'" in logged[0] and "oops" in logged[0]
    finally:
        close_window(window)

"""The palette imports a palette's node modules only when its tab is first shown."""

from __future__ import annotations

from torsal.app.gui.palette import Palette
from torsal.engine.registry import Registry


def lazy_registry() -> Registry:
    registry = Registry()
    registry.register_lazy("params", "torsal.nodes.params.sliders")
    registry.register_lazy("maths", "torsal.nodes.maths.expression")
    return registry


def test_populating_the_palette_fills_only_the_tab_shown(qtbot):
    registry = lazy_registry()
    palette = Palette(registry)
    qtbot.addWidget(palette)
    palette.populate()
    assert palette.filled == {"params"}
    assert set(registry._lazy) == {"maths"}  # not imported yet
    assert palette.findChild(object, "palette:params.NumberSlider") is not None


def test_showing_a_tab_fills_it_with_its_palettes_nodes(qtbot):
    registry = lazy_registry()
    palette = Palette(registry)
    qtbot.addWidget(palette)
    palette.populate()
    palette.setCurrentIndex(palette.tab_palettes.index("maths"))
    assert "maths" in palette.filled and not registry._lazy
    assert palette.findChild(object, "palette:maths.Expression") is not None
    assert palette.tabText(palette.currentIndex()) == "Maths"

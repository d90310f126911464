"""Colour bars: one legend per quantity and range, shared by the nodes that show it."""

from __future__ import annotations

from tests.support.fixtures_gui import EXAMPLES, wait_solved


def test_two_analyses_of_the_same_quantity_share_one_colour_bar_until_both_are_gone(qtbot, window):
    assert window.open_file(EXAMPLES / "textbook-ruled-surfaces.graph", ask=False)
    wait_solved(qtbot, window)
    preview, plotter = window.viewport.preview, window.viewport.plotter
    assert len(plotter.scalar_bars) == 1
    (title,) = plotter.scalar_bars.keys()
    assert title.startswith("min(") and "[" not in title  # shared: it names no node
    assert preview.bar_users[title] == {"hypar_analysis", "torus_analysis"}

    window.editor.set_preview(["torus_analysis"], False)
    wait_solved(qtbot, window)
    assert list(plotter.scalar_bars.keys()) == [title]  # the hypar still uses it
    assert preview.bar_users[title] == {"hypar_analysis"}

    window.editor.set_preview(["hypar_analysis"], False)
    wait_solved(qtbot, window)
    assert len(plotter.scalar_bars) == 0 and not preview.bar_users

    window.doc.undo_stack.undo()
    wait_solved(qtbot, window)
    assert list(plotter.scalar_bars.keys()) == [title]


def test_a_colour_bar_title_spells_absolute_values_out_as_vtk_drops_the_bars():
    from torsal.app.gui.viewport.preview import ascii_title

    assert ascii_title("min(|k1|, |k2|), 1/m") == "min(abs(k1), abs(k2)), 1/m"
    assert ascii_title("max |κ| · r²") == "max abs(k) * r^2"

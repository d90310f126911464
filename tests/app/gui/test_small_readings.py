"""Small things that read wrong otherwise: Help renders its Markdown, the status bar counts
"1 node", the undo history names the slider a drag changed."""

from __future__ import annotations

from PySide6.QtCore import QPoint

from tests.support.fixtures_gui import drag, right_click, slider_handle, title_point, wait_solved


def test_help_renders_markdown_instead_of_showing_its_marks(qtbot, first_steps):
    window = first_steps
    window.view.centerOn(window.scene.nodes["total"])
    right_click(window, title_point(window, "total"), "Help")
    text = window.inspector.help.toPlainText()
    assert "Expression" in text and "maths.Expression" in text
    # the docstring's ``sqrt(x**2 + y**2)`` is code: no backticks shown, its text intact, monospaced
    assert "``" not in text and "sqrt(x**2 + y**2)" in text
    html = window.inspector.help.toHtml()
    code = html.index("sqrt(x**2 + y**2)")
    assert "monospace" in html[html.rfind("<span", 0, code):code]


def test_the_status_bar_says_one_node_not_one_nodes(qtbot, window):
    window.editor.add_node("params.NumberSlider", (0.0, 0.0))
    wait_solved(qtbot, window)
    assert window.status.solve_label.text().startswith("Solved 1 node in ")


def test_a_slider_drag_is_undone_under_the_sliders_name(qtbot, first_steps):
    window = first_steps
    start, _left, right = slider_handle(window, "width")
    drag(window, start, QPoint(min(right, start.x() + 30), start.y()))
    wait_solved(qtbot, window)
    assert window.doc.undo_stack.undoText() == "Set value of Panel width (m)"

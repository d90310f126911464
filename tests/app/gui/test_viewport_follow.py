"""The 3D viewport frames a file's geometry when it opens, follows geometry that grows out
of view, and leaves the camera alone once the user has moved it."""

from __future__ import annotations

from tests.support.fixtures_gui import EXAMPLES, wait_solved


def circle(qtbot, window, radius: float) -> str:
    node_id = window.editor.add_node("curves.Circle", (40.0, 40.0))
    window.editor.set_input_value(node_id, "Radius", radius)
    wait_solved(qtbot, window)
    return node_id


def test_an_opened_file_is_framed(qtbot, window):
    assert window.open_file(EXAMPLES / "first-steps.graph", ask=False)
    wait_solved(qtbot, window)
    assert window.viewport.bounds_in_view()


def test_a_circle_grown_out_of_view_is_followed(qtbot, window):
    node_id = circle(qtbot, window, 1.0)
    panel = window.viewport
    assert panel.bounds_in_view()
    window.editor.set_input_value(node_id, "Radius", 10.0)
    wait_solved(qtbot, window)
    width = float(panel.preview.bounds()[1, 0] - panel.preview.bounds()[0, 0])
    assert abs(width - 20.0) < 0.02  # the grown circle (a polyline through points on it)
    assert panel.bounds_in_view()


def test_a_camera_the_user_moved_is_not_followed(qtbot, window):
    node_id = circle(qtbot, window, 1.0)
    panel = window.viewport
    panel.plotter.renderer.GetActiveCamera().Zoom(1.5)  # as the mouse wheel does
    assert panel.user_moved_camera()
    before = panel.plotter.renderer.GetActiveCamera().GetPosition()
    window.editor.set_input_value(node_id, "Radius", 10.0)
    wait_solved(qtbot, window)
    assert panel.plotter.renderer.GetActiveCamera().GetPosition() == before
    assert not panel.bounds_in_view()
    panel.set_view("extents")  # Zoom extents: the app frames it and follows again
    assert panel.bounds_in_view() and not panel.user_moved_camera()

"""While a cluster is edited, the model outside it stays in the viewport, dimmed.

Grasshopper keeps the whole document's preview while a cluster is open; the inside's
geometry is then read against the model it belongs to. The graph outside (the frame the
canvas left) is drawn once on entering, light grey and translucent, unpickable and apart
from the preview's own actors (so it never counts for zoom extents or selection). The
cluster's own instance is left out: its geometry is what is being edited inside.
"""

from __future__ import annotations

from typing import Any

from torsal.app.gui.viewport.datasets import dataset
from torsal.app.gui.viewport.preview import drawn_outputs, prepare, previewed

PREFIX = "outside:"
COLOUR = "#b8bcc4"
OPACITY = 0.3


def outside_names(plotter: Any) -> list[str]:
    return [name for name in plotter.actors if str(name).startswith(PREFIX)]


def show_outside(plotter: Any, doc: Any) -> int:
    """Draw the graph around the cluster being edited (none outside a cluster); how many
    actors it drew."""
    for name in outside_names(plotter):
        plotter.remove_actor(name, render=False)
    if not doc.frames:
        return 0
    frame = doc.frames[-1]
    drawn = 0
    for node_id in sorted(previewed(frame.graph, frame.results) - {frame.instance_id}):
        ready = prepare(frame.results[node_id], drawn_outputs(frame.graph, node_id))
        for index, piece in enumerate(ready.pieces):
            style: dict[str, Any] = {"color": COLOUR, "opacity": OPACITY, "pickable": False}
            if piece.kind in ("curves", "rulings", "vectors"):
                style["line_width"] = 1.0
            elif piece.kind == "points":
                style["point_size"] = 5.0
            plotter.add_mesh(dataset(piece), name=f"{PREFIX}{node_id}:{index}", scalars=None,
                             reset_camera=False, render=False, **style)
            drawn += 1
    return drawn

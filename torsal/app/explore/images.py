"""Pictures of solved variants, for the ``img:`` column of a Design Explorer table.

``torsal sweep --images`` draws each variant as the app's viewport would show it — the
geometry of every node with preview on, through the same preview protocol
(:func:`torsal.nodes.common.preview.preview_of`) — from one fixed camera, so the pictures of
a sweep compare at a glance: meshes shaded by a light from the camera's side, curves and
rulings as lines, points as dots, on white, without axes. The camera looks at the
variant's own bounding box (every picture is framed on its model) from the south-east
and 30° above, as Rhino's Perspective view does. Drawing uses matplotlib's Agg canvas:
no display, no Qt or VTK, so it runs on a sweep's workers, a dask worker included.
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

import numpy as np

from torsal.engine.graph import Graph
from torsal.engine.solver import ERROR, Solver
from torsal.engine.write_path import write_file

#: Picture size in pixels (width, height).
SIZE = (640, 480)
#: The camera: degrees above the ground and round from the x axis (Rhino's Perspective).
ELEVATION, AZIMUTH = 30.0, -60.0
#: Most triangles drawn: beyond it evenly spaced ones are kept (matplotlib sorts every
#: polygon for each picture; a sweep's thumbnail does not need more).
MAX_TRIANGLES = 40_000
#: Where the light comes from (unit vector, world coordinates): above, behind the camera.
LIGHT = np.array([0.35, -0.6, 0.72]) / np.linalg.norm([0.35, -0.6, 0.72])
SURFACE_RGB = np.array([0.78, 0.80, 0.84])
LINE_RGB = "#2b4a6f"
POINT_RGB = "#c0392b"


def previewed_values(graph: Graph, solver: Solver) -> list[Any]:
    """Every value the viewport would draw: the previewed outputs of the enabled nodes
    with preview on that are not in error (panels show text, not geometry)."""
    values: list[Any] = []
    for node_id, record in graph.nodes.items():
        if not record.shows_geometry:
            continue
        result = solver.result(node_id)
        if result.state == ERROR:
            continue
        drawn = record.node.previewed_outputs()
        for port, tree in result.outputs.items():
            if port in drawn:
                values.extend(item for item in tree.all_items() if item is not None)
    return values


def render(values: list[Any], path: Path, size: tuple[int, int] = SIZE) -> bool:
    """Draw ``values`` into the PNG ``path``; False (and no file) when none of them is geometry."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    from torsal.nodes.common.preview import preview_of

    triangles, shades, lines, points = [], [], [], []
    for value in values:
        geometry = preview_of(value)
        if geometry is None:
            continue
        for mesh in geometry.meshes:
            faces = np.asarray(mesh.faces, dtype=int)
            if len(faces) == 0:
                continue
            corners = np.asarray(mesh.vertices, dtype=float)[faces]
            normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
            length = np.linalg.norm(normal, axis=1, keepdims=True)
            normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
            triangles.append(corners)
            shades.append(np.abs(normal @ LIGHT))  # two-sided: a sheet is lit on either face
        drawn = (*geometry.polylines, *geometry.rulings)
        lines.extend(np.asarray(p, dtype=float) for p in drawn if len(p) > 1)
        points.extend(np.asarray(p, dtype=float).reshape(-1, 3) for p in geometry.points)
    if not (triangles or lines or points):
        return False
    every = [*(t.reshape(-1, 3) for t in triangles), *lines, *points]
    stacked = np.vstack(every)
    stacked = stacked[np.isfinite(stacked).all(axis=1)]
    if len(stacked) == 0:
        return False
    low, high = stacked.min(axis=0), stacked.max(axis=0)
    span = np.maximum(high - low, 1e-9 * max(float(np.max(high - low)), 1e-300))

    figure = Figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
    FigureCanvasAgg(figure)
    axes = figure.add_axes((0, 0, 1, 1), projection="3d")
    axes.set_axis_off()
    axes.view_init(elev=ELEVATION, azim=AZIMUTH)
    if triangles:
        corners = np.concatenate(triangles)
        shade = np.concatenate(shades)
        if len(corners) > MAX_TRIANGLES:
            keep = np.linspace(0, len(corners) - 1, MAX_TRIANGLES).astype(int)
            corners, shade = corners[keep], shade[keep]
        colours = np.clip(SURFACE_RGB[None, :] * (0.45 + 0.55 * shade[:, None]), 0.0, 1.0)
        axes.add_collection3d(Poly3DCollection(corners, facecolors=colours, edgecolors="none"))
    if lines:
        axes.add_collection3d(Line3DCollection(lines, colors=LINE_RGB, linewidths=0.5, alpha=0.8))
    if points:
        dots = np.vstack(points)
        axes.scatter(dots[:, 0], dots[:, 1], dots[:, 2], s=6, c=POINT_RGB, depthshade=False)
    centre = 0.5 * (low + high)
    half = 0.5 * span
    axes.set_xlim(centre[0] - half[0], centre[0] + half[0])
    axes.set_ylim(centre[1] - half[1], centre[1] + half[1])
    axes.set_zlim(centre[2] - half[2], centre[2] + half[2])
    axes.set_box_aspect(tuple(span / span.max()), zoom=1.0)
    picture = io.BytesIO()
    figure.savefig(picture, format="png", facecolor="white")
    # DIR/N.png beside the tables, DIR resolved once by the command: no link followed
    write_file(path, picture.getvalue(), base=path.parent, backup=False)
    return True

"""Picking a cut-sheet part in the viewport: a click on a part of ExportCutSheet's sheets
(:class:`~torsal.nodes.io.sheet_preview.SheetPreview`) highlights that part and the 3D
strip it was unrolled from on the model, as selecting a part in a nesting plug-in shows
where it goes; a click on a strip of the model does the same for the part cut from it
(the nearest strip to the point VTK's cell picker finds, within :data:`NEAR` of its size).
A press and release within :data:`CLICK_PIXELS` is a click (a drag orbits the camera as
before); a click on neither clears the highlight. When the layout changes (a better
nesting arrives), the part keeps its highlight by its ID.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from torsal.app.gui import theme
from torsal.engine.solver import NodeResult

if TYPE_CHECKING:
    from torsal.nodes.io.sheet_preview import SheetPreview

#: A left press and release at most this many pixels apart are a click, not a drag.
CLICK_PIXELS = 4
#: A point picked on the model belongs to the nearest strip when this close to its
#: tessellation, as a share of the strip's size.
NEAR = 0.01
#: Actor names of the highlight.
PART_ACTOR, STRIP_ACTOR = "picked-part", "picked-strip"


def sheet_previews(results: dict[str, NodeResult], shown: set[str]) -> list[tuple[str, SheetPreview]]:
    """(node id, preview) of every cut-sheet preview drawn in the viewport (asked on a
    click: the cut-sheet module, with its shapely, is not imported to start the viewport)."""
    from torsal.nodes.io.sheet_preview import SheetPreview

    found = []
    for node_id in sorted(shown):
        result = results.get(node_id)
        if result is None:
            continue
        for tree in result.outputs.values():
            found += [(node_id, v) for v in tree.all_items() if isinstance(v, SheetPreview)]
    return found


class PartPicker:
    """Listens to the interactor's left clicks and highlights the part under one (see the module)."""

    def __init__(self, plotter: Any, previews: Callable[[], list[tuple[str, SheetPreview]]],
                 changed: Callable[[], None]) -> None:
        self.plotter = plotter
        self.previews = previews
        self.changed = changed  #: asks for a render
        self.picked: tuple[str, str] | None = None  #: (node id, part ID) highlighted
        self._down: tuple[int, int] | None = None
        self._triangles: dict[int, tuple[object, np.ndarray]] = {}  # strip id -> (strip, triangles)
        plotter.iren.add_observer("LeftButtonPressEvent", self._pressed)
        plotter.iren.add_observer("LeftButtonReleaseEvent", self._released)

    def _pressed(self, *_args: object) -> None:
        self._down = tuple(self.plotter.iren.interactor.GetEventPosition())

    def _released(self, *_args: object) -> None:
        up = tuple(self.plotter.iren.interactor.GetEventPosition())
        down, self._down = self._down, None
        if down is not None and max(abs(up[0] - down[0]), abs(up[1] - down[1])) <= CLICK_PIXELS:
            self.pick(*up)

    def _ray(self, x: float, y: float) -> tuple[np.ndarray, np.ndarray]:
        """The points of the near and far clipping planes under display pixel (x, y)."""
        renderer = self.plotter.renderer
        ends = []
        for depth in (0.0, 1.0):
            renderer.SetDisplayPoint(float(x), float(y), depth)
            renderer.DisplayToWorld()
            world = np.array(renderer.GetWorldPoint(), dtype=float)
            ends.append(world[:3] / world[3])
        return ends[0], ends[1]

    def pick(self, x: float, y: float) -> tuple[str, str] | None:
        """Highlight the part under display pixel (x, y) (VTK's, from the lower left) and
        its strip; clear the highlight when there is none. Returns (node id, part ID)."""
        near, far = self._ray(x, y)
        hit = None
        for node_id, preview in self.previews():
            span = far[2] - near[2]
            if abs(span) <= 1e-12 * max(1.0, float(np.abs(far - near).max())):
                continue  # looking along the sheets' plane
            t = (preview.origin[2] - near[2]) / span
            if not 0.0 <= t <= 1.0:
                continue  # the sheets' plane is behind the camera or beyond the far plane
            index = preview.part_at(near + t * (far - near))
            if index is not None:
                hit = (node_id, preview.layout.parts[index].id)
                break
        self.picked = hit or self._strip_at(x, y)
        self.show()
        return self.picked

    def _strip_at(self, x: float, y: float) -> tuple[str, str] | None:
        """(node id, part ID) of the part cut from the strip under display pixel (x, y)."""
        from vtkmodules.vtkRenderingCore import vtkCellPicker

        picker = vtkCellPicker()
        picker.SetTolerance(1e-4)
        if not picker.Pick(float(x), float(y), 0.0, self.plotter.renderer) or picker.GetCellId() < 0:
            return None
        point = np.array(picker.GetPickPosition(), dtype=float)
        best: tuple[float, str, str] | None = None
        for node_id, preview in self.previews():
            for index, strip in enumerate(preview.strips):
                triangles = self._strip_triangles(strip)
                if not len(triangles):
                    continue
                gap = _distance(point, triangles)
                size = float(np.ptp(triangles.reshape(-1, 3), axis=0).max())
                if gap <= NEAR * size and (best is None or gap < best[0]):
                    best = (gap, node_id, preview.layout.parts[index].id)
        return None if best is None else (best[1], best[2])

    def _strip_triangles(self, strip: object) -> np.ndarray:
        """``(m, 3, 3)``: the triangles of ``strip`` as the viewport draws it (kept per strip)."""
        from torsal.app.gui.viewport.datasets import collect, pieces

        kept = self._triangles.get(id(strip))
        if kept is None or kept[0] is not strip:
            if len(self._triangles) > 1000:
                self._triangles.clear()
            drawn = [p.points[p.faces] for p in pieces(collect([strip]))
                     if p.kind == "surfaces" and p.faces is not None] if strip is not None else []
            kept = (strip, np.concatenate(drawn) if drawn else np.zeros((0, 3, 3)))
            self._triangles[id(strip)] = kept
        return kept[1]

    def show(self) -> None:
        """Draw the highlight of :attr:`picked` in the current layout (after a pick, or when the
        results changed)."""
        for name in (PART_ACTOR, STRIP_ACTOR):
            self.plotter.remove_actor(name, render=False)
        if self.picked is not None:
            node_id, part_id = self.picked
            for owner, preview in self.previews():
                ids = [p.id for p in preview.layout.parts]
                if owner == node_id and part_id in ids:
                    self._draw(preview, ids.index(part_id))
                    break
            else:
                self.picked = None
        self.changed()

    def _draw(self, preview: SheetPreview, index: int) -> None:
        import pyvista as pv

        from torsal.app.gui.viewport.datasets import collect, dataset, pieces

        contour = preview.part_polylines()[index][0]
        self.plotter.add_mesh(pv.lines_from_points(contour), color=theme.PREVIEW_PICKED, line_width=4,
                              name=PART_ACTOR, pickable=False, reset_camera=False, render=False)
        strip = preview.strip_of(index)
        if strip is None:
            return
        drawn = [p for p in pieces(collect([strip])) if p.kind == "surfaces"]
        if drawn:
            meshes = [dataset(p) for p in drawn]
            mesh = meshes[0] if len(meshes) == 1 else pv.merge(meshes)
            self.plotter.add_mesh(mesh, color=theme.PREVIEW_PICKED, name=STRIP_ACTOR, pickable=False,
                                  reset_camera=False, render=False)


def _distance(point: np.ndarray, triangles: np.ndarray) -> float:
    """How far ``point`` lies from ``(m, 3, 3)`` triangles: from the plane of one whose
    inside it projects into, else from the nearest vertex (an upper bound, exact for a
    point on the surface)."""
    a, e1, e2 = triangles[:, 0], triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    normal = np.cross(e1, e2)
    area2 = np.einsum("ij,ij->i", normal, normal)
    ok = area2 > 0
    rel = point - a
    # barycentric coordinates of the point's projection onto each triangle's plane
    u = np.einsum("ij,ij->i", np.cross(rel, e2), normal) / np.where(ok, area2, 1.0)
    v = np.einsum("ij,ij->i", np.cross(e1, rel), normal) / np.where(ok, area2, 1.0)
    inside = ok & (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1 + 1e-9)
    vertices = float(np.linalg.norm(triangles.reshape(-1, 3) - point, axis=1).min())
    if not inside.any():
        return vertices
    planes = np.abs(np.einsum("ij,ij->i", rel[inside], normal[inside])) / np.sqrt(area2[inside])
    return min(vertices, float(planes.min()))

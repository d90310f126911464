"""The Placement and Plane inputs of the nodes that output a flat development.

IsoMapping and SurfacePatching compute a development in its own XY frame; these two
inputs say where its flat outputs are shown. Placement is a whole number, as a
Grasshopper value list gives it:

- 0 **Beside model** (the default): flat, parallel to the world XY plane at the
  height of the model's lowest point, beside the model's bounding box in +X with a gap
  of a fifth of the model's size, its front edge (least y) level with the model's;
- 1 **Origin**: in its own frame (the first ruling from the origin up the Y axis);
- 2 **On plane**: its own frame carried onto Plane (origin to the plane's origin, X
  and Y to the plane's axes).

Each is a rigid motion, so no length, angle or area changes.
"""

from __future__ import annotations

from typing import Any

from numpy.typing import ArrayLike

from torsal.engine.node import In, Node
from torsal.engine.types import INTEGER, PLANE
from torsal.nodes.common.convert import kernel_plane
from torsal.nodes.geometry.development_placement import WORLD_XY, beside_model
from torsal.nodes.geometry.vectors import Plane

BESIDE_MODEL, ORIGIN, ON_PLANE = 0, 1, 2
#: The choices by number, as a value list names them.
NAMES = {BESIDE_MODEL: "Beside model", ORIGIN: "Origin", ON_PLANE: "On plane"}


def placement_inputs(what: str) -> tuple[In, In]:
    """The Placement and Plane ports, ``what`` naming the outputs they place."""
    return (
        In("Placement", INTEGER, "Pl",
           f"Where {what} lie: 0 beside the model (in +X, flat at its lowest point), 1 at the origin, "
           "2 on Plane. A rigid motion: no length or area changes.",
           default=BESIDE_MODEL, min=BESIDE_MODEL, max=ON_PLANE, choices=tuple(NAMES.items())),
        In("Plane", PLANE, "Pn", "The plane to lay them on when Placement is 2 (On plane).", optional=True),
    )


def placement_frame(node: Node, choice: int, plane: Any, model_points: ArrayLike,
                    flat_bounds: ArrayLike) -> Plane:
    """The frame the development's XY plane is carried onto, for ``choice`` (already
    bounded by the port); ``model_points`` are points of the 3D model, ``flat_bounds``
    the development's ``[xmin, ymin, xmax, ymax]`` in its own frame. Remarks on a Plane
    that is not used and on On plane without one (then the world XY plane)."""
    if choice == ON_PLANE:
        if plane is None:
            node.remark("Placement is 2 (On plane) but no Plane is wired: the world XY plane is used")
            return WORLD_XY
        return kernel_plane("Plane", plane)
    if plane is not None:
        node.remark(f"Plane is used only when Placement is 2 (On plane); Placement is {choice} "
                    f"({NAMES[choice]})")
    if choice == ORIGIN:
        return WORLD_XY
    return beside_model(model_points, flat_bounds)

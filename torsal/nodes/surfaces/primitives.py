"""Primitive surfaces on a plane: Sphere, Torus, Cylinder and Cone.

Each is the kernel's parametric primitive (exact analytic derivatives, outward
normals) built around the world Z axis and carried onto the Plane: the Plane's
origin is the centre (the base centre for a cylinder or cone), its normal the axis
and its X axis where u = 0 starts. A point given for the Plane means the XY plane
through it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from torsal.engine.node import In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER, PLANE
from torsal.engine.values import WORLD_XY
from torsal.nodes.common.checks import number, positive
from torsal.nodes.common.convert import kernel_plane
from torsal.nodes.common.values import SURFACE
from torsal.nodes.geometry import parametric_surface as kernel
from torsal.nodes.geometry import transforms
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.vectors import WORLD_XY as KERNEL_XY
from torsal.nodes.geometry.vectors import Plane as KernelPlane


def _placed(frame: KernelPlane, build: Callable[[np.ndarray], Surface]) -> Surface:
    """``build(centre)`` (a primitive about the world Z axis) carried onto ``frame``."""
    if np.array_equal(frame.axes, np.eye(3)):
        return build(frame.origin)
    return build(np.zeros(3)).transformed(transforms.orient(KERNEL_XY, frame))


def _height(value: Any, frame: KernelPlane, shape: str) -> tuple[float, KernelPlane]:
    """A non-zero height; a negative one builds on the far side of the plane (normal reversed)."""
    height = number("Height", value)
    if height == 0:
        raise NodeWarning(f"Height is 0, so the {shape} would be flat: give it a length")
    if height > 0:
        return height, frame
    return -height, KernelPlane(frame.origin, frame.x, -frame.y, -frame.z)


PLANE_INPUT = "The centre and orientation; a point means the XY plane through it."


class Sphere(Node):
    """A sphere of Radius around the Plane's origin.

    u is the longitude, once round the Plane's normal starting from its X axis; v
    the latitude, from the south pole (v = 0, below the Plane) to the north pole
    (v = 1, on the normal's side). Normals point outwards, so its principal
    curvatures are both −1/Radius (curvature is negative where the surface bends
    away from its normal) and its Gaussian curvature 1/Radius². Area 4π·Radius².
    """

    type_id = "surfaces.Sphere"
    nickname, aliases = "Sph", ("ball",)
    inputs = (
        In("Plane", PLANE, "P", PLANE_INPUT, default=WORLD_XY),
        In("Radius", NUMBER, "R", "Distance from the centre, in model units (positive).", default=1.0),
    )
    outputs = (Out("Sphere", SURFACE, "S", "The sphere, poles on the Plane's normal."),)

    def solve(self, plane: Any, radius: Any) -> Surface:
        frame = kernel_plane("Plane", plane)
        r = positive("Radius", radius)
        return _placed(frame, lambda centre: kernel.sphere(r, centre))


class Torus(Node):
    """A ring-shaped tube: a circle of MinorRadius swept round a circle of MajorRadius.

    The ring lies in the Plane, round its origin. u goes round the ring from the
    Plane's X axis; v goes round the tube, from the outer equator (v = 0) over the
    top. The outside of the ring (cos v > 0) is dome-like (positive Gaussian
    curvature), the inside saddle-like (negative), and the top and bottom circles
    between them have Gaussian curvature 0. Area 4π²·MajorRadius·MinorRadius.
    MinorRadius must be smaller than MajorRadius, so the tube leaves a hole.
    """

    type_id = "surfaces.Torus"
    nickname, aliases = "Torus", ("ring", "donut")
    inputs = (
        In("Plane", PLANE, "P", PLANE_INPUT, default=WORLD_XY),
        In("MajorRadius", NUMBER, "R", "From the centre to the middle of the tube (positive).",
           default=2.0),
        In("MinorRadius", NUMBER, "r", "Radius of the tube, less than MajorRadius.", default=0.5),
    )
    outputs = (Out("Torus", SURFACE, "T", "The closed torus."),)

    def solve(self, plane: Any, major: Any, minor: Any) -> Surface:
        frame = kernel_plane("Plane", plane)
        big, small = positive("MajorRadius", major), positive("MinorRadius", minor)
        if small >= big:
            raise NodeWarning(
                f"MinorRadius ({small:g}) must be less than MajorRadius ({big:g}), or the tube "
                "closes the hole and passes through itself"
            )
        return _placed(frame, lambda centre: kernel.torus(big, small, centre))


def _axial_inputs(plane: str, radius: str, height: str) -> tuple[In, In, In]:
    """The Plane, Radius and Height inputs of a surface round an axis (Cylinder, Cone)."""
    return (
        In("Plane", PLANE, "P", plane, default=WORLD_XY),
        In("Radius", NUMBER, "R", radius, default=1.0),
        In("Height", NUMBER, "H", height, default=1.0),
    )


def _axial(plane: Any, radius: Any, height: Any, what: str, make: Callable[..., Surface]) -> Surface:
    """A surface round the Plane's normal: ``make(radius, height, centre)`` placed on it."""
    frame = kernel_plane("Plane", plane)
    r = positive("Radius", radius)
    h, frame = _height(height, frame, what)
    return _placed(frame, lambda centre: make(r, h, centre))


class Cylinder(Node):
    """An open cylinder (no caps) of Radius, standing Height along the Plane's normal.

    The base circle is centred on the Plane's origin (v = 0) and the top circle is
    Height above it (v = 1); u goes round from the Plane's X axis. A negative Height
    builds it below the Plane. Normals point outwards; it is developable (Gaussian
    curvature 0) and unrolls to a Height × 2π·Radius rectangle, its area.
    """

    type_id = "surfaces.Cylinder"
    nickname, aliases = "Cyl", ("cylinder surface",)
    inputs = _axial_inputs(
        "The base: its origin is the centre of the bottom circle.",
        "Radius of the cylinder, in model units (positive).",
        "Length along the Plane's normal (not 0; negative goes below).",
    )
    outputs = (Out("Cylinder", SURFACE, "C", "The cylinder's side, without caps."),)

    def solve(self, plane: Any, radius: Any, height: Any) -> Surface:
        return _axial(plane, radius, height, "cylinder", kernel.cylinder)


class Cone(Node):
    """An open cone (no base disc): base circle of Radius on the Plane, apex Height above.

    The base circle is centred on the Plane's origin (v = 0) and the apex lies
    Height along the Plane's normal (v = 1); u goes round from the Plane's X axis. A
    negative Height puts the apex below the Plane. Normals point outwards; it is
    developable and its area is π·Radius·√(Radius² + Height²).
    """

    type_id = "surfaces.Cone"
    nickname, aliases = "Cone", ("cone surface",)
    inputs = _axial_inputs(
        "The base: its origin is the centre of the base circle.",
        "Radius of the base circle, in model units (positive).",
        "From the base to the apex (not 0; negative goes below).",
    )
    outputs = (Out("Cone", SURFACE, "C", "The cone's side, without the base disc."),)

    def solve(self, plane: Any, radius: Any, height: Any) -> Surface:
        return _axial(plane, radius, height, "cone", kernel.cone)

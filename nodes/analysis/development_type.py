"""The ``Development`` value type: an unrolled ruled strip and its map to the surface.

IsoMapping's ``Map`` output carries the kernel's
:class:`~nodes.geometry.unroll.Development` — the flat and 3D rulings, the accuracy
figures and the :class:`~nodes.geometry.unroll.DevelopmentMap` that carries points and
polylines between the development and the 3D strip (SurfacePatching draws panels on
the development and maps them onto the surface with it). Import
:data:`DEVELOPMENT` from here to declare a port of this type.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from engine.types import ValueType, register_type
from nodes.geometry.unroll import Development


def _summary(development: Development) -> dict[str, Any]:
    bounds = np.asarray(development.bounds, dtype=float)
    return {
        "type": "Development",
        "rulings": len(development.starts2d[:: development.stride]),
        "area_3d": float(development.area_3d),
        "area_2d": float(development.area_2d),
        "area_error": float(development.area_error),
        "max_edge_length_error": float(development.max_edge_length_error),
        "bounds": [bounds[:2].tolist(), bounds[2:].tolist()],
    }


DEVELOPMENT = register_type(ValueType(
    "Development", (Development,),
    "A ruled surface unrolled into the XY plane, with the map between the plane and the surface.",
    summarize=_summary,
))

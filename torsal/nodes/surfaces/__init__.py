"""Surfaces: lofts, ruled, NURBS, parametric and primitive surfaces; evaluating and measuring them."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("freeform", "primitives", "analysis", "mesh", "bounds", "closest", "division", "sections",
              "sweep", "mesh_booleans")

"""Curves: lines, polylines, splines, circles and arcs; dividing, evaluating and offsetting them."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("primitives", "splines", "analysis", "offset", "frames", "division", "outlines", "intersect",
              "pieces")

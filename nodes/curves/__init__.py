"""Curves: lines, polylines, splines, circles and arcs; dividing, evaluating and offsetting them."""

"""Surfaces: lofts, ruled, NURBS, parametric and primitive surfaces; evaluating and measuring them."""

"""Patching nodes: panel patterns and their mapping from a development onto its surface."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("staggered", "surface_patching")

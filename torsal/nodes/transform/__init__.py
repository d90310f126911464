"""Transform: move, rotate, scale, mirror, orient and array any geometry."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("euclidean", "arrays")

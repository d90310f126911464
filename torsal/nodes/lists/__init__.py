"""Lists: pick, reorder, cull and restructure lists and data trees."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("items", "ordering", "culling", "trees", "dispatching", "paths", "explode")

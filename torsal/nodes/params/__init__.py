"""Parameters: the values a designer sets by hand (sliders, toggles, panels, points)."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("sliders", "panel", "value_list", "points", "vectors", "planes", "deconstruct", "two_points")

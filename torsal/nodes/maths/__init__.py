"""Maths: expressions, number sequences, domains and random numbers."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("expression", "sequences", "domains", "random_numbers", "remap")

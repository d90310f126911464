"""Developable surfaces: the toolbox's generation nodes (ruled, cylindrical, conical,
tangent developables, paper strips, spline approximation, surface coupling) and Rationalise."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = (
    "ruling_developable",
    "spline_approximation",
    "surface_coupling",
    "cylindrical",
    "conical",
    "tangent",
    "parametric_ruled",
    "paper_strip",
    "rationalise",
)

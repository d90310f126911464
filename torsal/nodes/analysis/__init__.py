"""Analysis: vector products, surface curvature and developability, unrolling ruled
surfaces into the plane, and the curve of regression of a developable."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = (
    "vectors",
    "surface_analysis",
    "iso_mapping",
    "curve_of_regression",
    "curvature_histogram",
    "warp_chart",
    "bending",
)

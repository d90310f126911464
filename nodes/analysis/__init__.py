"""Analysis: vector products, surface curvature and developability, unrolling ruled
surfaces into the plane, and the curve of regression of a developable."""

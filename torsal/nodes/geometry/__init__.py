"""Torsal's geometry kernel: curves, surfaces, vectors, curvature, unrolling.

Plain numpy/scipy, vectorised, with no imports from ``engine`` or ``app``.
Every curve is parameterised on t in [0, 1] and every surface on (u, v) in [0, 1]².
"""

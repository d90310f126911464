"""Refining many bracketed roots at once: Newton's method inside a shrinking bracket.

The solver lives in :mod:`..roots` (:func:`~..roots.refine_roots`), the one root solver
of the geometry kernel; it is named here for the ruling-developable kernel.
"""

from __future__ import annotations

from ..roots import STEP, ZERO, refine_roots

__all__ = ["STEP", "ZERO", "refine_roots"]

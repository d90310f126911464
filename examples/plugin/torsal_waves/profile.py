"""The corrugated profile: a value that travels on wires and draws itself in the viewport."""

from __future__ import annotations

import numpy as np

from torsal.api import ValueType


class Profile:
    """A corrugated sheet's cross-section, as (n, 3) points in the XZ plane."""

    def __init__(self, points: np.ndarray) -> None:
        self.points = np.asarray(points, dtype=float)

    def length(self) -> float:
        """The developed length: how wide the flat sheet is before it is corrugated."""
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())

    def preview_geometry(self):  # the preview protocol: Torsal's viewport draws the polyline
        from torsal.api import PreviewGeometry

        return PreviewGeometry(polylines=[self.points])


#: Torsal learns value types from the modules the palette declares (VALUE_TYPES).
PROFILE = ValueType("CorrugatedProfile", (Profile,), "A corrugated sheet's cross-section.")

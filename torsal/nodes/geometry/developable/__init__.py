"""Developable-surface kernels: rulings of cylinders, cones, tangent developables and
of the developable strip between two curves, and the warp angles that check them.

Arrays in, arrays out, numpy/scipy only; the node layer wraps these.

- :func:`ruling_developable` — the strip between two curves (RulingDevelopable): every
  torsal ruling found by the partner search (:mod:`.candidates`, with certified root
  isolation, :mod:`.isolation`), stretches without one closed by flat triangles
  (:mod:`.fans`), run by :mod:`.ruling`; :func:`.alternatives.better_pairing` names a
  swap or reversal of the curves only when solving it shows fewer triangles.
- :func:`cylinder_rulings`, :func:`cone_rulings`, :func:`tangent_developable_rulings` —
  direct developables with exact edge tangents.
- :func:`warp_angles`, :func:`warp_of_rulings` — how far rulings are from torsal.
"""

from .direct import Rulings, cone_rulings, cylinder_rulings, tangent_developable_rulings
from .ruling import RulingResult, ruling_developable, ruling_developables
from .stations import LengthMap, station_parameters
from .warp import edge_tangents, in_plane_tangent, warp_angles, warp_of_rulings

__all__ = [
    "LengthMap",
    "RulingResult",
    "Rulings",
    "cone_rulings",
    "cylinder_rulings",
    "edge_tangents",
    "in_plane_tangent",
    "ruling_developable",
    "ruling_developables",
    "station_parameters",
    "tangent_developable_rulings",
    "warp_angles",
    "warp_of_rulings",
]

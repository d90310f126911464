"""The array type aliases of the kernel and the node library, defined here once.

Type hints only: numpy does not check them at run time. This module imports nothing of
the kernel, so any module can use it without an import circle.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

#: Coordinates, parameters, lengths: any float array.
FloatArray = NDArray[np.float64]
#: Counts and indices (``np.intp``, the integer numpy indexes with: 64 bits on 64-bit platforms).
IntArray = NDArray[np.intp]
#: Masks.
BoolArray = NDArray[np.bool_]

__all__ = ["BoolArray", "FloatArray", "IntArray"]

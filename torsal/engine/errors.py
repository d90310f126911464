"""The exceptions a node's solve raises to say how it went (re-exported by :mod:`torsal.engine.node`).

They live apart from :mod:`torsal.engine.node` so that modules the node base class itself uses
(:mod:`torsal.engine.writes`) can raise them without importing it.
"""

from __future__ import annotations


class NodeError(Exception):
    """Raised by ``solve`` to put the node in error with this message (no traceback)."""


class NodeWarning(Exception):
    """Raised by ``solve`` to skip this call and put the node in warning with this message."""


class Cancelled(Exception):
    """The solve was cancelled (raised by :meth:`CancelToken.check`)."""

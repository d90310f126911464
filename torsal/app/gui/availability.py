"""Whether the desktop app's libraries can be used here, asked before anything else of
app/gui is imported (``torsal gui`` says how to install them when they cannot)."""

from __future__ import annotations

import importlib.util


class Unavailable(Exception):
    """The desktop app cannot start here; ``str()`` says why (see :func:`missing`)."""


def missing() -> str | None:
    """Why the app cannot start here (Qt, pyvista or pyvistaqt missing), or None.

    Qt is imported (a missing system library fails there too); pyvista and pyvistaqt
    are only looked up, as the app imports them once its window is shown.
    """
    try:
        import PySide6.QtWidgets  # noqa: F401
    except ImportError as exc:
        return f"Qt for Python (PySide6) is not installed or does not load ({exc})"
    for name in ("pyvista", "pyvistaqt"):
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):  # blocked in sys.modules, or a broken parent package
            found = False
        if not found:
            return f"{name} is not installed"
    return None

"""What ``torsal gui`` imports before Qt: the libraries its first frame needs that do not
need Qt themselves, the node modules of the file it opens, and pyvista with VTK.

Order matters because of PySide6. Once ``PySide6.QtCore`` is imported, every later
``import`` goes through PySide6's own import function, which reads the whole source of
each newly imported module to see whether it uses PySide6's ``__feature__`` switches
(``shibokensupport/feature.py`` inside PySide6, issue PYSIDE-2029), and keeps that text
in ``linecache``. Modules imported before PySide6 are never read that way. For the
flagship's first frame that is ~1,150 modules (numpy, scipy, shapely, pyvista with VTK
and matplotlib, the node library): measured 0.19-0.30 CPU s (of ~1.6) and ~50 MB of
cached source text more when imported after Qt (see ``tests/benchmarks/bench_startup.py``).

So :func:`import_before_qt` runs first, the window after it: the window shows a little
later (after ~1.2 CPU s instead of ~0.4), the solved model sooner.
"""

from __future__ import annotations

import contextlib
from pathlib import Path

from torsal.engine.graphfile import GraphFileError, read_graph
from torsal.engine.registry import Registry
from torsal.nodes.catalogue import default_registry


def import_before_qt(path: Path | None, registry: Registry | None = None) -> Registry:
    """The node registry (``registry``, or Torsal's default one with the installed
    plug-ins) with the node types of ``path`` (if given) loaded, and pyvista's
    plotting imported. Nothing else happens: the file is read again when the window opens
    it (under a millisecond), and a file that cannot be read, or a pyvista that cannot be
    imported, is left for the window to report as before (its dialog, the viewport's
    message)."""
    if registry is None:
        registry = default_registry()
    if path is not None:
        with contextlib.suppress(GraphFileError, OSError):
            read_graph(path, registry)
    # VTK's rendering modules and matplotlib, all Qt-free; a failure (a missing GL library)
    # is reported where the viewport imports pyvista
    with contextlib.suppress(Exception):
        import pyvista.plotting  # noqa: F401
    return registry

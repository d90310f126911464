"""GUI tests: pytest-qt under a display (Xvfb), with the real 3D viewport (VTK's Qt widget).

Run them with::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python -m pytest tests/app/gui -q

Without a display (``DISPLAY`` unset and ``QT_QPA_PLATFORM`` not ``offscreen``) or
without PySide6/pyvista/pyvistaqt/pytest-qt, the GUI test modules are not collected and
``test_availability.py`` reports one skip saying why. Dialogs are patched in every test
so none can block.

Under pytest-xdist (``make test`` spreads the GUI test files over two processes) each
worker starts an Xvfb display of its own, on loopback only, and stops it at the end: two
windows on one display would take each other's keyboard focus, and a shortcut goes to the
active window only.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent


def unavailable_reason() -> str:
    """Why the GUI tests cannot run here ("" when they can)."""
    for module in ("PySide6", "pyvista", "pyvistaqt", "pytestqt"):
        if importlib.util.find_spec(module) is None:
            return f"GUI tests need {module} (pip install -e '.[test]')"
    has_display = os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    if not has_display and os.environ.get("QT_QPA_PLATFORM") != "offscreen":
        return "no display: run the GUI tests under xvfb-run (see tests/app/gui/conftest.py)"
    return ""


def own_display() -> subprocess.Popen | None:
    """An Xvfb display for this xdist worker (None when not a worker or Xvfb is missing);
    ``DISPLAY`` names it from here on."""
    xvfb = shutil.which("Xvfb")
    if not os.environ.get("PYTEST_XDIST_WORKER") or xvfb is None or not os.environ.get("DISPLAY"):
        return None
    read, write = os.pipe()
    server = subprocess.Popen(  # -displayfd: Xvfb picks a free display and writes its number
        [xvfb, "-displayfd", str(write), "-screen", "0", "1600x1000x24", "-nolisten", "tcp"],
        pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )
    os.close(write)
    with os.fdopen(read) as answer:
        number = answer.readline().strip()
    if not number:
        server.kill()
        return None
    os.environ["DISPLAY"] = f":{number}"
    return server


DISPLAY_SERVER = own_display()


def pytest_unconfigure(config: pytest.Config) -> None:
    if DISPLAY_SERVER is not None:
        DISPLAY_SERVER.terminate()
        DISPLAY_SERVER.wait(10)


REASON = unavailable_reason()
if REASON:  # the other modules import Qt at the top: they cannot even be collected
    collect_ignore = [str(p) for p in HERE.rglob("test_*.py") if p.name != "test_availability.py"]


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for item in items:
        if HERE in Path(str(item.fspath)).parents:
            item.add_marker(pytest.mark.gui)
    # The examples run last: an example whose solve outlasts its budget is skipped, but a
    # node that never checks for cancellation keeps its worker thread busy, and would slow
    # the timing tests that followed.
    items.sort(key=lambda item: Path(str(item.fspath)).name == "test_examples.py")


if not REASON:
    from tests.support.fixtures_gui import *  # noqa: F403 - the GUI fixtures (they import Qt)

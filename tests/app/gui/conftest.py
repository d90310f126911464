"""GUI tests: pytest-qt under a display (Xvfb), with the real pyvistaqt QtInteractor.

Run them with::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python -m pytest tests/app/gui -q

Without a display (``DISPLAY`` unset and ``QT_QPA_PLATFORM`` not ``offscreen``) or
without PySide6/pyvista/pyvistaqt/pytest-qt, the GUI test modules are not collected and
``test_availability.py`` reports one skip saying why. Dialogs are patched in every test
so none can block.
"""

from __future__ import annotations

import importlib.util
import os
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

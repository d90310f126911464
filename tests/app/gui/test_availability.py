"""Says, as a skip reason, why the GUI tests did not run (and passes when they can)."""

import pytest

from tests.app.gui.conftest import REASON


def test_gui_tests_can_run_here():
    if REASON:
        pytest.skip(REASON)

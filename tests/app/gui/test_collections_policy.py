"""When the garbage collector runs: held off while a slider is dragged and during start-up
(torsal/app/gui/collections_policy.py; the start-up hold in a real launch is checked by
tests/app/gui/test_startup.py)."""

from __future__ import annotations

import gc

import pytest

from torsal.app.gui.collections_policy import HELD_THRESHOLD, FullCollectionsHeld, StartUpCollectionsHeld


@pytest.fixture
def collector():
    """The collector's state as found, given back after the test."""
    enabled, thresholds = gc.isenabled(), gc.get_threshold()
    gc.enable()
    yield
    gc.set_threshold(*thresholds)
    (gc.enable if enabled else gc.disable)()


def test_start_up_turns_automatic_collection_off_until_released_once(collector):
    held = StartUpCollectionsHeld()
    held.hold()
    assert held.held and not gc.isenabled()
    held.hold()  # a second hold changes nothing
    held.release()
    assert not held.held and gc.isenabled()
    gc.disable()
    held.release()  # a second release does not turn on what someone else turned off
    assert not gc.isenabled()


def test_start_up_leaves_a_collector_someone_else_turned_off_alone(collector):
    gc.disable()
    held = StartUpCollectionsHeld()
    held.hold()
    assert not held.held
    held.release()
    assert not gc.isenabled()


def test_a_drag_holds_only_full_collections_and_gives_the_thresholds_back(collector):
    gc.set_threshold(700, 10, 10)
    held = FullCollectionsHeld()
    held.hold()
    held.hold()
    assert gc.get_threshold() == (700, 10, HELD_THRESHOLD) and gc.isenabled()
    held.release()
    assert held.held and gc.get_threshold() == (700, 10, HELD_THRESHOLD)
    held.release()
    assert not held.held and gc.get_threshold() == (700, 10, 10)

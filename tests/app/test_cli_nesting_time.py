"""``torsal run --nesting-time S``: TrueShape cut sheets answered with rows at once, then
nested for at most S seconds, the best kept (torsal/engine/improve.py)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from torsal.app.cli import main

GRAPH = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples" / (
    "kaohsiung-cut-sheets.graph")
TRUE_SHAPE = ["--set", "cut.Nesting=TrueShape", "--set", "cut.TimeBudget=2"]

pytest.importorskip("spyrrow")


def _layout(capsys, *extra: str) -> dict:
    assert main(["run", str(GRAPH), *TRUE_SHAPE, *extra, "--json"]) == 0
    (layout,) = json.loads(capsys.readouterr().out)["nodes"]["cut"]["outputs"]["Layout"]["{0}"]
    return layout


def test_no_time_keeps_the_rows(capsys):
    assert _layout(capsys, "--nesting-time", "0")["nesting"] == "Shelf"


def test_time_enough_gives_the_true_shape_layout_of_the_nodes_own_budget(capsys):
    anytime = _layout(capsys, "--nesting-time", "3600")
    whole = _layout(capsys)  # without --nesting-time: nested inside the solve
    assert anytime["nesting"] == whole["nesting"] == "TrueShape"
    assert anytime["stock_usage"] == whole["stock_usage"]  # the same seed, the same steps


def test_a_negative_time_is_refused(capsys):
    assert main(["run", str(GRAPH), "--nesting-time", "-1"]) == 2
    assert "--nesting-time must be a number of seconds from 0" in capsys.readouterr().err

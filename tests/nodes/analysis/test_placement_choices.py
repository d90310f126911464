"""The Placement input of the nodes that place a development is a value list: a value
that is no choice is refused naming the input and its three choices."""

from __future__ import annotations

import pytest

from torsal.engine.bounds import refusal
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.patching.surface_patching import SurfacePatching

CHOICES = "0 Beside model, 1 Origin, 2 On plane"


@pytest.mark.parametrize("node", [IsoMapping, SurfacePatching])
@pytest.mark.parametrize("value", [-1, 3, 10**12])
def test_a_placement_that_is_no_choice_names_the_choices(node, value):
    port = next(p for p in node.inputs if p.name == "Placement")
    assert refusal(port, value) == f"Placement is {value:,}, not one of its choices: {CHOICES}"


@pytest.mark.parametrize("node", [IsoMapping, SurfacePatching])
def test_every_placement_choice_is_accepted(node):
    port = next(p for p in node.inputs if p.name == "Placement")
    assert [refusal(port, v) for v in (0, 1, 2)] == [None, None, None]

"""The ``waves`` palette's node types."""

from __future__ import annotations

import math

import numpy as np

from torsal.api import INTEGER, NUMBER, In, Node, NodeWarning, Out, checks
from torsal_waves.profile import PROFILE, Profile


class Wave(Node):
    """The height of a sine wave at X: Amplitude · sin(2π X / Length)."""

    type_id = "waves.Wave"
    inputs = (
        In("X", NUMBER, "X", "Where along the wave.", default=0.0),
        In("Length", NUMBER, "L", "The wave length (greater than 0).", default=1.0),
        In("Amplitude", NUMBER, "A", "The height of a crest.", default=1.0),
    )
    outputs = (Out("Height", NUMBER, "H", "The wave's height at X."),)

    def solve(self, x: float, length: float, amplitude: float) -> float:
        x = checks.finite("X", x)
        length = checks.positive("Length", length)
        amplitude = checks.finite("Amplitude", amplitude)
        return amplitude * math.sin(2 * math.pi * x / length)


class Corrugation(Node):
    """A corrugated sheet's profile (a sine of the given Pitch and Depth across Width) and
    its developed width: how wide the flat sheet must be to be pressed into it. Sheet metal
    corrugates without stretching, so the developed width is the profile's length."""

    type_id = "waves.Corrugation"
    inputs = (
        In("Width", NUMBER, "W", "The corrugated sheet's width (greater than 0).", default=1.0),
        In("Pitch", NUMBER, "P", "Crest to crest (greater than 0).", default=0.1),
        In("Depth", NUMBER, "D", "Crest to trough (0 or more).", default=0.02),
        In("Samples", INTEGER, "N", "Points along the profile.", default=2001, min=2, max=1_000_000),
    )
    outputs = (
        Out("Profile", PROFILE, "C", "The profile, in the XZ plane."),
        Out("Developed", NUMBER, "F", "The flat sheet's width."),
    )

    def solve(self, width: float, pitch: float, depth: float, samples: int) -> tuple[Profile, float]:
        width = checks.positive("Width", width)
        pitch = checks.positive("Pitch", pitch)
        depth = checks.finite("Depth", depth)
        if depth < 0:
            raise NodeWarning(f"Depth must be 0 or more, not {depth:g}")
        samples = checks.count("Samples", samples, least=2)
        x = np.linspace(0.0, width, samples)
        z = depth / 2 * np.sin(2 * np.pi * x / pitch)
        profile = Profile(np.column_stack([x, np.zeros_like(x), z]))
        return profile, profile.length()

"""The variants of a sweep: a full grid, a Latin hypercube or a Sobol sequence."""

from __future__ import annotations

import itertools
import warnings
from typing import Any

import numpy as np
from scipy.stats import qmc

from torsal.app.explore.variables import Variable

SAMPLERS = ("grid", "lhs", "sobol")


def grid(variables: list[Variable]) -> list[dict[str, Any]]:
    """Every combination of each variable's ``steps`` evenly spaced values, the last varying fastest."""
    axes = []
    for variable in variables:
        steps = variable.steps or 1
        units = np.linspace(0.0, 1.0, steps) if steps > 1 else np.array([0.0])
        axes.append([variable.from_unit(u) for u in units])
    names = [v.node_id for v in variables]
    return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*axes)]


def sample(variables: list[Variable], sampler: str, samples: int, seed: int) -> list[dict[str, Any]]:
    """``samples`` variants from ``sampler`` (``lhs`` or ``sobol``), the same for the same seed."""
    if sampler == "grid":
        return grid(variables)
    dimensions = len(variables)
    if sampler == "lhs":
        units = qmc.LatinHypercube(d=dimensions, seed=seed).random(samples)
    else:
        with warnings.catch_warnings():  # a count that is not a power of two loses balance: fine here
            warnings.simplefilter("ignore", UserWarning)
            units = qmc.Sobol(d=dimensions, scramble=True, seed=seed).random(samples)
    names = [v.node_id for v in variables]
    return [
        dict(zip(names, (v.from_unit(u) for v, u in zip(variables, row, strict=True)), strict=True))
        for row in units
    ]

"""Settings for the whole suite.

Property tests (hypothesis) draw their examples from a fixed seed, so ``make test`` gives the
same verdict on every run and machine: a new counterexample is found on purpose, not by CI's
chance. To explore further, run with ``HYPOTHESIS_PROFILE=explore`` (fresh random examples
on each run).
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("suite", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "suite"))

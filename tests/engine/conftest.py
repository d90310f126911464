"""Fixtures for the engine tests: a registry of small test node types (see ``nodekit``)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.support.nodekit import make_registry
from torsal.engine.registry import Registry

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"


@pytest.fixture(scope="session")
def registry() -> Registry:
    return make_registry()


@pytest.fixture(scope="session")
def fixtures_dir() -> Path:
    return FIXTURES

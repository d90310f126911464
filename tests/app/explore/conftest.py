"""A dask.distributed LocalCluster for the exploration tests: two worker processes on loopback."""

from __future__ import annotations

import logging

import pytest


@pytest.fixture(scope="package")
def cluster():
    """Started once for tests/app/explore and stopped after them (not left running under the rest
    of the suite); each test gets its address."""
    from distributed import LocalCluster

    local = LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
        dashboard_address="127.0.0.1:0", silence_logs=logging.ERROR,
    )
    try:
        yield local
    finally:
        local.close()

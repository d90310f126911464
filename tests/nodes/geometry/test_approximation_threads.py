"""SplineApproximation's polish factors its normal matrix on one BLAS thread
(:func:`torsal.nodes.geometry.approximation._one_blas_thread`): threads gain nothing on a
matrix that small and stall a busy machine. threadpoolctl's own report is the witness."""

from __future__ import annotations

from threadpoolctl import threadpool_info

from torsal.nodes.geometry.approximation import _one_blas_thread


def test_inside_the_polish_every_blas_runs_on_one_thread_and_gets_its_threads_back_after():
    before = [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]
    with _one_blas_thread():
        inside = [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]
    after = [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]
    assert inside and set(inside) == {1}
    assert after == before

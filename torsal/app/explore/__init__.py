"""Design-space exploration: sweeps and optimisation of a graph's sliders.

``torsal sweep`` and ``torsal optimise`` solve many variants of one graph headless, in
worker processes on this machine or on a dask.distributed cluster. No Qt is imported.
"""

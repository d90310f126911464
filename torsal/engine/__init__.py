"""Torsal's dataflow runtime: value types, data trees, nodes, graphs, solving and files.

Plain Python with no knowledge of geometry, Qt or VTK. The node library (``nodes``)
registers geometry types and node classes; front-ends (``app``) drive graphs.
"""

__version__ = "0.1.0"

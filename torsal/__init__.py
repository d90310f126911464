"""Torsal: a node-graph designer for developable surfaces.

Everything Torsal installs lives under this one package: ``torsal.engine`` (graphs, data
trees, the solver), ``torsal.nodes`` (the node library), ``torsal.app`` (the command line
and the desktop app) and ``torsal.resources`` (the bundled examples). Plug-ins build on
``torsal.api``.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("torsal")
except PackageNotFoundError:  # a checkout run without installing it
    __version__ = "0+unknown"

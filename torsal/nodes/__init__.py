"""Torsal's node library: one package per palette tab, the helpers they share, the kernel.

Each palette package (``params``, ``maths`` ... ``analysis``) declares in its ``__init__``
the modules holding its node types (``NODE_TYPES``) and those defining the value types it
adds (``VALUE_TYPES``); :func:`torsal.nodes.catalogue.default_registry` finds them. The geometry
value types every palette shares (Curve, Line, Surface, Mesh, MeshSurface, Development)
are declared here, and so is the index of which module holds each node type
(:mod:`torsal.nodes.node_index`, written by ``tools/node_index.py``), so that opening a
graph imports only the modules of the node types in it.
"""

#: The modules defining the value types the palettes share (read by engine.registry).
VALUE_TYPES = ("common.values",)
#: The module mapping each node type id to the module holding it (read by engine.registry).
NODE_INDEX = "node_index"

"""The desktop app: a node canvas, a 3D viewport and docks around the engine's graph.

Only this package imports Qt, pyvista and VTK. The canvas is a *view* of
:class:`torsal.engine.graph.Graph`: every edit is an undo command that calls the graph's
methods, and the canvas redraws from the graph's change events. Solving runs on a
worker thread (:mod:`torsal.app.gui.solve_controller`); results come back through signals.
"""

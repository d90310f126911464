"""What the palettes share: one home for each idea a node needs besides its own solve.

- :mod:`torsal.nodes.common.checks` and :mod:`torsal.nodes.common.geometry_checks` — every input check
  (of values; of curves and surfaces), and the one rule for what is an error and what a
  warning;
- :mod:`torsal.nodes.common.convert` — engine values on wires to kernel arrays and back;
- :mod:`torsal.nodes.common.values` — the geometry value types (Curve, Line, Surface, Mesh,
  MeshSurface, Development);
- :mod:`torsal.nodes.common.strip_outputs` and :mod:`torsal.nodes.common.stations` — what every
  strip-making node hands on, and the per-station diagnostics it words;
- :mod:`torsal.nodes.common.preview` — geometry as plain arrays for a viewport (the preview
  protocol).
- :mod:`torsal.nodes.common.files`, :mod:`torsal.nodes.common.units` and :mod:`torsal.nodes.common.charts` —
  the write rules and file errors, length units, and the PNG charts that the io, display
  and analysis palettes share;
- :mod:`torsal.nodes.common.formulas` — formulas given as text inputs (ParametricCurve,
  ParametricSurface).

A palette folder holds nodes only; a helper two palettes need lives here.
"""

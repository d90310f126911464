"""What the palettes share: one home for each idea a node needs besides its own solve.

- :mod:`nodes.common.checks` and :mod:`nodes.common.geometry_checks` — every input check
  (of values; of curves and surfaces), and the one rule for what is an error and what a
  warning;
- :mod:`nodes.common.convert` — engine values on wires to kernel arrays and back;
- :mod:`nodes.common.values` — the geometry value types (Curve, Line, Surface, Mesh,
  MeshSurface, Development);
- :mod:`nodes.common.strip_outputs` and :mod:`nodes.common.stations` — what every
  strip-making node hands on, and the per-station diagnostics it words;
- :mod:`nodes.common.preview` — geometry as plain arrays for a viewport (the preview
  protocol).
- :mod:`nodes.common.files`, :mod:`nodes.common.units` and :mod:`nodes.common.charts` —
  the write rules and file errors, length units, and the PNG charts that the io, display
  and analysis palettes share;
- :mod:`nodes.common.formulas` — formulas given as text inputs (ParametricCurve,
  ParametricSurface).

A palette folder holds nodes only; a helper two palettes need lives here.
"""

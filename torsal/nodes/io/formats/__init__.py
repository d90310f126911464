"""File formats: the writers and readers behind the io palette's nodes, engine-free.

- :mod:`.cutfiles` — cut sheets (DXF, SVG): panel outlines, nesting onto sheets, labels
  (:mod:`.labels`) and seam marks, into a layout (:mod:`.cutlayout`) that
  :mod:`.sheetviews` draws as SVG and PNG;
- :mod:`.threedm` — Rhino ``.3dm`` through rhino3dm (kernel geometry as rhino3dm objects
  in :mod:`.threedm_native`, strips face by face in :mod:`.threedm_strips`);
- :mod:`.meshfiles` — OBJ, STL, PLY and GLB through trimesh;
- :mod:`.tables` — data trees as CSV and JSON.

The nodes that use them (``io.ExportCutSheet``, ``io.Export3dm`` …) live in
:mod:`torsal.nodes.io`; these modules know nothing of the engine's nodes.
"""

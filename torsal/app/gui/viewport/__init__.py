"""The 3D viewport: pyvista datasets from node outputs, actors per node, the dock widget."""

"""One SVG icon per node type (``<type id>.svg``), drawn by tools/make_icons.py; see README.md."""

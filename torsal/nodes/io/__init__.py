"""Files in and out: Rhino ``.3dm``, cut sheets (DXF, SVG), meshes (OBJ, STL, PLY, GLB), CSV.

Node modules (``rhino``, ``cutting``, ``meshes``, ``data``) hold the ``io.*`` node types;
the helper modules (``common``, ``threedm``, ``cutfiles``, ``meshfiles``, ``csvfiles``)
do the reading and writing, and are what ``torsal run --export`` calls too
(:mod:`torsal.app.exports`), so a file written headless is the file the node writes.
"""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("rhino", "cutting", "meshes", "data")
#: The modules defining value types this palette adds.
VALUE_TYPES = ("cutting",)

"""Write ``torsal/nodes/node_index.py``: which module holds each of Torsal's node types.

``python tools/node_index.py`` after adding, renaming or moving a node type
(``tests/nodes/test_node_index.py`` fails until then). The registry reads the index to
import only the modules of the node types a graph holds (``torsal/engine/registry.py``).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TARGET = ROOT / "torsal" / "nodes" / "node_index.py"
HEADER = '''"""Which module of ``torsal.nodes`` holds each node type (type id → module, relative).

Written by ``tools/node_index.py`` (run it after adding, renaming or moving a node type;
``tests/nodes/test_node_index.py`` checks it). :class:`torsal.engine.registry.Registry`
reads it to import only the modules of the node types a graph holds; a type missing
here still loads, with its whole palette.
"""

MODULES: dict[str, str] = {
'''


def index() -> dict[str, str]:
    """Every built-in node type id → its module, relative to ``torsal.nodes``."""
    sys.path.insert(0, str(ROOT))
    from torsal.nodes.catalogue import default_registry

    registry = default_registry(plugins=False)
    return {cls.type_id: cls.__module__.removeprefix("torsal.nodes.") for cls in registry}


def text(modules: dict[str, str]) -> str:
    lines = [f'    "{type_id}": "{module}",\n' for type_id, module in sorted(modules.items())]
    return HEADER + "".join(lines) + "}\n"


if __name__ == "__main__":
    if not TARGET.exists():  # the registry imports the index the library declares
        TARGET.write_text(text({}), encoding="utf-8")
    TARGET.write_text(text(index()), encoding="utf-8")
    print(f"wrote {TARGET.relative_to(ROOT)}")

"""torsal/nodes/node_index.py names the module of every node type in the catalogue, and
opening a graph imports only the modules of the node types it holds."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from torsal.nodes.catalogue import default_registry
from torsal.nodes.node_index import MODULES

ROOT = Path(__file__).resolve().parents[2]


def test_the_index_names_the_module_of_every_node_type_and_nothing_else():
    """Fails after a node type is added, renamed or moved: run ``python tools/node_index.py``."""
    catalogue = {cls.type_id: cls.__module__ for cls in default_registry(plugins=False)}
    assert len(catalogue) > 100
    assert {type_id: f"torsal.nodes.{name}" for type_id, name in MODULES.items()} == catalogue


def test_opening_the_flagship_imports_only_its_node_types_modules():
    """Its 12 node types live in 10 modules (which import 2 more); the other modules of
    their palettes (planes, panels, arrays, the other curve nodes...) are imported when a
    palette tab or the search lists them, not to open the file."""
    flagship = ROOT / "torsal" / "resources" / "examples" / "kaohsiung-stadium.graph"
    script = (
        "import json, sys\n"
        "from torsal.engine.graphfile import read_graph\n"
        "from torsal.nodes.catalogue import default_registry\n"
        f"graph = read_graph({str(flagship)!r}, default_registry(plugins=False))\n"
        "print(json.dumps(sorted({record.node.type_id for record in graph.nodes.values()})))\n"
        "print(json.dumps(sorted(m for m in sys.modules if m.startswith('torsal.nodes.'))))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True, cwd=ROOT)
    types_line, modules_line = out.stdout.strip().splitlines()
    held, imported = json.loads(types_line), set(json.loads(modules_line))
    node_modules = {f"torsal.nodes.{name}" for name in MODULES.values()}
    used = {f"torsal.nodes.{MODULES[type_id]}" for type_id in held}
    # what the used modules import from other node modules, read from their source
    needed = set(used)
    for name in used:
        source = (ROOT / Path(*name.split("."))).with_suffix(".py").read_text(encoding="utf-8")
        needed |= {other for other in node_modules if f"from {other} import" in source}
    assert len(held) == 12 and len(used) == 10
    assert imported & node_modules == needed
    palettes = {type_id.partition(".")[0] for type_id in held}
    assert len(needed) < len({m for m in node_modules if m.split(".")[2] in palettes}) / 2

"""``torsal.api``, the plug-ins' public surface: every documented name is there, importing it
loads no geometry library, and the worked example plug-in imports nothing else of Torsal."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import torsal.api as api

ROOT = Path(__file__).resolve().parent.parent


def test_every_public_name_resolves():
    assert sorted(set(api.__all__)) == sorted(api.__all__)
    for name in api.__all__:
        assert getattr(api, name) is not None, name


def test_the_documented_table_lists_exactly_the_public_names():
    text = (ROOT / "docs" / "plugins.md").read_text(encoding="utf-8")
    table = text.split("## What a plug-in may import", 1)[1].split("###", 1)[0]
    documented = set(re.findall(r"`([A-Za-z_]+)`", table)) - {"torsal", "api"}
    assert documented == set(api.__all__)


def test_importing_the_api_loads_no_geometry_library():
    heavy = {"trimesh", "scipy", "shapely", "matplotlib"}
    script = f"import sys, torsal.api\nprint(sorted({{m.split('.')[0] for m in sys.modules}} & {heavy!r}))\n"
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=ROOT,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_the_example_plugin_imports_only_torsal_api_of_torsal():
    for path in (ROOT / "examples" / "plugin").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else (
                [node.module] if isinstance(node, ast.ImportFrom) and node.module else [])
            for name in names:
                if name.split(".")[0] == "torsal":
                    assert name == "torsal.api", (path.name, name)

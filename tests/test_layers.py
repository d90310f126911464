"""The layer rule (engine ← nodes ← app) and a headless path free of Qt and VTK."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GUI_MODULES = ("PySide6", "pyvista", "pyvistaqt", "vtk", "vtkmodules", "shiboken6")


def _root(module: str) -> str:
    """The layer a module belongs to: ``torsal.<layer>`` for Torsal's own, else its top level."""
    parts = module.split(".")
    return parts[1] if parts[0] == "torsal" and len(parts) > 1 else parts[0]


def imported_roots(folder: str) -> dict[str, set[str]]:
    """Top-level module names imported by each file under ``folder``."""
    found = {}
    for path in (ROOT / folder).rglob("*.py"):
        roots = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                roots.update(_root(alias.name) for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                roots.add(_root(node.module))
        found[str(path.relative_to(ROOT))] = roots
    return found


def test_engine_imports_neither_nodes_nor_app_nor_gui_libraries():
    for path, roots in imported_roots("torsal/engine").items():
        assert not roots & {"nodes", "app", *GUI_MODULES}, path


def test_nodes_import_neither_app_nor_gui_libraries():
    for path, roots in imported_roots("torsal/nodes").items():
        assert not roots & {"app", *GUI_MODULES}, path


def test_geometry_kernel_does_not_import_engine():
    for path, roots in imported_roots("torsal/nodes/geometry").items():
        assert "engine" not in roots, path


def test_only_app_gui_imports_qt_or_vtk():
    for path, roots in imported_roots("torsal/app").items():
        if not path.startswith("torsal/app/gui"):
            assert not roots & set(GUI_MODULES), path


def test_headless_run_imports_no_qt_pyvista_or_vtk(tmp_path):
    example = ROOT / "torsal" / "resources" / "examples" / "first-steps.graph"
    script = (
        "import sys, io, contextlib\n"
        "from torsal.app.cli import main\n"
        "buffer = io.StringIO()\n"
        "with contextlib.redirect_stdout(buffer):\n"
        f"    main(['run', {str(example)!r}, '--json'])\n"
        "    main(['check', " + repr(str(example)) + "])\n"
        "    main(['nodes', '--json'])\n"
        f"print(sorted(m for m in sys.modules if m.split('.')[0] in {GUI_MODULES!r}))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout.strip().replace("'", '"')) == []

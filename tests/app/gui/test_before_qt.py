"""What torsal gui imports before Qt (torsal/app/gui/before_qt.py): pyvista's plotting and
the node modules of the file, and no Qt (nor trimesh or shapely, which the flagship does not
use); a file that cannot be read is left to the window."""

from __future__ import annotations

import json
import subprocess
import sys

from tests.support.fixtures_gui import EXAMPLES, ROOT
from torsal.app.gui.before_qt import import_before_qt


def test_the_imports_before_qt_take_the_files_node_modules_and_pyvista_and_no_qt_nor_unused_libraries():
    script = (
        "import json, sys\n"
        "from pathlib import Path\n"
        "from torsal.app.gui.before_qt import import_before_qt\n"
        f"registry = import_before_qt(Path({str(EXAMPLES / 'kaohsiung-stadium.graph')!r}))\n"
        "print(json.dumps(sorted(m for m in sys.modules if m.split('.')[0] in\n"
        "      ('PySide6', 'shiboken6', 'qtpy', 'pyvistaqt', 'pyvista', 'scipy', 'torsal',\n"
        "       'trimesh', 'shapely'))))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=ROOT,
                         timeout=120, check=True)
    imported = set(json.loads(out.stdout))
    needed = {"pyvista.plotting", "scipy.interpolate", "torsal.nodes.developable.ruling_developable"}
    assert needed <= imported
    assert not {m for m in imported if m.split(".")[0] in ("PySide6", "shiboken6", "qtpy", "pyvistaqt")}
    assert not {m for m in imported if m.split(".")[0] in ("trimesh", "shapely")}  # the flagship uses neither


def test_a_file_that_cannot_be_read_is_left_to_the_window(tmp_path):
    broken = tmp_path / "broken.graph"
    broken.write_text("{ not a graph", encoding="utf-8")
    for path in (broken, tmp_path / "missing.graph", tmp_path):
        registry = import_before_qt(path)
        assert registry.get("params.NumberSlider") is not None

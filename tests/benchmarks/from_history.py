"""Old code from the project's own git history, loaded as a benchmark's baseline.

A benchmark that holds today's code to the time of an earlier version runs that version
itself: its files are read with ``git show COMMIT:PATH`` when the benchmark runs (a clone
has the history), written into a temporary package and imported under a name of its own,
so nothing of the old version is kept in the tree. Imports of the kernel's other modules
(``from ..vec_ops import …``) are pointed at today's modules, which the old code called
the same way; only the listed modules are taken from the past.
"""

from __future__ import annotations

import atexit
import importlib
import importlib.util
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[2]


def git_show(commit: str, path: str) -> str:
    """The text of ``path`` at ``commit``; skips the benchmark (saying why) where git or
    that commit is not there (a shallow clone, an exported tree)."""
    try:
        shown = subprocess.run(
            ["git", "-C", str(ROOT), "show", f"{commit}:{path}"],
            capture_output=True, text=True, check=False, timeout=60,
        )
    except (OSError, subprocess.TimeoutExpired) as exc:
        pytest.skip(f"the baseline is read from git history, and git could not run: {exc}")
    if shown.returncode != 0:
        reason = shown.stderr.strip()
        pytest.skip(f"the baseline {path} at commit {commit} is not in this clone's history: {reason}")
    return shown.stdout


def load_package(commit: str, folder: str, modules: tuple[str, ...], parent: str, name: str) -> ModuleType:
    """The modules ``folder/<module>.py`` as they were at ``commit``, as the package ``name``.

    ``parent`` is the dotted package the folder's modules were in (``torsal.nodes.geometry`` for
    ``nodes/geometry/developable``): their imports from it (``from ..x import``) are
    taken from today's ``parent.x``; their imports of each other stay within ``name``.
    """
    if name in sys.modules:
        return sys.modules[name]
    where = Path(tempfile.mkdtemp(prefix="torsal-baseline-"))
    atexit.register(shutil.rmtree, where, ignore_errors=True)
    package = where / name
    package.mkdir()
    (package / "__init__.py").write_text(f'"""{folder} at commit {commit}, from git history."""\n')
    for module in modules:
        text = git_show(commit, f"{folder}/{module}.py")
        text = re.sub(r"^from \.\.(\w+) import", rf"from {parent}.\1 import", text, flags=re.MULTILINE)
        (package / f"{module}.py").write_text(text, encoding="utf-8")
    spec = importlib.util.spec_from_file_location(
        name, package / "__init__.py", submodule_search_locations=[str(package)]
    )
    assert spec is not None and spec.loader is not None
    loaded = importlib.util.module_from_spec(spec)
    sys.modules[name] = loaded
    spec.loader.exec_module(loaded)
    for module in modules:
        importlib.import_module(f"{name}.{module}")
    return loaded


def extract_tree(commit: str, paths: tuple[str, ...]) -> Path:
    """The folders and files ``paths`` as they were at ``commit``, in a temporary folder
    (removed at exit) that a subprocess can run the old version from; skips the
    benchmark (saying why) where the history is not there."""
    where = Path(tempfile.mkdtemp(prefix="torsal-tree-"))
    atexit.register(shutil.rmtree, where, ignore_errors=True)
    try:
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", "--format=tar", commit, *paths],
            capture_output=True, check=False, timeout=120,
        )
    except (OSError, subprocess.TimeoutExpired) as exc:
        pytest.skip(f"the baseline is read from git history, and git could not run: {exc}")
    if archive.returncode != 0:
        reason = archive.stderr.decode(errors="replace").strip()
        pytest.skip(f"commit {commit} is not in this clone's history: {reason}")
    subprocess.run(["tar", "-x", "-C", str(where)], input=archive.stdout, check=True, timeout=120)
    return where

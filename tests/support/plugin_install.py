"""Installing plug-ins for the tests: the worked example (examples/plugin) and small ones a
test writes, each into a folder of its own with ``pip install --target`` (offline: no
dependencies, no build isolation), used by putting that folder on the path."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "plugin"


def install(sources: list[Path], target: Path) -> Path:
    """``pip install --target target`` of the project folders ``sources`` (copied first:
    setuptools builds in the source folder)."""
    copies = []
    for source in sources:
        copy = target.parent / f"{target.name}-src" / source.name
        shutil.copytree(source, copy, ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
        copies.append(str(copy))
    command = [sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--no-build-isolation",
               "--no-index", "--target", str(target), *copies]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    return target


def write_plugin(folder: Path, distribution: str, package: str, module_text: str) -> Path:
    """A one-module plug-in project: ``package/__init__.py`` holds ``module_text`` and is the
    ``torsal.nodes`` entry point."""
    (folder / package).mkdir(parents=True)
    (folder / package / "__init__.py").write_text(module_text, encoding="utf-8")
    (folder / "pyproject.toml").write_text(
        '[build-system]\nrequires = ["setuptools>=61"]\nbuild-backend = "setuptools.build_meta"\n\n'
        f'[project]\nname = "{distribution}"\nversion = "0.1"\n\n'
        f'[project.entry-points."torsal.nodes"]\nnodes = "{package}"\n\n'
        f'[tool.setuptools]\npackages = ["{package}"]\n', encoding="utf-8")
    return folder


def environment(*plugin_folders: Path) -> dict[str, str]:
    """This checkout's torsal with the plug-ins in ``plugin_folders`` installed, and nothing
    else of the tests' own path (the current folder is left out with ``-P``)."""
    path = [str(p) for p in plugin_folders] + [str(ROOT)]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(path)}


def torsal(cwd: Path, *args: str, plugins: tuple[Path, ...] = (), timeout: float = 240
           ) -> subprocess.CompletedProcess[str]:
    """The ``torsal`` command, run with the plug-ins in ``plugins`` installed."""
    return subprocess.run([sys.executable, "-P", "-m", "torsal.app.cli", *args], capture_output=True,
                          text=True, cwd=cwd, env=environment(*plugins), timeout=timeout)

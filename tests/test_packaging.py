"""Packaging: what the wheel and the sdist carry (checked by twine and check-wheel-contents),
what `make run` installs, `torsal gui` without Qt, and (opt-in, slow) the declared lower bounds."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted(p.name for p in (ROOT / "torsal" / "resources" / "examples").glob("*.graph"))
CHECKOUT_INSTALL = "-m pip install -c constraints.txt "


@pytest.fixture(scope="module")
def dists(tmp_path_factory) -> tuple[Path, Path]:
    """The sdist `python -m build` makes of this checkout, and the wheel it builds from that
    sdist (so the sdist is complete enough to build from); about 20 s."""
    folder = tmp_path_factory.mktemp("dist")
    source = folder / "src"
    # A copy without the checkout's build leftovers, as a clean clone would be.
    shutil.copytree(ROOT, source, ignore=shutil.ignore_patterns(
        ".venv", ".git", "build", "dist", "*.egg-info", "__pycache__", ".pytest_cache", ".ruff_cache",
        ".hypothesis"))
    done = subprocess.run([sys.executable, "-m", "build", "--outdir", str(folder), str(source)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, (done.stdout + done.stderr)[-3000:]
    (wheel_file,) = folder.glob("torsal-*.whl")
    (sdist_file,) = folder.glob("torsal-*.tar.gz")
    return wheel_file, sdist_file


@pytest.fixture(scope="module")
def wheel(dists) -> Path:
    return dists[0]


def test_the_sdist_holds_every_file_of_the_repository(dists):
    """tests, docs, tools, examples, constraints.txt, the Makefile: everything git tracks but
    its own files and CI's entry point, so the sdist builds and tests as a clone does."""
    import tarfile

    listed = subprocess.run(["git", "-C", str(ROOT), "ls-files"], capture_output=True, text=True, timeout=60)
    if shutil.which("git") is None or listed.returncode != 0:
        pytest.skip("not a git checkout: nothing to compare the sdist with")
    tracked = {name for name in listed.stdout.splitlines() if (ROOT / name).is_file()}
    tracked -= {".gitignore", ".ci/run"}
    with tarfile.open(dists[1]) as archive:
        held = {name.split("/", 1)[1] for name in archive.getnames() if "/" in name}
    assert tracked - held == set()
    assert {"constraints.txt", "Makefile", "docs/plugins.md", "examples/plugin/pyproject.toml",
            "tests/test_packaging.py"} <= held


def test_twine_check_passes_on_the_wheel_and_the_sdist(dists):
    done = subprocess.run([sys.executable, "-m", "twine", "check", "--strict", *map(str, dists)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.count("PASSED") == 2


def test_check_wheel_contents_passes(wheel):
    done = subprocess.run([sys.executable, "-m", "check_wheel_contents", str(wheel)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.strip().endswith(": OK")


def test_the_metadata_has_classifiers_keywords_and_the_readme(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    (metadata,) = [n for n in names if n.endswith(".dist-info/METADATA")]
    text = zipfile.ZipFile(wheel).read(metadata).decode()
    assert "Classifier: Programming Language :: Python :: 3.11" in text
    assert "Keywords: developable surfaces" in text
    assert "Description-Content-Type: text/markdown" in text


def test_the_wheel_contains_every_example_graph(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    assert EXAMPLES
    assert {f"torsal/resources/examples/{name}" for name in EXAMPLES} <= names
    assert "torsal/resources/examples/canopy.3dm" in names  # the design rationalise-canopy reads


def test_the_wheel_installs_one_namespace(wheel):
    """Everything lives under ``torsal``: no generic top-level ``app``, ``engine``, ``nodes``
    or ``resources`` package to shadow (or be shadowed by) someone else's."""
    tops = {name.split("/")[0] for name in zipfile.ZipFile(wheel).namelist()}
    assert {top for top in tops if not top.endswith(".dist-info")} == {"torsal"}


def test_the_wheel_carries_the_mit_license(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    (metadata,) = [n for n in names if n.endswith(".dist-info/METADATA")]
    text = zipfile.ZipFile(wheel).read(metadata).decode()
    assert "License-Expression: MIT" in text
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)


def test_torsal_examples_lists_the_examples_from_an_installed_wheel(wheel, tmp_path):
    site = tmp_path / "site"
    done = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--quiet", "--target",
                           str(site), str(wheel)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    script = ("import sys, torsal\n"
              f"assert torsal.__file__.startswith({str(site)!r}), torsal.__file__\n"
              "from torsal.app.cli import main\n"
              "sys.exit(main(['examples']))\n")
    env = {**os.environ, "PYTHONPATH": str(site)}
    listed = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=tmp_path,
                            env=env, timeout=120)
    assert listed.returncode == 0, listed.stderr
    rows = [line.split() for line in listed.stdout.splitlines() if not line.startswith(" ")]
    assert [row[0] for row in rows] == [n[: -len(".graph")] for n in EXAMPLES]
    # each file's path: the installed copy, which is the example's own bytes
    for (name, where), example in zip(rows, EXAMPLES, strict=True):
        assert Path(where) == site / "torsal" / "resources" / "examples" / example, name
        assert Path(where).read_bytes() == (ROOT / "torsal" / "resources" / "examples" / example).read_bytes()


def test_torsal_gui_from_a_wheel_without_qt_names_the_gui_requirements(wheel, tmp_path):
    """From a wheel, `torsal[gui]` cannot be resolved (Torsal is not on the package index): the
    hint installs the extra's own requirements, read from the wheel's metadata, into this Python."""
    site = tmp_path / "site"
    done = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--quiet", "--target",
                           str(site), str(wheel)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    script = ("import sys\n"
              "sys.modules['PySide6'] = None  # as if PySide6 were not installed\n"
              "from torsal.app.cli import main\n"
              "sys.exit(main(['gui', '--example', 'first-steps']))\n")
    env = {**os.environ, "PYTHONPATH": str(site), "DISPLAY": os.environ.get("DISPLAY") or ":99"}
    shown = subprocess.run([sys.executable, "-P", "-c", script], capture_output=True, text=True, cwd=tmp_path,
                           env=env, timeout=120)
    assert shown.returncode == 2
    hint = next(line for line in shown.stderr.splitlines() if "Install it with:" in line)
    assert f"{sys.executable} -m pip install " in hint
    for requirement in ("PySide6-Essentials>=6.9", "pyvista>=0.45", "pyvistaqt>=0.11"):
        assert requirement in hint
    assert "torsal[gui]" not in hint and "constraints" not in hint


def test_torsal_gui_without_pyside6_exits_2_with_the_install_line(tmp_path):
    script = ("import sys\n"
              "sys.modules['PySide6'] = None  # as if PySide6 were not installed\n"
              "from torsal.app.cli import main\n"
              "sys.exit(main(['gui', '--example', 'first-steps']))\n")
    env = {**os.environ, "DISPLAY": os.environ.get("DISPLAY") or ":99"}
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=ROOT, env=env,
                          timeout=120)
    assert done.returncode == 2
    # run from this checkout: the command that works here, in this checkout's folder (with -e
    # when Torsal is installed editable from it, as make run does)
    hint = next(line for line in done.stderr.splitlines() if "Install it with:" in line)
    start = f"cd {ROOT} && {sys.executable} {CHECKOUT_INSTALL}"
    assert hint.split("Install it with: ")[1] in (f"{start}'.[gui]'", f"{start}-e '.[gui]'")
    assert "Traceback" not in done.stderr + done.stdout


def test_torsal_gui_opens_an_example_by_name_headless_without_a_display(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    done = subprocess.run([sys.executable, "-m", "torsal.app.cli", "gui", "--example", "first-steps"],
                          capture_output=True, text=True, cwd=ROOT, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "first-steps.graph: solved 8 nodes" in done.stdout


def test_torsal_version_is_the_installed_distributions():
    from importlib.metadata import version

    done = subprocess.run([sys.executable, "-m", "torsal.app.cli", "--version"], capture_output=True,
                          text=True, cwd=ROOT, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == f"torsal {version('torsal')}"


def test_torsal_run_and_check_take_an_example_by_name():
    from torsal.app.cli import main

    command = [sys.executable, "-m", "torsal.app.cli", "run", "--example", "first-steps", "--json"]
    done = subprocess.run(command, capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    import json

    assert json.loads(done.stdout)["file"].endswith("first-steps.graph")
    assert main(["check", "--example", "paper-strip"]) == 0
    assert main(["run", "--example", "no-such-example"]) == 2
    assert main(["run"]) == 2
    assert main(["run", "x.graph", "--example", "first-steps"]) == 2


def make_dry_run(tmp_path: Path, target: str) -> str:
    """`make -n TARGET` in a folder holding only what a fresh clone has for make (no .venv)."""
    for name in ("Makefile", "pyproject.toml", "constraints.txt"):
        shutil.copy(ROOT / name, tmp_path / name)
    # as a user types it: not as a sub-make of `make test` (whose flags and "Entering
    # directory /tmp/pytest-…" lines would leak in)
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MAKELEVEL", "MFLAGS")}
    done = subprocess.run(["make", "--no-print-directory", "-n", target], capture_output=True, text=True,
                          cwd=tmp_path, timeout=60, env=env)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_make_run_in_a_fresh_clone_installs_the_app_but_no_test_tools(tmp_path):
    commands = make_dry_run(tmp_path, "run")
    assert "-m venv .venv" in commands
    assert "-c constraints.txt -e '.[gui]'" in commands
    assert "[test]" not in commands and "pytest" not in commands


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_make_test_in_a_fresh_clone_installs_the_test_tools_with_the_constraints(tmp_path):
    commands = make_dry_run(tmp_path, "test")
    assert "-c constraints.txt -e '.[test]'" in commands
    assert "-m pytest" in commands


def test_constraints_pin_every_declared_dependency():
    import tomllib

    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    extras = project["optional-dependencies"].values()
    declared = project["dependencies"] + [r for extra in extras for r in extra]
    names = {r.split(">")[0].split("=")[0].split("[")[0].split("<")[0].strip().lower().replace("_", "-")
             for r in declared if not r.startswith("torsal")}
    lines = (ROOT / "constraints.txt").read_text(encoding="utf-8").splitlines()
    pinned = {line.split("==")[0].strip().lower().replace("_", "-") for line in lines if "==" in line}
    assert names <= pinned, sorted(names - pinned)


@pytest.mark.skipif(os.environ.get("TORSAL_CHECK_BOUNDS") != "1",
                    reason="slow (downloads the oldest allowed wheels): TORSAL_CHECK_BOUNDS=1 "
                    "or make check-bounds")
def test_the_declared_lower_bounds_install_and_every_module_imports():
    done = subprocess.run([sys.executable, "-m", "tools.check_bounds"], capture_output=True, text=True,
                          cwd=ROOT, timeout=1800)
    assert done.returncode == 0, done.stdout[-4000:]
    assert "lower bounds: OK" in done.stdout

"""The tests' folders mirror the package's, and shared helpers live in one place.

A test of ``torsal/a/b/c.py`` sits in ``tests/a/b/``; what several test files share sits in
``tests/support/`` (docs/contributing.md, "Tests").
"""
from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TESTS = ROOT / "tests"
#: Folders of tests that are not a package's mirror: shared helpers, data, timings.
OWN = {"support", "fixtures", "benchmarks", "screenshots", "__pycache__"}
#: Modules a test folder may hold besides its tests: pytest's hooks, the package marker, and
#: the one script a GUI test runs as a child process by its path.
ALLOWED = {"conftest.py", "__init__.py", "autosave_child.py"}


def test_every_test_folder_mirrors_a_package():
    strays = []
    for folder in TESTS.rglob("*"):
        relative = folder.relative_to(TESTS)
        if not folder.is_dir() or OWN & set(relative.parts):
            continue
        if not (ROOT / "torsal" / relative / "__init__.py").is_file():
            strays.append(str(relative))
    assert strays == [], f"test folders with no package of that name in torsal/: {strays}"


def test_shared_helpers_live_in_support():
    helpers = [
        str(path.relative_to(TESTS))
        for path in TESTS.rglob("*.py")
        if not OWN & set(path.relative_to(TESTS).parts)
        and not path.name.startswith("test_")
        and path.name not in ALLOWED
    ]
    assert helpers == [], f"helper modules outside tests/support/: {helpers}"

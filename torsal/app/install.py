"""How this Torsal was installed, so that what the ``torsal`` command tells a user works here.

Torsal is installed two ways: from a checkout of its repository (``make run``, or
``pip install -c constraints.txt .`` / ``-e .``) or from a wheel someone built. A checkout is
recognised by the folder holding this ``torsal`` package: it also holds the ``pyproject.toml``
that names the project ``torsal`` and the ``constraints.txt`` the Makefile installs with.
A wheel's files sit in site-packages, with no such folder around them.
"""

from __future__ import annotations

import json
import shlex
import sys
import tomllib
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

import torsal

#: The distribution that installs the ``torsal`` package.
DISTRIBUTION = "torsal"


def version() -> str:
    """This Torsal's version (``0+unknown`` for a checkout run without installing it)."""
    return torsal.__version__


def checkout() -> Path | None:
    """The repository folder this Torsal runs from, or None when it was installed from a wheel."""
    root = Path(torsal.__file__).resolve().parent.parent
    try:
        project = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8")).get("project", {})
    except (OSError, ValueError):
        return None
    if project.get("name") != DISTRIBUTION or not (root / "constraints.txt").is_file():
        return None
    return root


def _editable(root: Path) -> bool:
    """Whether the installed ``torsal`` is an editable install of the checkout ``root``
    (``make run``'s ``pip install -e``): pip's record of where it came from says so."""
    try:
        record = json.loads(distribution(DISTRIBUTION).read_text("direct_url.json") or "{}")
    except (PackageNotFoundError, ValueError):
        return False
    url = record.get("url", "") if isinstance(record, dict) else ""
    editable = isinstance(record, dict) and bool(record.get("dir_info", {}).get("editable"))
    return editable and url.startswith("file://") and Path(url[len("file://"):]).resolve() == root


def _pip() -> str:
    """``pip`` of the interpreter running Torsal (a bare ``pip`` may belong to another one)."""
    return f"{shlex.quote(sys.executable)} -m pip"


def extra_requirements(extra: str) -> list[str]:
    """The requirements the installed distribution declares for ``extra`` (``gui``, ``test``)."""
    try:
        declared = distribution(DISTRIBUTION).requires or []
    except PackageNotFoundError:
        return []
    wanted = []
    for requirement in declared:
        spec, _, marker = requirement.partition(";")
        if marker and "extra" in marker and (f'"{extra}"' in marker or f"'{extra}'" in marker):
            wanted.append(spec.strip())
    return wanted


def install_command(extra: str = "gui") -> str:
    """The command that installs ``extra``'s packages for the way this Torsal was installed.

    From a checkout: the project with the extra, pinned by its constraints, run in the checkout
    (editable, ``-e``, when Torsal is installed editable from it, as ``make run`` does).
    From a wheel (Torsal is not on the package index, so ``torsal[gui]`` cannot be resolved
    there): the extra's own requirements, as the wheel's metadata declares them.
    """
    root = checkout()
    if root is not None:
        editable = "-e " if _editable(root) else ""
        return f"cd {shlex.quote(str(root))} && {_pip()} install -c constraints.txt {editable}'.[{extra}]'"
    requirements = extra_requirements(extra)
    if not requirements:  # metadata unreadable: name the packages pyproject.toml declares for the app
        requirements = ["PySide6-Essentials>=6.9", "pyvista>=0.45", "pyvistaqt>=0.11"]
    return f"{_pip()} install " + " ".join(shlex.quote(r) for r in requirements)

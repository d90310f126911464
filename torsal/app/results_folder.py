"""``--out DIR`` of ``torsal run``: the folder resolved once and Torsal's results written into it.

``DIR`` is made if missing and resolved once, when the command starts; a ``DIR`` that is a
symbolic link is refused (exit 2) rather than followed, and its (device, inode) is kept so
that a folder swapped in later is refused too. ``results.json`` and every file the
graph's exporters write there go through the one write path
(:mod:`torsal.engine.write_path`): never through a link, never half-written.
"""

from __future__ import annotations

from pathlib import Path

from torsal.app.headless import UsageError
from torsal.engine.write_path import OutFolder


def out_folder(path: Path, flag: str = "--out") -> OutFolder:
    """``path`` as a results folder, or a :class:`UsageError` saying why it cannot be one."""
    try:
        return OutFolder.resolve(path, flag)
    except OSError as exc:
        raise UsageError(str(exc)) from None  # resolve_out_folder's sentences name the flag


def write_results(out: OutFolder, name: str, text: str) -> Path:
    """Write ``out/name`` atomically (a full disk leaves the old file whole, or none)."""
    try:
        return out.write(name, text)
    except OSError as exc:
        raise UsageError(f"--out {out.path}: cannot write {name}: {exc.strerror or exc}") from None

"""Settings kept between sessions: recent files and the window layout.

Stored in ``torsal.ini`` in the configuration folder: ``$TORSAL_CONFIG_DIR`` when set
(tests use it), otherwise Qt's per-user application config folder.
"""

from __future__ import annotations

import os
from pathlib import Path

from PySide6.QtCore import QByteArray, QSettings, QStandardPaths

RECENT_KEPT = 10


def config_dir() -> Path:
    """The folder for settings and recovery files (created when missing)."""
    explicit = os.environ.get("TORSAL_CONFIG_DIR")
    if explicit:
        folder = Path(explicit)
    else:
        base = QStandardPaths.writableLocation(QStandardPaths.StandardLocation.GenericConfigLocation)
        folder = Path(base or Path.home() / ".config") / "torsal"
    folder.mkdir(parents=True, exist_ok=True)
    return folder


class AppSettings:
    """Recent files and window state, in an INI file."""

    def __init__(self, folder: Path | None = None) -> None:
        self.folder = folder or config_dir()
        self._settings = QSettings(str(self.folder / "torsal.ini"), QSettings.Format.IniFormat)

    def recent_files(self) -> list[Path]:
        value = self._settings.value("recent", [])
        if isinstance(value, str):
            value = [value]
        return [Path(p) for p in (value or []) if p]

    def add_recent(self, path: Path) -> None:
        path = Path(path).resolve()
        files = [path, *[p for p in self.recent_files() if p != path]][:RECENT_KEPT]
        self._settings.setValue("recent", [str(p) for p in files])
        self._settings.sync()

    def window_state(self) -> tuple[QByteArray | None, QByteArray | None]:
        return self._settings.value("geometry"), self._settings.value("state")

    def save_window_state(self, geometry: QByteArray, state: QByteArray) -> None:
        self._settings.setValue("geometry", geometry)
        self._settings.setValue("state", state)
        self._settings.sync()

    def show_nicknames(self) -> bool:
        """Nicknames on tiles instead of the node icons (View menu)."""
        return str(self._settings.value("show_nicknames", "false")).lower() == "true"

    def set_show_nicknames(self, show: bool) -> None:
        self._settings.setValue("show_nicknames", "true" if show else "false")
        self._settings.sync()

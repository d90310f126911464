"""Run by test_autosave.py in a subprocess: open a file, make unsaved edits, wait for the
autosave, say so on stdout, then wait to be killed."""

from __future__ import annotations

import sys
from pathlib import Path

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication


def main() -> None:
    app = QApplication(sys.argv[:1])
    from torsal.app.gui.main_window import MainWindow

    window = MainWindow()  # TORSAL_CONFIG_DIR and TORSAL_AUTOSAVE_SECONDS come from the test
    window.show()
    assert window.open_file(Path(sys.argv[1]), ask=False)
    window.editor.move({"width": (111.0, 222.0)})
    window.editor.set_setting("count", "value", 7)

    def report() -> None:
        if window.autosaver.saves:
            print("autosaved", flush=True)
            poll.stop()

    poll = QTimer()
    poll.timeout.connect(report)
    poll.start(50)
    app.exec()


if __name__ == "__main__":
    main()

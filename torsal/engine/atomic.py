"""Replacing a file without ever leaving it half-written, keeping the old one as ``.bak``.

A save that is killed at any moment leaves the file and its ``.bak`` each a complete
version. This is the graph-save spelling of :func:`torsal.engine.write_path.write_file`
(the one write path): the file's folder is resolved once and held open, the new content
goes to a temporary file created beside it exclusively (never through a link), is
flushed to disk, and is renamed over the file; the previous file becomes the ``.bak``
through a hard link renamed into place. The replaced file's permissions are kept.

Example::

    replace_keeping_backup(target, lambda temporary: temporary.write_text(text))
"""

from __future__ import annotations

from pathlib import Path

from torsal.engine.write_path import BACKUP_SUFFIX, Produce, backup_path, write_file

__all__ = ["BACKUP_SUFFIX", "backup_path", "replace_keeping_backup"]


def replace_keeping_backup(path: Path, write: Produce) -> Path:
    """Replace ``path`` with what ``write`` gives (bytes, text, or a callable writing the
    file name it is given); the current file, if any, becomes ``<name>.bak``. Returns
    ``path``. A failure leaves ``path`` and its ``.bak`` as they were."""
    return write_file(Path(path), write, backup=True, mode=None)

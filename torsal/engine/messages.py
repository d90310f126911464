"""What a solve says and how it is stopped: message levels, messages, the cancel token.

They live apart from :mod:`torsal.engine.node` so that the per-solve state
(:mod:`torsal.engine.solve_context`) can hold them without importing the node class.
:mod:`torsal.engine.node` re-exports all three, where nodes and front-ends import them.
"""

from __future__ import annotations

import enum
import threading
from dataclasses import dataclass

from torsal.engine.errors import Cancelled


class Level(enum.IntEnum):
    """Message levels, in increasing severity."""

    REMARK = 0
    WARNING = 1
    ERROR = 2


class CancelToken:
    """Shared between a front-end and a running solve; long nodes call :meth:`check`."""

    def __init__(self) -> None:
        self._event = threading.Event()

    def cancel(self) -> None:
        self._event.set()

    @property
    def cancelled(self) -> bool:
        return self._event.is_set()

    def check(self) -> None:
        """Raise :class:`Cancelled` if the solve has been cancelled."""
        if self._event.is_set():
            raise Cancelled


@dataclass(frozen=True)
class Message:
    level: Level
    text: str

    def to_json(self) -> dict[str, str]:
        return {"level": self.level.name.lower(), "text": self.text}

"""Fuzzy search over the node catalogue: names, nicknames and descriptions.

``"numsl"`` finds NumberSlider (the letters in order), ``"slider"`` finds both
sliders, ``"ruled"`` finds nodes whose description mentions rulings.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

from app.gui.icons import node_letters


@dataclass(frozen=True)
class Entry:
    """One node type as the search sees it."""

    type_id: str
    name: str
    palette: str
    nickname: str
    description: str
    cls: type


def build_entries(node_classes: Iterable[type]) -> list[Entry]:
    entries = []
    for cls in node_classes:
        palette, _, name = cls.type_id.partition(".")
        help_text = cls.help() if hasattr(cls, "help") else ""
        nickname = getattr(cls, "nickname", "") or node_letters(cls)
        entries.append(Entry(cls.type_id, name, palette, str(nickname), help_text, cls))
    return entries


def _subsequence_score(query: str, text: str) -> float | None:
    """How tightly ``query``'s letters appear in order in ``text`` (None if they do not)."""
    position, gaps, start = 0, 0, -1
    for char in query:
        found = text.find(char, position)
        if found < 0:
            return None
        if start < 0:
            start = found
        gaps += found - position if position else 0
        position = found + 1
    return 1.0 / (1.0 + gaps + start * 0.5)


def score(query: str, entry: Entry) -> float | None:
    """A relevance score (higher is better), or None when ``entry`` does not match."""
    q = query.strip().lower()
    if not q:
        return 0.0
    compact = q.replace(" ", "")
    name = entry.name.lower()
    if name == compact:
        return 100.0
    if entry.nickname.lower() == compact:
        return 88.0
    if name.startswith(compact):
        return 90.0 - len(name) / 100
    if compact in name:
        return 80.0 - name.index(compact) / 100
    tight = _subsequence_score(compact, name)
    if tight is not None:
        return 50.0 + 20.0 * tight
    if compact in entry.type_id.lower():
        return 45.0
    description = entry.description.lower()
    words = q.split()
    if all(word in description for word in words):
        return 30.0 - description.index(words[0]) / 1000
    return None


def search(
    entries: list[Entry], query: str, accept: Callable[[Entry], bool] | None = None, limit: int = 60
) -> list[Entry]:
    """Entries matching ``query`` (and ``accept``), best first."""
    scored = []
    for entry in entries:
        if accept is not None and not accept(entry):
            continue
        value = score(query, entry)
        if value is not None:
            scored.append((-value, entry.palette, entry.name, entry))
    scored.sort(key=lambda t: t[:3])
    return [t[3] for t in scored[:limit]]

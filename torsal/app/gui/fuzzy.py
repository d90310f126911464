"""Fuzzy search over the node catalogue: names, nicknames, aliases and descriptions.

A node is found by its name ("DivideCurve" or "Divide Curve"), its nickname ("Pt"), one
of its aliases — Grasshopper's name for the same thing ("Construct Point", "XY Plane",
"Unroll Surface") or a designer's word ("unroll", "flat pattern") — or words of its
description. Each node class declares its ``nickname`` and ``aliases``; the search knows
no node by name. Ranking: the exact name first, then an exact nickname or alias, then
names that start with what was typed, aliases that start with it, names that contain it,
the letters in order (``"numsl"`` finds NumberSlider), the description. A typed number
(``6``, ``-2.5``) or range (``0<6<10``) is read by :func:`slider_settings` as a slider to
place, as in Grasshopper.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from torsal.app.gui.icons import node_letters
from torsal.engine.node import words


@dataclass(frozen=True)
class Entry:
    """One node type as the search sees it."""

    type_id: str
    name: str
    palette: str
    nickname: str
    description: str
    cls: type
    aliases: tuple[str, ...] = ()

    @property
    def title(self) -> str:
        """The name as words ("Divide Curve"), as the canvas titles the node."""
        return words(self.name)


def build_entries(node_classes: Iterable[type]) -> list[Entry]:
    entries = []
    for cls in node_classes:
        palette, _, name = cls.type_id.partition(".")
        help_text = cls.help() if hasattr(cls, "help") else ""
        nickname = getattr(cls, "nickname", "") or node_letters(cls)
        aliases = tuple(str(a) for a in getattr(cls, "aliases", ()) or ())
        entries.append(Entry(cls.type_id, name, palette, str(nickname), help_text, cls, aliases))
    return entries


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)"
_SLIDER_RE = re.compile(rf"^\s*(?:({_NUMBER})\s*<\s*)?({_NUMBER})(?:\s*<\s*({_NUMBER}))?\s*$")


def _decimals(text: str) -> int:
    return len(text.partition(".")[2]) if "." in text else 0


def slider_settings(query: str) -> dict[str, float | int] | None:
    """The NumberSlider a typed number makes, as in Grasshopper: ``6`` is a slider at 6,
    from 0 to the power of ten above it (0 to 10); ``0<6<20`` sets the range too. The
    decimals are those typed. None when ``query`` is not a number (or the range is empty,
    or the value outside it)."""
    match = _SLIDER_RE.match(query)
    if match is None:
        return None
    lo_text, value_text, hi_text = match.groups()
    if (lo_text is None) != (hi_text is None):
        return None
    value = float(value_text)
    if not math.isfinite(value):
        return None
    decimals = max(_decimals(t) for t in (lo_text, value_text, hi_text) if t is not None)
    if lo_text is not None:
        lo, hi = float(lo_text), float(hi_text)
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi and lo <= value <= hi):
            return None
    else:
        size = abs(value)
        reach = 10.0 ** math.ceil(math.log10(size)) if size > 0 else 1.0
        if reach == size:  # 10 reaches 100: the value does not sit at the end
            reach *= 10
        lo, hi = (0.0, reach) if value >= 0 else (-reach, 0.0)
    return {"value": value, "min": lo, "max": hi, "decimals": min(decimals, 15)}


def _compact(text: str) -> str:
    return text.lower().replace(" ", "")


def _alias_score(compact: str, entry: Entry) -> float | None:
    """95 for an exact nickname or alias; 84 for an alias that starts with the query."""
    best = None
    if _compact(entry.nickname) == compact:
        return 95.0
    for alias in entry.aliases:
        word = _compact(alias)
        if word == compact:
            return 95.0
        if len(compact) >= 3 and word.startswith(compact):
            best = 84.0
    return best


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
    alias = _alias_score(compact, entry)
    if alias is not None and alias > 90.0:
        return alias
    if name.startswith(compact):
        return 90.0 - len(name) / 100
    if alias is not None:
        return alias
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
    entries: list[Entry],
    query: str,
    accept: Callable[[Entry], bool] | None = None,
    limit: int = 60,
    rank: Callable[[Entry], tuple] | None = None,
) -> list[Entry]:
    """Entries matching ``query`` (and ``accept``), best first; ``rank`` (a sort key) orders
    entries that score alike — all of them when nothing is typed (a dropped wire's likeliest
    nodes, :mod:`torsal.app.gui.wire_ranking`)."""
    scored = []
    for entry in entries:
        if accept is not None and not accept(entry):
            continue
        value = score(query, entry)
        if value is not None:
            key = rank(entry) if rank is not None else (entry.palette, entry.name)
            scored.append((-value, key, entry))
    scored.sort(key=lambda t: t[:2])
    return [t[2] for t in scored[:limit]]

"""Length units, named as in the ``.graph`` file's ``"units"`` field: ``mm``, ``cm``, ``m``,
``in`` and ``ft`` (a few spelled-out synonyms are accepted). The file nodes scale what they
write by them; BendingCheck turns a model's radii into millimetres."""

from __future__ import annotations

from torsal.nodes.common.files import FileFailure

#: Length of one unit in metres.
METRES: dict[str, float] = {"mm": 0.001, "cm": 0.01, "m": 1.0, "in": 0.0254, "ft": 0.3048}

_SYNONYMS = {
    "millimeter": "mm", "millimeters": "mm", "millimetre": "mm", "millimetres": "mm",
    "centimeter": "cm", "centimeters": "cm", "centimetre": "cm", "centimetres": "cm",
    "meter": "m", "meters": "m", "metre": "m", "metres": "m",
    "inch": "in", "inches": "in", '"': "in",
    "foot": "ft", "feet": "ft", "'": "ft",
}


def unit_name(text: str | None, what: str = "Units") -> str:
    """The canonical name (``mm``, ``cm``, ``m``, ``in``, ``ft``) of a unit, or a FileFailure
    naming ``what`` (the file nodes turn it into their file error, BendingCheck into a warning)."""
    key = (text or "").strip().lower()
    key = _SYNONYMS.get(key, key)
    if key not in METRES:
        raise FileFailure(
            f"{what} {text!r} is not a length unit Torsal knows: use mm, cm, m, in or ft"
        )
    return key


def unit_scale(source: str, target: str) -> float:
    """The factor that turns lengths in ``source`` units into ``target`` units."""
    return METRES[unit_name(source)] / METRES[unit_name(target)]

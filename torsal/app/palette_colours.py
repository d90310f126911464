"""Each palette's colour, in one place for the app (tiles, node bars) and the icon drawer
(``tools/make_icons.py``), which needs no Qt to read it."""

from __future__ import annotations

COLOURS: dict[str, str] = {
    "params": "#5b7fa6",
    "maths": "#7a6aa8",
    "lists": "#5f8f6a",
    "curves": "#3d8fb3",
    "surfaces": "#3f9e95",
    "transform": "#8a7a4e",
    "analysis": "#c0622f",
    "developable": "#b3453f",
    "patching": "#a0527f",
    "display": "#5a5a5a",
    "io": "#6b6b8a",
    "optimise": "#4f7f4f",
}

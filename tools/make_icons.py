"""Write one 24 px SVG icon per node type into ``torsal/resources/icons/`` (see its README).

Each icon is a rounded tile in its palette's colour with a white line glyph that shows
what the node does (a developable strip is a band crossed by straight rulings; a divide
is a curve with points on it). The glyphs are composed here from a few primitives so the
whole set keeps one style; run ``.venv/bin/python tools/make_icons.py`` after adding a
node, then look at the sheet it writes (``--sheet out.png``).
"""

from __future__ import annotations

import sys
from pathlib import Path

from torsal.app.palette_colours import COLOURS

OUT = Path(__file__).resolve().parent.parent / "torsal" / "resources" / "icons"

#: Tile colours: the palette colours of the app (torsal/app/gui/theme.py), repeated here so
#: the icons are plain files that need no Qt to be made.
TILES = COLOURS  # the palettes' own colours (the app's, torsal/app/palette_colours.py)
INK = "#ffffff"  # every glyph's lines
ACCENT = "#ffd166"  # the one part a glyph points at (the item picked, the result)
SOFT = "#ffffff55"  # fills: a surface, a sheet


# -- primitives (a 24 × 24 canvas, y down) ------------------------------------------------
def _paint(kind: str, colour: str) -> str:
    """``fill="…"`` (or stroke), with an 8-digit colour's alpha as an opacity (SVG Tiny,
    which Qt renders, has no #RRGGBBAA)."""
    if colour.startswith("#") and len(colour) == 9:
        return f'{kind}="{colour[:7]}" {kind}-opacity="{int(colour[7:], 16) / 255:.2f}"'
    return f'{kind}="{colour}"'


def line(x1: float, y1: float, x2: float, y2: float, c: str = INK, w: float = 1.6, dash: str = "") -> str:
    d = f' stroke-dasharray="{dash}"' if dash else ""
    return f'<line x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="{c}" stroke-width="{w}"{d}/>'


def path(d: str, c: str = INK, w: float = 1.6, fill: str = "none", dash: str = "") -> str:
    extra = f' stroke-dasharray="{dash}"' if dash else ""
    return f'<path d="{d}" {_paint("stroke", c)} stroke-width="{w}" {_paint("fill", fill)}{extra}/>'


def poly(
    points: list[tuple[float, float]], c: str = INK, w: float = 1.6, fill: str = "none", closed: bool = False
) -> str:
    tag = "polygon" if closed else "polyline"
    pts = " ".join(f"{x},{y}" for x, y in points)
    return f'<{tag} points="{pts}" {_paint("stroke", c)} stroke-width="{w}" {_paint("fill", fill)}/>'


def circle(cx: float, cy: float, r: float, c: str = INK, w: float = 1.6, fill: str = "none") -> str:
    paint = f'{_paint("stroke", c)} stroke-width="{w}" {_paint("fill", fill)}'
    return f'<circle cx="{cx}" cy="{cy}" r="{r}" {paint}/>'


def spot(cx: float, cy: float, r: float = 1.7, c: str = INK) -> str:
    return f'<circle cx="{cx}" cy="{cy}" r="{r}" fill="{c}" stroke="none"/>'


def rect(
    x: float, y: float, w: float, h: float, c: str = INK, sw: float = 1.4, fill: str = "none", rx: float = 0
) -> str:
    return (
        f'<rect x="{x}" y="{y}" width="{w}" height="{h}" rx="{rx}" {_paint("stroke", c)} '
        f'stroke-width="{sw}" {_paint("fill", fill)}/>'
    )


def text(x: float, y: float, s: str, size: float = 7, c: str = INK, anchor: str = "middle") -> str:
    return (
        f'<text x="{x}" y="{y}" font-family="DejaVu Sans, Arial, sans-serif" font-weight="bold" '
        f'font-size="{size}" fill="{c}" stroke="none" text-anchor="{anchor}">{s}</text>'
    )


def arrow(x1: float, y1: float, x2: float, y2: float, c: str = INK, w: float = 1.6, head: float = 3.2) -> str:
    import math

    a = math.atan2(y2 - y1, x2 - x1)
    left = (x2 - head * math.cos(a - 0.5), y2 - head * math.sin(a - 0.5))
    right = (x2 - head * math.cos(a + 0.5), y2 - head * math.sin(a + 0.5))
    return line(x1, y1, x2, y2, c, w) + poly([left, (x2, y2), right], c, w)


CURVE = "M4,17 C8,5 14,21 20,8"  # the curve every curves-palette glyph starts from
PATCH = "M4,9 C9,6 15,10 20,7 L20,18 C15,21 9,17 4,19 Z"  # a curved surface patch
FLAT = [(3, 16), (15, 16), (21, 10), (9, 10)]  # a plane seen from above, in perspective


def strip_rulings(top: list[tuple[float, float]], bottom: list[tuple[float, float]], c: str = INK) -> str:
    """A developable strip: two rims and the straight rulings between them."""
    out = poly(top, c, 1.5) + poly(bottom, c, 1.5)
    out += poly(top + bottom[::-1], "none", 0, SOFT, closed=True)
    for (x1, y1), (x2, y2) in zip(top, bottom, strict=True):
        out += line(x1, y1, x2, y2, c, 0.9)
    return out


def page(c: str = INK) -> str:
    return path("M3,3 L12,3 L16,7 L16,21 L3,21 Z", c, 1.4, "#ffffff22") + path("M12,3 L12,7 L16,7", c, 1.2)


def out_arrow() -> str:
    """Written: an arrow leaving the page."""
    return arrow(13, 16, 22, 16, ACCENT, 2, 3.4)


def in_arrow() -> str:
    """Read: an arrow entering the page."""
    return arrow(22, 16, 13, 16, ACCENT, 2, 3.4)


GLYPHS: dict[str, str] = {
    "curves.CurvePlane": poly([(9, 3), (15, 6), (15, 21), (9, 18)], INK, 1.1, SOFT, True)
    + path(CURVE, INK, 1.6)
    + spot(12, 12.6, 2.2, ACCENT),
    "curves.Rectangle": rect(3.5, 6, 17, 12, INK, 2) + spot(12, 12, 1.3, ACCENT),
    "curves.Polygon": poly([(20, 12), (16, 19), (8, 19), (4, 12), (8, 5), (16, 5)], INK, 2, "none", True)
    + spot(12, 12, 1.3, ACCENT),
    "lists.Dispatch": line(3, 12, 8, 12, INK, 2.4)
    + path("M8,12 C12,12 12,6 15,6 M8,12 C12,12 12,18 15,18", INK, 1)
    + line(16, 4, 21, 4, ACCENT, 2)
    + line(16, 8, 21, 8, ACCENT, 2)
    + line(16, 16, 21, 16, INK, 2)
    + line(16, 20, 21, 20, INK, 2),
    "curves.DivideLength": path(CURVE, INK, 1.6)
    + spot(4, 17, 1.8, ACCENT)
    + spot(8.3, 11, 1.8, ACCENT)
    + spot(14, 13.4, 1.8, ACCENT)
    + line(4, 22, 8.3, 22, INK, 1.1)
    + line(8.3, 22, 14, 22, INK, 1.1)
    + line(4, 20.5, 4, 23, INK, 1)
    + line(8.3, 20.5, 8.3, 23, INK, 1)
    + line(14, 20.5, 14, 23, INK, 1),
    "surfaces.SurfaceClosestPoint": path(PATCH, INK, 1.3, SOFT)
    + spot(12, 3, 2, INK)
    + line(12, 3, 12, 13, ACCENT, 1.2, "1.5,1.2")
    + spot(12, 13.5, 2, ACCENT),
    "params.VectorTwoPoints": spot(4, 18, 2.2) + spot(20, 6, 2.2) + arrow(5.5, 17, 18, 7.5, ACCENT, 1.8),
    "params.Distance": spot(4, 12, 2.2)
    + spot(20, 12, 2.2)
    + line(4, 17, 20, 17, ACCENT, 1.2)
    + line(4, 15, 4, 19, ACCENT, 1.2)
    + line(20, 15, 20, 19, ACCENT, 1.2)
    + text(12, 9, "d", 7),
    "curves.CurveClosestPoint": path(CURVE, INK, 1.6)
    + spot(17, 20, 2, INK)
    + line(17, 20, 14.8, 13.2, ACCENT, 1.2, "1.5,1.2")
    + spot(14.8, 13.2, 2, ACCENT),
    # -- joining, exploding and cutting curves; dividing and cutting surfaces ------------
    "curves.JoinCurves": path("M4,17 C6,10 9,10 12,12.5", INK, 1.6)
    + path("M12,12.5 C15,15 18,14 20,8", INK, 1.6)
    + spot(12, 12.5, 2.4, ACCENT),
    "curves.Explode": line(3, 18, 6.5, 9, INK, 1.8)
    + line(9, 7, 12.5, 15, INK, 1.8)
    + line(15, 15, 20, 5, INK, 1.8)
    + "".join(spot(x, y, 1.5, ACCENT) for x, y in ((6.5, 9), (9, 7), (12.5, 15), (15, 15))),
    "curves.Shatter": path(CURVE, INK, 1.6)
    + line(6, 9, 10.5, 13, ACCENT, 1.8)
    + line(12, 16.5, 16, 10.5, ACCENT, 1.8),
    "surfaces.DivideSurface": path(PATCH, INK, 1.2, SOFT)
    + "".join(spot(x, y, 1.2, ACCENT) for x in (6, 10, 14, 18) for y in (11, 16)),
    "surfaces.Contour": path(PATCH, INK, 1.2, SOFT)
    + path("M4,12.5 C9,9.5 15,13.5 20,10.5", ACCENT, 1.2)
    + path("M4,16 C9,13 15,17 20,14", ACCENT, 1.2),
    "surfaces.Section": path(PATCH, INK, 1.2, SOFT)
    + poly([(9, 2.5), (15, 5), (15, 22), (9, 19.5)], INK, 0.9, "none", True)
    + path("M12,8.5 C12.5,12 11.5,15 12,18.5", ACCENT, 2.2),
    "surfaces.Sweep1": path("M4,19 C8,19 14,16 18,6", ACCENT, 1.6)
    + path("M2,17 C2,14 6,14 6,17 C6,20 2,20 2,17 Z", INK, 1.3, SOFT)
    + path("M15,7 C15,4 21,4 21,7 C21,10 15,10 15,7 Z", INK, 1.3, SOFT)
    + path("M4,14.5 C9,14 13,11 16,4.5 M4,19.8 C9,20 15,17 20.5,8.5", INK, 0.9),
    "lists.SimplifyTree": line(3, 12, 9, 12, ACCENT, 1.4, "1.5,1.2")
    + path("M9,12 C12,12 12,6 15,6 M9,12 C12,12 12,18 15,18", INK, 1)
    + line(16, 6, 21, 6, INK, 2)
    + line(16, 18, 21, 18, INK, 2),
    "lists.ExplodeTree": line(3, 12, 7, 12, INK, 2)
    + "".join(line(8, 12, 8 + 2.6 * dx, 12 + 2.6 * dy, ACCENT, 1.2)
              for dx, dy in ((0.7, -0.7), (1, 0), (0.7, 0.7), (0, -1), (0, 1)))
    + path("M11,12 C13,12 13,4 16,4 M11,12 L16,12 M11,12 C13,12 13,20 16,20", INK, 1)
    + line(17, 4, 21, 4, ACCENT, 2.2)
    + line(17, 12, 21, 12, ACCENT, 2.2)
    + line(17, 20, 21, 20, ACCENT, 2.2),
    "lists.TreeBranch": line(3, 12, 7, 12, INK, 2)
    + path("M7,12 C11,12 11,5 14,5 M7,12 L14,12 M7,12 C11,12 11,19 14,19", INK, 1)
    + line(15, 5, 20, 5, INK, 2)
    + line(15, 12, 20, 12, INK, 2)
    + line(15, 19, 21, 19, ACCENT, 2.6),
    "lists.TrimTree": "".join(line(3, y, 7, y, INK, 2) for y in (3.5, 8.5, 15.5, 20.5))
    + path("M7,3.5 C10,3.5 10,6 12,6 M7,8.5 C10,8.5 10,6 12,6 M7,15.5 C10,15.5 10,18 12,18 "
           "M7,20.5 C10,20.5 10,18 12,18", INK, 1)
    + line(13, 6, 20, 6, ACCENT, 2.2)
    + line(13, 18, 20, 18, ACCENT, 2.2),
    "lists.PathMapper": line(3, 7, 8, 7, INK, 2)
    + line(3, 17, 8, 17, INK, 2)
    + path("M8,7 C13,7 11,17 16,17 M8,17 C13,17 11,7 16,7", ACCENT, 1.3)
    + line(16, 7, 21, 7, INK, 2)
    + line(16, 17, 21, 17, INK, 2),
    # -- params: values a designer sets: knobs, dots and planes --------------------------
    "params.NumberSlider": line(3, 13, 21, 13) + circle(14, 13, 3.2, INK, 1.4, ACCENT) + text(7, 9, "0.5", 6),
    "params.IntegerSlider": line(3, 14, 21, 14)
    + "".join(line(x, 11.5, x, 16.5, INK, 1) for x in (4, 9, 14, 19))
    + rect(7, 10.5, 4, 7, INK, 1.2, ACCENT)
    + text(17, 9, "3", 6.5),
    "params.Panel": rect(4, 4, 16, 16, INK, 1.4, SOFT, 1.5)
    + "".join(line(7, y, 17, y, INK, 1.2) for y in (9, 12.5, 16)),
    "params.Point": line(12, 5, 12, 19, INK, 1) + line(5, 12, 19, 12, INK, 1) + spot(12, 12, 3, ACCENT),
    "params.Toggle": rect(3.5, 8, 17, 8, INK, 1.4, SOFT, 4) + spot(16.5, 12, 3, ACCENT),
    "params.UnitX": arrow(4, 15, 20, 15) + text(8, 11, "X", 8),
    "params.UnitY": arrow(5, 18, 18, 7) + text(7, 10, "Y", 8),
    "params.UnitZ": arrow(12, 21, 12, 4) + text(18, 16, "Z", 8),
    "params.ValueList": rect(4, 5, 16, 14, INK, 1.3, SOFT, 1.5)
    + line(7, 9, 13, 9, ACCENT, 2)
    + line(7, 12.5, 13, 12.5, INK, 1.2)
    + line(7, 16, 13, 16, INK, 1.2)
    + poly([(15, 8), (17, 10), (19, 8)], INK, 1.2),
    "params.Vector": spot(5, 19, 2) + arrow(5, 19, 19, 5, ACCENT, 1.8),
    "params.XYPlane": poly(FLAT, INK, 1.4, SOFT, True) + text(12, 14.8, "XY", 6.5),
    "params.XZPlane": rect(5, 4, 14, 13, INK, 1.4, SOFT)
    + text(12, 13, "XZ", 6.5)
    + line(3, 20, 21, 20, INK, 1),
    "params.YZPlane": poly([(8, 3), (16, 7), (16, 21), (8, 17)], INK, 1.4, SOFT, True)
    + text(12, 14, "YZ", 5.5),
    "params.ConstructPlane": poly(FLAT, INK, 1.2, SOFT, True)
    + arrow(9, 13, 17, 13, ACCENT, 1.6)
    + arrow(9, 13, 12, 8.5, ACCENT, 1.6)
    + spot(9, 13, 1.5),
    "params.DeconstructPlane": poly([(3, 20), (11, 20), (15, 16), (7, 16)], INK, 1.1, SOFT, True)
    + arrow(13, 11, 20, 11, ACCENT, 1.4)
    + arrow(13, 11, 16, 5, ACCENT, 1.4)
    + arrow(6, 11, 6, 3, ACCENT, 1.4),
    "params.PlaneNormal": poly(FLAT, INK, 1.3, SOFT, True) + arrow(12, 13, 12, 2.5, ACCENT, 1.8),
    "params.PlaneThreePoints": poly(FLAT, INK, 1.2, SOFT, True)
    + spot(3.5, 16, 2, ACCENT)
    + spot(15, 16, 2, ACCENT)
    + spot(20.5, 10, 2, ACCENT),
    "params.DeconstructPoint": spot(15, 8, 2.6, ACCENT)
    + line(15, 8, 15, 20, INK, 1, "2,1.5")
    + line(15, 8, 3, 8, INK, 1, "2,1.5")
    + line(3, 20, 21, 20, INK, 1.2)
    + line(3, 4, 3, 20, INK, 1.2),
    "params.DeconstructVector": arrow(4, 19, 18, 6, ACCENT, 1.8)
    + line(4, 19, 18, 19, INK, 1, "2,1.5")
    + line(18, 19, 18, 9, INK, 1, "2,1.5"),
    # -- maths: numbers: intervals, sequences, formulas ---------------------------------
    "maths.Domain": line(5, 12, 19, 12) + path("M6,8 L4,8 L4,16 L6,16") + path("M18,8 L20,8 L20,16 L18,16"),
    "maths.DeconstructDomain": line(7, 12, 17, 12, INK, 1, "2,1.5")
    + path("M5,8 L3,8 L3,16 L5,16", ACCENT)
    + path("M19,8 L21,8 L21,16 L19,16", ACCENT)
    + spot(7, 12, 1.6)
    + spot(17, 12, 1.6),
    "maths.Expression": text(12, 16, "f(x)", 8.5),
    "maths.Random": rect(5, 5, 14, 14, INK, 1.4, SOFT, 2.5)
    + spot(8.5, 8.5, 1.5)
    + spot(15.5, 8.5, 1.5)
    + spot(12, 12, 1.5)
    + spot(8.5, 15.5, 1.5)
    + spot(15.5, 15.5, 1.5),
    "maths.Range": line(4, 14, 20, 14)
    + "".join(line(x, 10, x, 18, INK, 1.2) for x in (4, 8, 12, 16, 20))
    + path("M4,7 L20,7", ACCENT, 1.2),
    "maths.Series": spot(5, 18)
    + spot(9.5, 14.5)
    + spot(14, 11)
    + spot(18.5, 7.5)
    + arrow(4, 21, 21, 21, INK, 1),
    "maths.Remap": line(8, 6, 16, 6, INK, 1.8)
    + line(3, 18, 21, 18, ACCENT, 1.8)
    + line(8, 6, 3, 18, INK, 0.9, "1.5,1.5")
    + line(16, 6, 21, 18, INK, 0.9, "1.5,1.5")
    + line(12, 6, 12, 18, INK, 0.9, "1.5,1.5"),
    "maths.Bounds": spot(6, 12, 1.4)
    + spot(10, 12, 1.4)
    + spot(12.5, 12, 1.4)
    + spot(18, 12, 1.4)
    + path("M5,7 L3,7 L3,17 L5,17", ACCENT)
    + path("M19,7 L21,7 L21,17 L19,17", ACCENT),
    # -- lists: bars, one per item -------------------------------------------------------
    "lists.ListItem": "".join(line(5, y, 15, y, INK, 2) for y in (6, 10, 18))
    + line(5, 14, 15, 14, ACCENT, 2.4)
    + arrow(21, 14, 17, 14, ACCENT, 1.4),
    "lists.ListLength": "".join(line(4, y, 12, y, INK, 2) for y in (6, 10, 14, 18))
    + path("M15,5 L17,5 L17,19 L15,19", INK, 1.2)
    + text(20.5, 14.5, "#", 7, ACCENT),
    "lists.CullPattern": "".join(line(4, y, 18, y, INK, 2) for y in (5, 13))
    + "".join(line(4, y, 18, y, INK, 1, "1.5,1.5") for y in (9, 17))
    + line(17, 7, 21, 11, ACCENT, 1.4)
    + line(21, 7, 17, 11, ACCENT, 1.4),
    "lists.Flatten": line(4, 5, 8, 5, INK, 2)
    + line(4, 12, 8, 12, INK, 2)
    + line(4, 19, 8, 19, INK, 2)
    + path("M9,5 C13,5 13,12 16,12 M9,19 C13,19 13,12 16,12 M9,12 L16,12", INK, 1)
    + line(16, 12, 21, 12, ACCENT, 2.4),
    "lists.Graft": line(3, 12, 8, 12, ACCENT, 2.4)
    + path("M8,12 C12,12 12,5 15,5 M8,12 C12,12 12,19 15,19 M8,12 L15,12", INK, 1)
    + line(16, 5, 20, 5, INK, 2)
    + line(16, 12, 20, 12, INK, 2)
    + line(16, 19, 20, 19, INK, 2),
    "lists.Merge": line(3, 6, 9, 6, INK, 2)
    + line(3, 18, 9, 18, INK, 2)
    + path("M9,6 C13,6 13,12 16,12 M9,18 C13,18 13,12 16,12", INK, 1.2)
    + line(16, 10, 21, 10, ACCENT, 2)
    + line(16, 14, 21, 14, ACCENT, 2),
    "lists.Partition": "".join(line(4, y, 14, y, INK, 2) for y in (4, 7.5))
    + "".join(line(4, y, 14, y, ACCENT, 2) for y in (12.5, 16))
    + line(4, 20, 14, 20, INK, 2)
    + path("M17,3.5 L19,3.5 L19,8 L17,8 M17,12 L19,12 L19,16.5 L17,16.5", INK, 1),
    "lists.Reverse": line(4, 6, 16, 6, INK, 2)
    + line(4, 11, 13, 11, INK, 2)
    + line(4, 16, 10, 16, INK, 2)
    + path("M19,17 L19,6", ACCENT, 1.4)
    + poly([(17, 8), (19, 5.5), (21, 8)], ACCENT, 1.4)
    + poly([(17, 15), (19, 17.5), (21, 15)], ACCENT, 1.4),
    "lists.Shift": "".join(line(4, y, 14, y, INK, 2) for y in (6, 10, 14))
    + line(4, 18, 14, 18, ACCENT, 2)
    + path("M18,18 C22,18 22,6 18,6", ACCENT, 1.3)
    + poly([(19.5, 4.5), (17.5, 6), (19.5, 7.5)], ACCENT, 1.3),
    "lists.Sort": line(4, 5, 8, 5, INK, 2)
    + line(4, 10, 11, 10, INK, 2)
    + line(4, 15, 14, 15, INK, 2)
    + line(4, 20, 17, 20, INK, 2)
    + arrow(20, 4, 20, 20, ACCENT, 1.3),
    # -- curves: one thick curve, and what the node does to it ---------------------------
    "curves.Line": line(4, 19, 20, 5, INK, 2) + spot(4, 19, 1.8) + spot(20, 5, 1.8),
    "curves.Polyline": poly([(3, 18), (8, 7), (13, 15), (20, 5)], INK, 1.8)
    + spot(3, 18, 1.5)
    + spot(8, 7, 1.5)
    + spot(13, 15, 1.5)
    + spot(20, 5, 1.5),
    "curves.Circle": circle(12, 12, 7.5, INK, 2) + spot(12, 12, 1.4),
    "curves.Arc": path("M4.5,16 A8,8 0 0 1 19.5,16", INK, 2)
    + spot(12, 16, 1.3)
    + line(12, 16, 4.5, 16, INK, 0.8, "1.5,1.2"),
    "curves.Interpolate": path(CURVE, INK, 1.8)
    + spot(4, 17, 1.8, ACCENT)
    + spot(9.3, 11.2, 1.8, ACCENT)
    + spot(14.8, 13.2, 1.8, ACCENT)
    + spot(20, 8, 1.8, ACCENT),
    "curves.NurbsCurve": poly([(4, 17), (8, 5), (14, 21), (20, 8)], INK, 0.9)
    + path(CURVE, ACCENT, 1.8)
    + spot(8, 5, 1.5)
    + spot(14, 21, 1.5),
    "curves.ParametricCurve": path("M3,14 C6,6 9,6 12,14 C15,22 18,22 21,14", INK, 1.8)
    + text(19.5, 8, "t", 8, ACCENT),
    "curves.DivideCurve": path(CURVE, INK, 1.6)
    + "".join(spot(x, y, 1.8, ACCENT) for x, y in ((4, 17), (7.5, 12), (11.5, 12.8), (16, 13.4), (20, 8))),
    "curves.EvaluateCurve": path(CURVE, INK, 1.6)
    + arrow(11.5, 12.8, 18, 16.5, ACCENT, 1.4)
    + spot(11.5, 12.8, 2.2, ACCENT),
    "curves.CurveLength": path(CURVE, INK, 1.6)
    + line(4, 21, 20, 21, ACCENT, 1.1)
    + line(4, 19.5, 4, 22.5, ACCENT, 1.1)
    + line(20, 19.5, 20, 22.5, ACCENT, 1.1)
    + text(18.5, 6, "L", 7, ACCENT),
    "curves.EndPoints": path(CURVE, INK, 1.6) + spot(4, 17, 2.6, ACCENT) + spot(20, 8, 2.6, ACCENT),
    "curves.Flip": path(CURVE, INK, 1.6) + poly([(7.5, 18), (4, 17), (5, 13.5)], ACCENT, 1.6),
    "curves.Offset": path("M3,15 C8,5 14,19 21,7", INK, 1.6) + path("M3,20 C8,10 14,24 21,12", ACCENT, 1.6),
    "curves.CurveFrame": path(CURVE, INK, 1.5)
    + arrow(11.5, 12.8, 18.5, 15.5, ACCENT, 1.4)
    + arrow(11.5, 12.8, 9, 5.5, ACCENT, 1.4),
    "curves.PerpFrames": path(CURVE, INK, 1.5)
    + line(2.5, 11.5, 9, 14.5, ACCENT, 2)
    + line(11, 8, 12, 17.5, ACCENT, 2)
    + line(14.5, 10, 21, 15, ACCENT, 2),
    # -- surfaces: a curved patch, and what is read from it or made -----------------------
    "surfaces.Loft": path("M3,6 C8,3 14,8 21,5", INK, 1.4)
    + path("M3,12 C8,9 14,14 21,11", INK, 1.4)
    + path("M3,18 C8,15 14,20 21,17", INK, 1.4)
    + path("M3,6 L3,18 M21,5 L21,17", ACCENT, 1.2)
    + path("M3,6 C8,3 14,8 21,5 L21,17 C14,20 8,15 3,18 Z", "none", 0, SOFT),
    "surfaces.RuledSurface": path("M3,6 C9,2 15,9 21,5", INK, 1.6)
    + path("M3,19 C9,15 15,22 21,18", INK, 1.6)
    + "".join(
        line(x, y1, x, y2, ACCENT, 0.9)
        for x, y1, y2 in ((3, 6, 19), (8, 4.3, 17.3), (13, 5.6, 18.6), (18, 6.2, 19.2))
    ),
    "surfaces.NurbsSurface": path(PATCH, INK, 1.2, SOFT)
    + "".join(spot(x, y, 1.3, ACCENT) for x in (5, 12, 19) for y in (8, 13, 18)),
    "surfaces.ParametricSurface": path(PATCH, INK, 1.4, SOFT) + text(12, 15.5, "uv", 7.5, ACCENT),
    # a mesh's triangle with the smooth patch fitted over it
    "surfaces.SurfaceFromMesh": poly([(4, 20), (9, 11), (14, 20)], INK, 1.0, SOFT, True)
    + line(6.5, 15.5, 11.5, 15.5, INK, 0.8)
    + path("M3,9 C8,3 15,12 21,6", ACCENT, 1.6)
    + path("M10,20 C14,15 17,18 21,14", INK, 1.4),
    # -- mesh booleans: two overlapping boxes, A up left and B down right; the result in accent
    "surfaces.MeshUnion": poly([(3, 4), (14, 4), (14, 9), (21, 9), (21, 20), (9, 20), (9, 15), (3, 15)],
                               ACCENT, 1.8, SOFT, True)
    + line(9, 9, 14, 9, INK, 0.8, "1.2,1.2")
    + line(9, 9, 9, 15, INK, 0.8, "1.2,1.2"),
    "surfaces.MeshDifference": rect(9, 9, 12, 11, INK, 1, "none")
    + poly([(3, 4), (14, 4), (14, 9), (9, 9), (9, 15), (3, 15)], ACCENT, 1.8, SOFT, True),
    "surfaces.MeshIntersection": rect(3, 4, 11, 11, INK, 1, "none")
    + rect(9, 9, 12, 11, INK, 1, "none")
    + rect(9, 9, 5, 6, ACCENT, 1.8, ACCENT),
    "surfaces.MeshSurface": poly([(4, 19), (12, 4), (20, 19)], INK, 1.4, SOFT, True)
    + line(8, 11.5, 16, 11.5, INK, 1)
    + line(8, 11.5, 12, 19, INK, 1)
    + line(16, 11.5, 12, 19, INK, 1)
    + spot(12, 4, 1.3)
    + spot(4, 19, 1.3)
    + spot(20, 19, 1.3),
    "surfaces.Sphere": circle(12, 12, 8.5, INK, 1.6, SOFT)
    + path("M3.5,12 A8.5,3 0 0 0 20.5,12", INK, 1)
    + path("M3.5,12 A8.5,3 0 0 1 20.5,12", INK, 0.8, "none", "1.5,1.2"),
    "surfaces.Cylinder": path("M5,6 L5,18 A7,2.6 0 0 0 19,18 L19,6", INK, 1.5, SOFT)
    + path("M5,6 A7,2.6 0 0 1 19,6 A7,2.6 0 0 1 5,6", INK, 1.5),
    "surfaces.Cone": path("M12,3 L4,18 A8,2.8 0 0 0 20,18 Z", INK, 1.5, SOFT)
    + path("M4,18 A8,2.8 0 0 1 20,18", INK, 0.8, "none", "1.5,1.2"),
    "surfaces.Torus": path("M2.5,12 A9.5,6 0 1 0 21.5,12 A9.5,6 0 1 0 2.5,12 Z", INK, 1.5, SOFT)
    + path("M8,12 C10,14 14,14 16,12 M9,12.8 C10.5,10.8 13.5,10.8 15,12.8", INK, 1.2),
    "surfaces.EvaluateSurface": path(PATCH, INK, 1.3, SOFT)
    + arrow(12, 13.5, 12, 2.5, ACCENT, 1.5)
    + spot(12, 13.5, 2, ACCENT),
    "surfaces.Isocurve": path(PATCH, INK, 1.3, SOFT)
    + path("M12,8.2 C12.5,12 11.5,15 12,18.8", ACCENT, 2)
    + path("M4,14 C9,11.5 15,15 20,12.5", ACCENT, 1, "none", "1.5,1.2"),
    "surfaces.SurfaceCurvature": path(PATCH, INK, 1.2, SOFT)
    + path("M6,15 C9,10 15,10 18,15", ACCENT, 1.6)
    + path("M10,8 C7,11 7,15 10,19", ACCENT, 1.6),
    "surfaces.SurfaceEdges": path(PATCH, ACCENT, 2.2)
    + spot(4, 9, 1.6)
    + spot(20, 7, 1.6)
    + spot(20, 18, 1.6)
    + spot(4, 19, 1.6),
    "surfaces.Area": path(PATCH, INK, 1.3, "#ffffffaa") + text(12, 16.2, "A", 8, "#335f5a"),
    "surfaces.BoundingBox": path(
        "M4,8 L14,8 L14,20 L4,20 Z M4,8 L9,4 L19,4 L14,8 M19,4 L19,16 L14,20", INK, 1.2
    )
    + circle(9.5, 14, 3.8, ACCENT, 1.5),
    "surfaces.Volume": path("M4,8 L14,8 L14,20 L4,20 Z", INK, 1.3, "#ffffff88")
    + path("M4,8 L9,4 L19,4 L14,8 M19,4 L19,16 L14,20", INK, 1.3, "#ffffff44")
    + spot(9, 14, 2.2, ACCENT),
    # -- transform: a shape and the motion ------------------------------------------------
    "transform.Move": rect(3, 13, 7, 7, INK, 1.2, "none")
    + rect(14, 4, 7, 7, INK, 1.4, SOFT)
    + arrow(9, 13, 15, 9, ACCENT, 1.5),
    "transform.Rotate": rect(9, 9, 6, 6, INK, 1.4, SOFT)
    + path("M4.5,12 A7.5,7.5 0 1 1 12,19.5", ACCENT, 1.5)
    + poly([(14, 17.5), (12, 19.5), (14, 21.5)], ACCENT, 1.5),
    "transform.Scale": rect(3, 11, 7, 7, INK, 1.2)
    + rect(3, 3, 18, 18, INK, 1.4, "none")
    + arrow(8, 13, 18, 6, ACCENT, 1.4),
    "transform.ScaleNonUniform": rect(3, 8, 7, 8, INK, 1.2)
    + rect(3, 8, 18, 8, INK, 1.4)
    + arrow(10, 19.5, 20, 19.5, ACCENT, 1.4),
    "transform.Mirror": poly([(3, 18), (9, 6), (9, 18)], INK, 1.4, SOFT, True)
    + poly([(21, 18), (15, 6), (15, 18)], ACCENT, 1.4, "none", True)
    + line(12, 3, 12, 21, INK, 1, "2,1.5"),
    "transform.Orient": poly([(2, 20), (9, 20), (12, 16), (5, 16)], INK, 1.2, SOFT, True)
    + poly([(14, 4), (20, 7), (20, 14), (14, 11)], ACCENT, 1.2, "none", True)
    + path("M8,14 C9,8 11,7 14,8", INK, 1.2),
    "transform.Array": rect(2.5, 9, 5.5, 6, INK, 1.3, SOFT)
    + rect(9.3, 9, 5.5, 6, INK, 1.3)
    + rect(16, 9, 5.5, 6, ACCENT, 1.3)
    + arrow(3, 19.5, 20, 19.5, INK, 1),
    "transform.PolarArray": spot(12, 12, 1.3)
    + "".join(
        rect(x - 2, y - 2, 4, 4, ACCENT if i == 0 else INK, 1.2)
        for i, (x, y) in enumerate(((12, 4.5), (19, 9.5), (16.5, 18), (7.5, 18), (5, 9.5)))
    ),
    # -- analysis: geometry with a reading laid over it -----------------------------------
    "analysis.IsoMapping": path("M3,7 C5,4 8,4 10,7 L10,19 C8,16 5,16 3,19 Z", INK, 1.2, SOFT)
    + line(6.5, 5.3, 6.5, 17.3, INK, 0.8)
    + arrow(11.5, 12, 15, 12, ACCENT, 1.3)
    + rect(16, 5, 5, 14, INK, 1.2, SOFT)
    + line(18.5, 5, 18.5, 19, INK, 0.8),
    "analysis.SurfaceAnalysis": path("M4,9 C9,6 15,10 20,7 L20,11 C15,14 9,10 4,13 Z", "none", 0, "#ff6b6b")
    + path("M4,13 C9,10 15,14 20,11 L20,15 C15,18 9,14 4,17 Z", "none", 0, ACCENT)
    + path("M4,17 C9,14 15,18 20,15 L20,18 C15,21 9,17 4,19 Z", "none", 0, "#7bd389")
    + path(PATCH, INK, 1.2),
    "analysis.VectorAnalysis": arrow(5, 19, 20, 16, INK, 1.6)
    + arrow(5, 19, 10, 4, INK, 1.6)
    + path("M12,17.6 A7,7 0 0 0 7.5,12.3", ACCENT, 1.5),
    "analysis.CurveOfRegression": path("M4,20 C8,12 14,8 20,7", ACCENT, 1.8)
    + line(2, 14, 14, 22, INK, 0.9)
    + line(5, 9, 19, 15, INK, 0.9)
    + line(9, 4, 22, 11, INK, 0.9),
    "analysis.BendingCheck": path("M3,18 A12,12 0 0 1 18,6", INK, 3.2)
    + path("M3,18 A12,12 0 0 1 18,6", "#c0622f", 1)
    + line(15, 18, 5.5, 9, INK, 0.8, "1.5,1.2")
    + path("M14,17 L17,20.5 L22,13", ACCENT, 1.8),
    "analysis.WarpChart": line(3, 20, 21, 20, INK, 1)
    + line(3, 4, 3, 20, INK, 1)
    + line(3, 9, 21, 9, ACCENT, 1, "2,1.5")
    + poly([(4, 17), (7, 14), (10, 16), (13, 10), (16, 13), (20, 7)], INK, 1.5),
    "analysis.CurvatureHistogram": line(3, 20, 21, 20, INK, 1)
    + rect(4.5, 14, 3, 6, INK, 0, INK)
    + rect(8.5, 8, 3, 12, INK, 0, INK)
    + rect(12.5, 5, 3, 15, INK, 0, ACCENT)
    + rect(16.5, 11, 3, 9, INK, 0, INK),
    # -- developable: bands crossed by straight rulings ------------------------------------
    "developable.RulingDevelopable": strip_rulings(
        [(3, 7), (8, 4), (13, 5), (18, 3), (21, 5)], [(3, 19), (7, 18), (12, 20), (17, 17), (21, 19)]
    ),
    "developable.CylindricalSurface": strip_rulings(
        [(3, 7), (7, 4), (11, 6), (15, 5), (20, 7)], [(3, 20), (7, 17), (11, 19), (15, 18), (20, 20)]
    )
    + arrow(22, 18, 22, 8, ACCENT, 1.1, 2.2),
    "developable.ConicalSurface": strip_rulings(
        [(12, 3), (12, 3), (12, 3), (12, 3), (12, 3)], [(3, 19), (7, 21), (12, 21.5), (17, 21), (21, 19)]
    )
    + spot(12, 3, 2, ACCENT),
    "developable.TangentDevelopable": path("M3,19 C8,17 13,12 20,4", ACCENT, 2)
    + line(5.5, 18, 13, 13.5, INK, 1)
    + line(9, 16, 17, 9.5, INK, 1)
    + line(13, 12.5, 21, 5.5, INK, 1)
    + line(3, 19, 10.5, 15.5, INK, 1),
    "developable.PaperStrip": path("M3,6 C9,3 13,10 21,6 L21,12 C13,17 9,9 3,13 Z", INK, 1.4, SOFT)
    + "".join(
        line(x, y1, x, y2, INK, 0.8) for x, y1, y2 in ((7, 4.8, 11.8), (12, 6.6, 12.6), (17, 7.6, 14.4))
    )
    + path("M3,16 L21,16 L21,21 L3,21 Z", ACCENT, 1.1)
    + "".join(line(x, 16, x, 21, ACCENT, 0.7) for x in (7, 12, 17)),
    "developable.ParametricRuledSurface": strip_rulings(
        [(3, 6), (8, 4), (13, 6), (18, 4), (21, 6)], [(3, 15), (8, 17), (13, 15), (18, 17), (21, 15)]
    )
    + text(12, 22.5, "S(u,v)", 5.2, ACCENT),
    "developable.Rationalise": path(
        "M3,5 C9,2 15,7 21,4 L21,20 C15,22 9,18 3,21 Z", ACCENT, 1, "none", "1.5,1.2"
    )
    + strip_rulings([(3, 6), (12, 5), (21, 5)], [(3, 11), (12, 10.5), (21, 10)])
    + strip_rulings([(3, 13), (12, 13), (21, 12)], [(3, 19), (12, 18.5), (21, 18)]),
    "developable.SplineApproximation": path(PATCH, ACCENT, 1.1, "none", "1.5,1.2")
    + strip_rulings([(4, 9), (9, 7.6), (15, 9.2), (20, 7)], [(4, 19), (9, 17.8), (15, 19), (20, 18)]),
    "developable.SurfaceCoupling": path("M2,4 L8,6 L8,18 L2,20 Z", INK, 1.2, SOFT)
    + path("M16,6 L22,4 L22,20 L16,18 Z", INK, 1.2, SOFT)
    + path("M8,6 C11,8 13,8 16,6 M8,18 C11,16 13,16 16,18", ACCENT, 1.3)
    + line(10, 7.2, 10, 16.8, ACCENT, 0.8)
    + line(14, 7.2, 14, 16.8, ACCENT, 0.8),
    # -- patching: panels over a development ----------------------------------------------
    "patching.StaggeredPattern": rect(2, 4, 20, 16, INK, 1.3)
    + line(2, 9.3, 22, 9.3, INK, 1)
    + line(2, 14.6, 22, 14.6, INK, 1)
    + line(8, 4, 8, 9.3, INK, 1)
    + line(15, 4, 15, 9.3, INK, 1)
    + line(4.5, 9.3, 4.5, 14.6, INK, 1)
    + line(11.5, 9.3, 11.5, 14.6, INK, 1)
    + line(18.5, 9.3, 18.5, 14.6, INK, 1)
    + line(8, 14.6, 8, 20, INK, 1)
    + line(15, 14.6, 15, 20, INK, 1)
    + rect(11.5, 9.3, 7, 5.3, INK, 0, ACCENT),
    "patching.SurfacePatching": path(PATCH, INK, 1.4, SOFT)
    + path("M4,14 C9,11 15,15 20,12.5", INK, 1)
    + line(9, 7.2, 9, 18.2, INK, 1)
    + line(15, 8.6, 15, 19.3, INK, 1)
    + path("M9,13 C11,12 13,13.4 15,13.8 L15,19.3 C13,19.6 11,18.6 9,18.2 Z", "none", 0, ACCENT),
    # -- display ------------------------------------------------------------------------------
    "display.Preview": path("M2,12 C6,5 18,5 22,12 C18,19 6,19 2,12 Z", INK, 1.5)
    + circle(12, 12, 3.5, INK, 1.3, ACCENT),
    "display.Plot": line(3, 20, 21, 20, INK, 1.2)
    + line(3, 3, 3, 20, INK, 1.2)
    + poly([(4, 17), (8, 11), (12, 14), (16, 6), (20, 9)], ACCENT, 1.6),
    "display.Tag": path("M3,8 L15,8 L20,12 L15,16 L3,16 Z", INK, 1.4, SOFT)
    + text(9, 14.5, "Aa", 6.5)
    + spot(20, 12, 1.3, ACCENT),
    # -- io: a page and which way it goes -------------------------------------------------------
    "io.Export3dm": page() + text(9.5, 12, "3dm", 5.5) + out_arrow(),
    "io.Import3dm": page() + text(9.5, 12, "3dm", 5.5) + in_arrow(),
    "io.ExportCSV": page()
    + "".join(line(5, y, 13, y, INK, 1) for y in (9, 12, 15, 18))
    + line(9, 8, 9, 19, INK, 1)
    + out_arrow(),
    "io.ExportMesh": page()
    + poly([(5, 13), (9.5, 6), (13, 13)], INK, 1.2, "none", True)
    + line(9.5, 6, 9.5, 13, INK, 0.8)
    + out_arrow(),
    "io.ImportMesh": page()
    + poly([(5, 13), (9.5, 6), (13, 13)], INK, 1.2, "none", True)
    + line(9.5, 6, 9.5, 13, INK, 0.8)
    + in_arrow(),
    "io.ExportCutSheet": rect(3, 4, 18, 14, INK, 1.3)
    + path("M5,6 C8,5 10,8 12,6 L12,11 C10,12 8,10 5,11 Z", ACCENT, 1)
    + path("M13,8 L19,6 L19,16 L13,14 Z", ACCENT, 1)
    + path("M5,13 L11,13 L10,16 L5,16 Z", ACCENT, 1)
    + arrow(13, 21.5, 22, 21.5, INK, 1.2, 2.2),
}


def svg(type_id: str) -> str:
    palette = type_id.partition(".")[0]
    tile = TILES.get(palette, "#6a6a6a")
    return (
        '<svg xmlns="http://www.w3.org/2000/svg" width="24" height="24" viewBox="0 0 24 24" '
        'stroke-linecap="round" stroke-linejoin="round">'
        f'<rect x="0.5" y="0.5" width="23" height="23" rx="4.5" fill="{tile}" '
        'stroke="#000000" stroke-opacity="0.25"/>'
        f"{GLYPHS[type_id]}</svg>\n"
    )


def main(argv: list[str]) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    for type_id in GLYPHS:
        (OUT / f"{type_id}.svg").write_text(svg(type_id), encoding="utf-8")
    print(f"wrote {len(GLYPHS)} icons to {OUT}")
    if "--sheet" in argv:
        sheet(Path(argv[argv.index("--sheet") + 1]))


def sheet(target: Path) -> None:
    """A contact sheet of every icon at 100 % and 200 %, a palette per row (needs Qt)."""
    from PySide6.QtCore import QRectF
    from PySide6.QtGui import QColor, QGuiApplication, QImage, QPainter
    from PySide6.QtSvg import QSvgRenderer

    app = QGuiApplication.instance() or QGuiApplication([])  # noqa: F841 - Qt needs it alive
    rows: dict[str, list[str]] = {}
    for type_id in GLYPHS:
        rows.setdefault(type_id.partition(".")[0], []).append(type_id)
    width = max(len(r) for r in rows.values()) * 80 + 20
    image = QImage(width, len(rows) * 60 + 20, QImage.Format.Format_ARGB32)
    image.fill(QColor("#f0f0f0"))
    painter = QPainter(image)
    for r, ids in enumerate(rows.values()):
        for c, type_id in enumerate(ids):
            renderer = QSvgRenderer(str(OUT / f"{type_id}.svg"))
            renderer.render(painter, QRectF(10 + c * 80, 10 + r * 60 + 12, 24, 24))
            renderer.render(painter, QRectF(10 + c * 80 + 28, 10 + r * 60, 48, 48))
    painter.end()
    image.save(str(target))


if __name__ == "__main__":
    main(sys.argv[1:])

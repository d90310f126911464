"""Cut sheets a person can check: the SVG rendered by rsvg-convert shows every cut line, and
``--preview`` writes a PNG of each sheet (docs/cut-sheets.md)."""

from __future__ import annotations

import shutil
import subprocess

import ezdxf
import numpy as np
import pytest
import shapely
from PIL import Image

from tests.support.io_helpers import random_panels
from torsal.nodes.io.formats import cutfiles, sheetviews

PIXELS = 1600
#: rsvg-convert comes with librsvg2-bin (the Makefile's SYSTEM_PACKAGES)
NEEDS_RSVG = pytest.mark.skipif(shutil.which("rsvg-convert") is None, reason="rsvg-convert is not installed")


def _outlines(dxf_files):
    """Each sheet's cut contours as ezdxf reads them from the DXF (mm)."""
    return [[np.array([(x, y) for x, y, *_ in e.get_points()])
             for e in ezdxf.readfile(f).modelspace().query('LWPOLYLINE[layer=="CUT"]')] for f in dxf_files]


def _inked_share(image: np.ndarray, outline: np.ndarray, width: float, height: float) -> float:
    """Share of points every 2 px along the outline with a dark pixel (not near white) within a
    pixel of it, the sheet ``width`` × ``height`` mm drawn ``image``'s size, y down."""
    ring = shapely.LinearRing(outline)
    scale = image.shape[1] / width
    samples = np.array([ring.interpolate(d).coords[0] for d in np.arange(0.0, ring.length, 2.0 / scale)])
    cols = np.clip(np.round(samples[:, 0] * scale).astype(int), 1, image.shape[1] - 2)
    rows = np.clip(np.round((height - samples[:, 1]) * scale).astype(int), 1, image.shape[0] - 2)
    dark = image[..., :3].astype(int).sum(axis=2) < 600
    near = np.zeros(len(samples), dtype=bool)
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            near |= dark[rows + dr, cols + dc]
    return float(near.mean())


def _layout():
    return cutfiles.lay_out(random_panels(24, seed=4), width=2500.0, height=1250.0, text_height=10.0)


def _rendered(svg, tmp_path) -> np.ndarray:
    png = tmp_path / (svg.stem + "-render.png")
    subprocess.run(["rsvg-convert", "-w", str(PIXELS), "-b", "white", str(svg), "-o", str(png)], check=True,
                   timeout=60)
    return np.asarray(Image.open(png).convert("RGB"))


@NEEDS_RSVG
def test_svg_rendered_at_1600_px_shows_every_parts_outline(tmp_path):
    layout = _layout()
    svgs = cutfiles.write_cut_files(layout, tmp_path / "sheet.svg")
    sheets = _outlines(cutfiles.write_cut_files(layout, tmp_path / "sheet.dxf"))
    assert sum(len(s) for s in sheets) == 24
    for svg, outlines in zip(svgs, sheets, strict=True):
        image = _rendered(svg, tmp_path)
        assert image.shape[1] == PIXELS
        for outline in outlines:
            assert _inked_share(image, outline, 2500.0, 1250.0) >= 0.97


@NEEDS_RSVG
def test_a_hairline_in_sheet_units_is_what_renders_invisible(tmp_path):
    """The check above can fail: the old 0.01 mm strokes leave the parts' edges blank."""
    layout = _layout()
    svg = tmp_path / "old.svg"
    svg.write_text(sheetviews.svg_text(layout, 0, hairline_mm=0.01), encoding="utf-8")
    image = _rendered(svg, tmp_path)
    (outlines, *_) = _outlines(cutfiles.write_cut_files(layout, tmp_path / "sheet.dxf"))
    assert max(_inked_share(image, outline, 2500.0, 1250.0) for outline in outlines) < 0.2


def test_preview_writes_one_png_per_sheet_beside_the_dxf_with_every_outline_drawn(tmp_path):
    """What ``torsal run --export cut.Layout=roof.dxf --preview`` writes."""
    from torsal.app.exports import export_tree
    from torsal.engine.datatree import DataTree

    layout = cutfiles.lay_out(random_panels(60, seed=11), text_height=10.0)
    assert layout.sheets >= 2
    files = export_tree(DataTree({(0,): [layout]}), tmp_path / "roof.dxf", preview=True)
    dxfs = [f for f in files if f.suffix == ".dxf"]
    pngs = [f for f in files if f.suffix == ".png"]
    assert [p.with_suffix(".dxf") for p in pngs] == dxfs and len(dxfs) == layout.sheets
    for png, outlines in zip(pngs, _outlines(dxfs), strict=True):
        image = np.asarray(Image.open(png).convert("RGB"))
        assert image.shape[1] == sheetviews.PREVIEW_PX
        for outline in outlines:
            assert _inked_share(image, outline, 2500.0, 1250.0) >= 0.97

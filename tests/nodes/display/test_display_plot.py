"""display.Plot: a PNG line graph and a summary in words."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.support.node_helpers import allowed, out, run, texts
from torsal.nodes.display.plot import Plot

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
WARP_ANGLES = [0.0, 1.5, 3.0, 2.0, 4.5, 1.0]


def image(result) -> Path:
    (path,) = out(result, "Image")[(0,)]
    return Path(path)


def test_plot_writes_a_png_to_the_file(tmp_path):
    target = tmp_path / "warp.png"
    result = run(Plot(), Values=WARP_ANGLES, Title="Warp angle per panel", File="warp.png",
                 writes=allowed(tmp_path))
    assert result.state == "ok"
    assert image(result) == target
    data = target.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert len(data) > 0


def test_plot_summarises_min_max_and_mean(tmp_path):
    result = run(Plot(), Values=WARP_ANGLES, File="a.png", writes=allowed(tmp_path))
    assert out(result, "Summary") == {(0,): ["min 0, max 4.5, mean 2 over 6 values"]}


def test_plot_without_a_file_writes_a_temporary_png_and_says_where():
    result = run(Plot(), Values=[1.0, 2.0, 4.0])
    path = image(result)
    assert result.state == "ok"
    assert texts(result) == [f"No File given: the plot was written to {path}"]
    assert path.read_bytes()[:8] == PNG_SIGNATURE


def test_plot_file_without_suffix_becomes_png_and_folders_are_made(tmp_path):
    result = run(Plot(), Values=[1.0, 2.0], File="graphs/angles", writes=allowed(tmp_path))
    assert image(result) == tmp_path / "graphs" / "angles.png"
    assert image(result).read_bytes()[:8] == PNG_SIGNATURE


def test_plot_leaves_non_finite_values_out_of_the_summary(tmp_path):
    result = run(Plot(), Values=[1.0, float("nan"), 3.0], File="b.png", writes=allowed(tmp_path))
    assert out(result, "Summary") == {(0,): ["min 1, max 3, mean 2 over 2 values (1 not finite, left out)"]}


def test_plot_of_no_values_warns():
    result = run(Plot(), Values=[])
    assert result.state == "warning"
    assert texts(result) == ["Input Values collected no data"]


def test_plot_only_writes_png(tmp_path):
    result = run(Plot(), Values=[1.0], File="plot.jpg", writes=allowed(tmp_path))
    assert texts(result) == ["File must be a .png image, not 'plot.jpg'"]


@pytest.mark.parametrize("values", [[float("nan")], [float("inf"), float("-inf")]])
def test_plot_of_only_non_finite_values_warns(values, tmp_path):
    result = run(Plot(), Values=values, File="c.png", writes=allowed(tmp_path))
    assert texts(result) == ["None of the Values is a finite number: there is nothing to plot"]


def test_plot_to_an_unwritable_place_warns(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    result = run(Plot(), Values=[1.0], File="file/plot.png", writes=allowed(tmp_path))
    assert result.state == "warning"
    assert texts(result)[0].startswith(f"Could not write the plot to {blocker / 'plot.png'}")

"""Saving a ``.graph`` file: atomically, with a backup, never half-written, keeping its
permissions, and never into a named pipe.
"""

from __future__ import annotations

import json
import os

import pytest

from tests.support.graphfile_files import (
    no_temporaries,
    read,
)
from torsal.engine import graphfile
from torsal.engine.graphfile import GraphFileError

# --------------------------------------------------------------------------- saving


def test_write_graph_creates_a_new_file_without_a_backup(registry, tmp_path):
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    path = tmp_path / "new.graph"
    graphfile.write_graph(graph, path)
    assert path.read_text(encoding="utf-8") == read("engine-basic.graph")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.graph"]


def test_write_graph_keeps_the_previous_content_as_bak(registry, tmp_path):
    path = tmp_path / "design.graph"
    first = graphfile.loads(read("engine-basic.graph"), registry)
    graphfile.write_graph(first, path)
    first.set_setting("height", "value", 6.0)
    graphfile.write_graph(first, path)
    backup = tmp_path / "design.graph.bak"
    assert backup.read_text(encoding="utf-8") == read("engine-basic.graph")
    assert json.loads(path.read_text(encoding="utf-8"))["nodes"][0]["settings"]["value"] == 6.0
    # a third save moves the second version into the backup
    second = path.read_bytes()
    first.set_setting("height", "value", 7.0)
    graphfile.write_graph(first, path)
    assert backup.read_bytes() == second
    assert no_temporaries(tmp_path) == []


@pytest.mark.parametrize("failing", ["rename", "fsync"])
def test_a_failure_mid_save_leaves_the_original_untouched_and_no_temporary_files(
    registry, tmp_path, monkeypatch, failing
):
    path = tmp_path / "design.graph"
    original = read("engine-spec-example.graph").encode("utf-8")
    path.write_bytes(original)
    graph = graphfile.loads(read("engine-basic.graph"), registry)

    def boom(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, failing, boom)
    with pytest.raises(OSError, match="No space left"):
        graphfile.write_graph(graph, path)
    monkeypatch.undo()
    assert path.read_bytes() == original
    assert no_temporaries(tmp_path) == []
    assert set(p.name for p in tmp_path.iterdir()) <= {"design.graph", "design.graph.bak"}
    # and the next save works
    graphfile.write_graph(graph, path)
    assert path.read_text(encoding="utf-8") == read("engine-basic.graph")


def test_an_interrupted_save_leaves_no_temporary_files(registry, tmp_path, monkeypatch):
    path = tmp_path / "design.graph"
    graph = graphfile.loads(read("engine-basic.graph"), registry)

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "rename", interrupted)
    with pytest.raises(KeyboardInterrupt):
        graphfile.write_graph(graph, path)
    assert not path.exists()
    assert no_temporaries(tmp_path) == []


def test_an_unsaveable_graph_does_not_touch_the_file(registry, tmp_path):
    path = tmp_path / "design.graph"
    original = read("engine-basic.graph").encode("utf-8")
    path.write_bytes(original)
    graph = graphfile.loads(original, registry)
    graph.set_setting("height", "value", float("nan"))  # JSON cannot hold NaN
    with pytest.raises(GraphFileError):
        graphfile.write_graph(graph, path)
    assert path.read_bytes() == original
    assert sorted(p.name for p in tmp_path.iterdir()) == ["design.graph"]


def test_saving_keeps_the_files_permissions(registry, tmp_path):
    path = tmp_path / "shared.graph"
    path.write_text(read("engine-spec-example.graph"), encoding="utf-8")
    os.chmod(path, 0o644)
    graphfile.write_graph(graphfile.loads(path.read_bytes(), registry), path)
    assert os.stat(path).st_mode & 0o777 == 0o644


def test_read_graph_errors_are_graph_file_errors(registry, tmp_path):
    with pytest.raises(GraphFileError, match="cannot read"):
        graphfile.read_graph(tmp_path / "absent.graph", registry)
    with pytest.raises(GraphFileError):
        graphfile.read_graph(tmp_path, registry)  # a directory
    big = tmp_path / "big.graph"
    with open(big, "wb") as stream:
        stream.truncate(graphfile.MAX_FILE_BYTES + 1)  # sparse: cheap to make
    with pytest.raises(GraphFileError, match="64 MB"):
        graphfile.read_graph(big, registry)


@pytest.mark.timeout(20)
@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_write_graph_does_not_replace_a_named_pipe(registry, tmp_path):
    fifo = tmp_path / "pipe.graph"
    os.mkfifo(fifo)
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    with pytest.raises(OSError, match="named pipe"):
        graphfile.write_graph(graph, fifo)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pipe.graph"]

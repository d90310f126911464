"""The torsal command as a CI user runs it: outputs, exit codes, messages on stderr."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from torsal.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "torsal" / "resources" / "examples" / "first-steps.graph"
TORSAL = [sys.executable, "-m", "torsal.app.cli"]


def run_json(capsys, *args: str) -> tuple[int, dict]:
    code = main(["run", *args, "--json"])
    return code, json.loads(capsys.readouterr().out)


def test_run_json_reports_every_node_with_state_and_outputs(capsys):
    code, data = run_json(capsys, str(EXAMPLE))
    assert code == 0
    assert data["ok"] is True
    assert data["file"].endswith("first-steps.graph")
    total = data["nodes"]["total"]
    assert total["type"] == "maths.Expression"
    assert total["state"] == "ok"
    assert total["outputs"]["Result"] == {"{0}": [pytest.approx(1.2 * 12)]}
    assert len(data["nodes"]["edges"]["outputs"]["Series"]["{0}"]) == 12


def test_set_overrides_a_slider_value(capsys):
    _, data = run_json(capsys, str(EXAMPLE), "--set", "width=2.5", "--set", "count=4")
    assert data["nodes"]["total"]["outputs"]["Result"]["{0}"] == [10.0]


def test_set_overrides_an_input_value(capsys):
    _, data = run_json(capsys, str(EXAMPLE), "--set", "edges.Start=100")
    assert data["nodes"]["edges"]["outputs"]["Series"]["{0}"][0] == 100.0


def test_out_writes_results_json(tmp_path, capsys):
    assert main(["run", str(EXAMPLE), "--out", str(tmp_path / "out")]) == 0
    written = json.loads((tmp_path / "out" / "results.json").read_text())
    assert written["nodes"]["count"]["outputs"]["Value"] == {"{0}": [12]}
    assert "solved 8 nodes" in capsys.readouterr().out


def test_export_writes_one_output_as_csv(tmp_path):
    target = tmp_path / "heights.csv"
    assert main(["run", str(EXAMPLE), "--export", f"heights.Result={target}"]) == 0
    rows = target.read_text().splitlines()
    assert rows[0] == "path,index,value"
    assert len(rows) == 1 + 12
    assert rows[1] == "{0},0,2.5"


def test_node_in_error_exits_1(tmp_path, capsys):
    graph = tmp_path / "broken.graph"
    data = json.loads(EXAMPLE.read_text())
    for node in data["nodes"]:
        if node["id"] == "total":
            node["settings"]["expression"] = "w * "  # a syntax error: the node goes red
    graph.write_text(json.dumps(data))
    code, result = run_json(capsys, str(graph))
    assert code == 1
    assert result["ok"] is False
    assert result["nodes"]["total"]["state"] == "error"
    assert result["nodes"]["heights"]["state"] == "ok"  # siblings still solve


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["run", "no-such-file.graph"], "cannot read"),
        (["run", str(EXAMPLE), "--set", "nobody=1"], "no node with id 'nobody'"),
        (["run", str(EXAMPLE), "--set", "edges.Nope=1"], "has no input 'Nope'"),
        (["run", str(EXAMPLE), "--set", "edges=1"], "has no value setting"),
        (["run", str(EXAMPLE), "--set", "novalue"], "wants ID=VALUE"),
        (["run", str(EXAMPLE), "--export", "edges.Series=x.dxf"], "cannot export"),
        (["run", str(EXAMPLE), "--export", "edges.Nope=x.csv"], "has no output 'Nope'"),
        (["check", "no-such-file.graph"], "cannot read"),
    ],
)
def test_bad_requests_exit_2_with_a_message_and_no_traceback(args, needle, capsys):
    assert main(args) == 2
    err = capsys.readouterr().err
    assert needle in err
    assert "Traceback" not in err


def test_corrupt_file_exits_2_with_the_reason(tmp_path, capsys):
    bad = tmp_path / "bad.graph"
    bad.write_text(EXAMPLE.read_text()[:300])
    assert main(["run", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "not valid JSON" in err and "Traceback" not in err


def test_newer_version_is_refused_and_left_untouched(tmp_path, capsys):
    newer = tmp_path / "newer.graph"
    text = EXAMPLE.read_text().replace('"version": 1', '"version": 7')
    newer.write_text(text)
    assert main(["run", str(newer)]) == 2
    assert "newer Torsal" in capsys.readouterr().err
    assert newer.read_text() == text


def test_check_validates_without_solving(capsys):
    assert main(["check", str(EXAMPLE)]) == 0
    assert "valid — 8 nodes, 8 wires, 2 groups" in capsys.readouterr().out


def test_nodes_json_lists_the_catalogue_with_ports(capsys):
    assert main(["nodes", "--json"]) == 0
    catalogue = {entry["type"]: entry for entry in json.loads(capsys.readouterr().out)}
    slider = catalogue["params.NumberSlider"]
    assert slider["outputs"][0]["name"] == "Value"
    assert [s["name"] for s in slider["settings"]] == ["value", "min", "max", "decimals"]
    assert "maths.Expression" in catalogue and "lists.ListItem" in catalogue


def test_gui_without_a_display_says_so_and_solves_headless(monkeypatch, capsys):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert main(["gui", str(EXAMPLE)]) == 0
    out = capsys.readouterr().out
    assert "No display found" in out
    assert "solved 8 nodes" in out


def test_gui_where_qt_cannot_load_says_how_to_install_it_and_leaves_the_collector_on(monkeypatch, capsys):
    """The check runs after the Qt-free imports (torsal/app/gui/before_qt.py), here stubbed;
    the collector, off for the start-up, is on again."""
    import gc

    import torsal.app.gui.availability as availability
    import torsal.app.gui.before_qt as before_qt

    monkeypatch.setenv("DISPLAY", ":99")
    monkeypatch.setattr(before_qt, "import_before_qt", lambda path, registry=None: None)
    monkeypatch.setattr(availability, "missing", lambda: "Qt for Python (PySide6) is not installed")
    assert gc.isenabled()
    assert main(["gui", str(EXAMPLE)]) == 2
    err = capsys.readouterr().err
    assert "the desktop app cannot start: Qt for Python (PySide6) is not installed." in err
    assert "Install it with:" in err and "torsal run" in err
    assert gc.isenabled()


def test_the_installed_command_runs_as_a_ci_user_would(tmp_path):
    torsal = shutil.which("torsal", path=str(Path(sys.executable).parent))
    command = [torsal] if torsal else TORSAL
    done = subprocess.run([*command, "run", str(EXAMPLE), "--json"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["nodes"]["count"]["state"] == "ok"
    done = subprocess.run([*command, "run", str(tmp_path / "missing.graph")], capture_output=True, text=True)
    assert done.returncode == 2
    assert done.stderr.startswith("torsal: ") and "Traceback" not in done.stderr


# ------------------------------------------------------------------- bounded reads, clear messages

HANG_GUARD = 30  # seconds; a FIFO opened for reading would block forever


def special_file(kind: str, tmp_path: Path) -> str:
    if kind == "/dev/zero":
        return "/dev/zero"
    if kind == "a FIFO":
        fifo = tmp_path / "pipe.graph"
        os.mkfifo(fifo)
        return str(fifo)
    return str(tmp_path)  # a folder


REASONS = {"/dev/zero": "is a device", "a FIFO": "is a named pipe (FIFO)", "a folder": "is a folder"}


@pytest.mark.skipif(not hasattr(os, "mkfifo") or not Path("/dev/zero").exists(), reason="needs POSIX")
@pytest.mark.parametrize("command", ["run", "check"])
@pytest.mark.parametrize("kind", list(REASONS))
def test_only_regular_files_are_read_the_rest_exit_2_at_once_with_the_reason(tmp_path, command, kind):
    target = special_file(kind, tmp_path)
    done = subprocess.run(
        [*TORSAL, command, target], capture_output=True, text=True, timeout=HANG_GUARD, cwd=ROOT
    )
    assert done.returncode == 2
    assert done.stderr == (
        f"torsal: {target}: it {REASONS[kind]}, not a graph file: only regular files are read\n"
    )


def test_set_on_a_wired_input_exits_2_naming_the_source(capsys):
    assert main(["run", str(EXAMPLE), "--set", "total.w=3"]) == 2
    err = capsys.readouterr().err
    assert "total.w is wired from width.Value: set the source" in err
    assert "Traceback" not in err


def test_out_pointed_at_a_file_is_a_sentence_not_an_errno(tmp_path, capsys):
    existing = tmp_path / "results.txt"
    existing.write_text("mine\n")
    assert main(["run", str(EXAMPLE), "--out", str(existing)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"torsal: --out {existing} is a file, not a folder")
    assert "Errno" not in err and "Traceback" not in err
    assert existing.read_text() == "mine\n"


def test_a_nan_given_with_set_is_reported_as_not_a_number(capsys):
    assert main(["run", str(EXAMPLE), "--set", "edges.Start=NaN"]) == 0
    out = capsys.readouterr().out
    assert "[edges] warning: Start is not a number (NaN)" in out
    assert "null" not in out

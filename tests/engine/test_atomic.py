"""``torsal.engine.atomic``: replacing a file atomically while keeping the old one as ``.bak``."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from torsal.engine import atomic
from torsal.engine.atomic import backup_path, remove_stale_temporaries, replace_keeping_backup


def writer(text: str):
    def write(temporary: Path) -> None:
        temporary.write_text(text, encoding="utf-8")

    return write


def temporaries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if ".tmp" in p.name)


def test_a_new_file_is_written_without_a_backup(tmp_path):
    target = tmp_path / "points.csv"
    assert replace_keeping_backup(target, writer("1,2\n")) == target
    assert target.read_text(encoding="utf-8") == "1,2\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["points.csv"]


def test_replacing_keeps_the_previous_content_as_bak(tmp_path):
    target = tmp_path / "points.csv"
    target.write_text("old\n", encoding="utf-8")
    replace_keeping_backup(target, writer("new\n"))
    assert target.read_text(encoding="utf-8") == "new\n"
    assert backup_path(target) == tmp_path / "points.csv.bak"
    assert backup_path(target).read_text(encoding="utf-8") == "old\n"
    assert temporaries(tmp_path) == []


def test_the_temporary_path_keeps_the_targets_suffix_and_folder(tmp_path):
    seen: list[Path] = []

    def write(temporary: Path) -> None:
        seen.append(temporary)
        temporary.write_bytes(b"solid\n")

    replace_keeping_backup(tmp_path / "mesh.stl", write)
    assert seen[0].suffix == ".stl"
    assert seen[0].parent == tmp_path
    assert seen[0].name.startswith(".mesh.stl.")


def test_the_backup_is_replaced_by_a_rename_not_rewritten_in_place(tmp_path):
    """An open handle on the old ``.bak`` still sees the old bytes: the backup file was
    swapped, never truncated and rewritten."""
    target = tmp_path / "a.txt"
    target.write_text("one", encoding="utf-8")
    replace_keeping_backup(target, writer("two"))
    with open(backup_path(target), encoding="utf-8") as old_backup:
        replace_keeping_backup(target, writer("three"))
        assert old_backup.read() == "one"
    assert backup_path(target).read_text(encoding="utf-8") == "two"


def test_a_failing_writer_leaves_file_and_backup_as_they_were(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("current", encoding="utf-8")
    backup_path(target).write_text("previous", encoding="utf-8")

    def broken(temporary: Path) -> None:
        temporary.write_text("half", encoding="utf-8")
        raise RuntimeError("exporter failed")

    with pytest.raises(RuntimeError, match="exporter failed"):
        replace_keeping_backup(target, broken)
    assert target.read_text(encoding="utf-8") == "current"
    assert backup_path(target).read_text(encoding="utf-8") == "previous"
    assert temporaries(tmp_path) == []


def test_without_hard_links_the_backup_is_a_copy(tmp_path, monkeypatch):
    def no_links(*args, **kwargs):
        raise OSError(1, "Operation not permitted")

    monkeypatch.setattr(os, "link", no_links)
    target = tmp_path / "a.txt"
    target.write_text("old", encoding="utf-8")
    replace_keeping_backup(target, writer("new"))
    assert backup_path(target).read_text(encoding="utf-8") == "old"
    assert temporaries(tmp_path) == []


def test_the_replaced_files_permissions_are_kept(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old", encoding="utf-8")
    os.chmod(target, 0o640)
    replace_keeping_backup(target, writer("new"))
    assert os.stat(target).st_mode & 0o777 == 0o640


def dead_pid() -> int:
    """The id of a process that has exited (and been reaped)."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_leftovers_of_a_killed_save_are_removed_by_the_next_save(tmp_path):
    target = tmp_path / "a.graph"
    pid = dead_pid()
    leftovers = [
        tmp_path / f".a.graph.{pid}-0badf00d.tmp.graph",
        tmp_path / f".a.graph.bak.{pid}-0badf00d.tmp.bak",
    ]
    for leftover in leftovers:
        leftover.write_text("half a sav", encoding="utf-8")
    replace_keeping_backup(target, writer("new"))
    assert temporaries(tmp_path) == []


def test_a_temporary_of_a_live_process_is_left_alone(tmp_path):
    """Another process may be saving the same file right now (here: this test's parent)."""
    target = tmp_path / "a.graph"
    busy = tmp_path / f".a.graph.{os.getppid()}-12345678.tmp.graph"
    busy.write_text("in progress", encoding="utf-8")
    assert remove_stale_temporaries(target) == []
    assert busy.exists()


def test_files_that_only_look_alike_are_not_touched(tmp_path):
    target = tmp_path / "a.graph"
    other = [tmp_path / ".a.graph.notes.tmp.graph", tmp_path / ".b.graph.1-aa.tmp.graph"]
    for path in other:
        path.write_text("mine", encoding="utf-8")
    replace_keeping_backup(target, writer("new"))
    assert all(path.exists() for path in other)


def test_a_day_old_temporary_is_removed_whatever_its_process_id(tmp_path):
    target = tmp_path / "a.graph"
    old = tmp_path / f".a.graph.{os.getppid()}-12345678.tmp.graph"
    old.write_text("ancient", encoding="utf-8")
    stamp = os.stat(old).st_mtime - atomic._STALE_SECONDS - 60
    os.utime(old, (stamp, stamp))
    assert remove_stale_temporaries(target) == [old]


def test_names_with_glob_characters_are_handled(tmp_path):
    target = tmp_path / "plan [v2]*.csv"
    target.write_text("old", encoding="utf-8")
    replace_keeping_backup(target, writer("new"))
    replace_keeping_backup(target, writer("newer"))
    assert target.read_text(encoding="utf-8") == "newer"
    assert backup_path(target).read_text(encoding="utf-8") == "new"
    assert temporaries(tmp_path) == []


def test_a_backup_that_already_is_the_file_leaves_no_temporary(tmp_path):
    """A save killed between its two renames leaves ``.bak`` a hard link to the file;
    renaming a link onto another link of the same file does nothing, so the staged link
    must not be left behind by the next save."""
    target = tmp_path / "a.txt"
    target.write_text("old", encoding="utf-8")
    os.link(target, backup_path(target))
    replace_keeping_backup(target, writer("new"))
    assert target.read_text(encoding="utf-8") == "new"
    assert backup_path(target).read_text(encoding="utf-8") == "old"
    assert temporaries(tmp_path) == []

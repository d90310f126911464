"""``torsal.engine.atomic``: replacing a file atomically while keeping the old one as ``.bak``."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from torsal.engine.atomic import backup_path, replace_keeping_backup


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


def test_the_writers_file_keeps_the_targets_suffix_in_a_private_folder(tmp_path):
    seen: list[Path] = []

    def write(temporary: Path) -> None:
        seen.append(temporary)
        temporary.write_bytes(b"solid\n")

    replace_keeping_backup(tmp_path / "mesh.stl", write)
    assert seen[0].suffix == ".stl"
    assert seen[0].parent != tmp_path  # a library writes by name only in a private folder
    assert os.stat(seen[0].parent.parent).st_mode & 0o777 == 0o700
    assert (tmp_path / "mesh.stl").read_bytes() == b"solid\n"


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


def test_files_that_only_look_alike_are_not_touched(tmp_path):
    target = tmp_path / "a.graph"
    other = [tmp_path / ".a.graph.notes.tmp.graph", tmp_path / ".b.graph.1-aa.tmp.graph"]
    for path in other:
        path.write_text("mine", encoding="utf-8")
    replace_keeping_backup(target, writer("new"))
    assert all(path.exists() for path in other)


def test_a_save_never_deletes_a_file_it_did_not_make_even_an_old_temporary(tmp_path):
    """Issue 24: an export to ``notes`` deleted an unrelated ``.notes.keep-me.tmp`` a day old."""
    target = tmp_path / "notes"
    keep = [tmp_path / ".notes.keep-me.tmp", tmp_path / ".notes.1-0badf00d.tmp"]
    for path in keep:
        path.write_text("mine", encoding="utf-8")
        os.utime(path, (1e9, 1e9))
    replace_keeping_backup(target, writer("new"))
    assert all(path.read_text(encoding="utf-8") == "mine" for path in keep)


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

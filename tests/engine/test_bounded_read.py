"""``torsal.engine.bounded_read``: only regular files are read, and never more than the limit."""

from __future__ import annotations

import os
import socket
import stat
from pathlib import Path

import pytest

from torsal.engine import bounded_read
from torsal.engine.bounded_read import UnreadableFileError, kind_of, read_bounded

pytestmark = pytest.mark.timeout(20)  # a FIFO opened by mistake would wait forever


def test_a_regular_file_within_the_limit_is_read_whole(tmp_path):
    path = tmp_path / "a.graph"
    path.write_bytes(b"x" * 100)
    assert read_bounded(path, 100) == b"x" * 100


def test_a_file_one_byte_over_the_limit_is_refused_naming_the_limit(tmp_path):
    path = tmp_path / "a.graph"
    path.write_bytes(b"x" * 2049)
    with pytest.raises(UnreadableFileError, match="larger than 2 kB; a graph file is at most 2 kB"):
        read_bounded(path, 2048, "a graph file")


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux /proc")
def test_the_limit_counts_the_bytes_read_not_the_reported_size():
    """/proc files report a size of 0 and still hold text."""
    assert os.stat("/proc/self/status").st_size == 0
    with pytest.raises(UnreadableFileError, match="larger than 10 bytes"):
        read_bounded("/proc/self/status", 10)


def test_a_folder_is_refused(tmp_path):
    with pytest.raises(UnreadableFileError, match="it is a folder, not a graph file"):
        read_bounded(tmp_path, 1000, "a graph file")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_named_pipe_is_refused_without_waiting_for_a_writer(tmp_path):
    fifo = tmp_path / "pipe.graph"
    os.mkfifo(fifo)
    with pytest.raises(UnreadableFileError, match=r"named pipe \(FIFO\)"):
        read_bounded(fifo, 1000)


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero")
def test_a_device_is_refused_before_any_byte_is_read():
    with pytest.raises(UnreadableFileError, match="it is a device"):
        read_bounded("/dev/zero", 1000)


@pytest.mark.skipif(not hasattr(socket, "AF_UNIX"), reason="no Unix sockets")
def test_a_socket_is_refused(tmp_path):
    path = tmp_path / "s"
    with socket.socket(socket.AF_UNIX) as server:
        try:
            server.bind(str(path))
        except OSError:
            pytest.skip("cannot bind a Unix socket here")
        with pytest.raises(UnreadableFileError, match="it is a socket"):
            read_bounded(path, 1000)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_named_pipe_swapped_in_after_the_check_is_refused_on_the_open_file(tmp_path, monkeypatch):
    """``stat`` said "regular file", then a FIFO took its place: the open does not block
    (O_NONBLOCK) and the open file's own ``fstat`` refuses it."""
    fifo = tmp_path / "pipe.graph"
    os.mkfifo(fifo)
    regular = tmp_path / "regular"
    regular.write_bytes(b"{}")
    real_stat = os.stat

    def stale_stat(path, *args, **kwargs):
        return real_stat(regular if Path(path) == fifo else path, *args, **kwargs)

    monkeypatch.setattr(bounded_read.os, "stat", stale_stat)
    with pytest.raises(UnreadableFileError, match="named pipe"):
        read_bounded(fifo, 1000)


def test_a_missing_file_says_it_cannot_be_read(tmp_path):
    with pytest.raises(UnreadableFileError, match=r"cannot read .*absent\.graph: No such file"):
        read_bounded(tmp_path / "absent.graph", 1000)


def test_kind_of_names_what_is_not_a_regular_file(tmp_path):
    path = tmp_path / "a"
    path.write_bytes(b"")
    assert kind_of(path) is None
    assert kind_of(tmp_path / "absent") is None
    assert kind_of(tmp_path) == "a folder"
    if Path("/dev/null").exists():
        assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
        assert kind_of("/dev/null") == "a device"

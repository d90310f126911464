"""A stand-in reader child that misbehaves on request, for the fenced-reader tests.

Run as ``python -P -m tests.support.hostile_reader MEMORY SECONDS`` by a FencedReader: it
answers each request's ``do`` with a crash (SIGSEGV), a hang, a huge allocation, a
malformed reply or a proper one.
"""

from __future__ import annotations

import os
import signal
import sys
import time

from torsal.nodes.io.formats.threedm_child import limit, receive, send


def main(argv: list[str]) -> int:
    limit(int(argv[0]), int(argv[1]))
    source, sink = sys.stdin.buffer, sys.stdout.buffer
    send(sink, {"ready": True})
    while (request := receive(source)) is not None:
        do = request.get("do")
        if do == "segfault":
            os.kill(os.getpid(), signal.SIGSEGV)
        elif do == "hang":
            time.sleep(3600)
        elif do == "allocate":
            blob = bytearray(4 << 30)  # 4 GiB: over the memory limit
            send(sink, {"ok": True, "size": len(blob)})
        elif do == "garbage":
            sink.write(b"\x05\x00\x00\x00\xc1\xc1\xc1\xc1\xc1")
            sink.flush()
        else:
            send(sink, {"ok": True, "pid": os.getpid()})
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

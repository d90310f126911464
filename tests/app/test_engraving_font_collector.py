"""The engraving font's first load (ezdxf's import and the font's parse, once a process)
sets off no full garbage collection: one would hold the interpreter lock for 70-350 ms,
so Esc could not be seen meanwhile (issue 16). Each case runs in a fresh process, since
the load happens once a process."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

LOAD = """
import gc, json, sys, threading
full = []
gc.callbacks.append(lambda phase, info: full.append(threading.current_thread().name)
                    if phase == "start" and info["generation"] == 2 else None)
from torsal.nodes.io.formats.labels import text_outlines
if sys.argv[1] == "disabled":
    gc.disable()
before = len(full)
outlines = text_outlines("A1")
print(json.dumps({"full": full[before:], "enabled": gc.isenabled(), "frozen": gc.get_freeze_count(),
                  "outlines": len(outlines)}))
"""


def load_in_a_fresh_process(collector: str) -> dict:
    done = subprocess.run([sys.executable, "-c", LOAD, collector], capture_output=True, text=True,
                          cwd=ROOT, timeout=120, check=True)
    return json.loads(done.stdout)


def test_the_first_font_load_sets_off_no_full_collection():
    seen = load_in_a_fresh_process("enabled")
    assert seen["outlines"] >= 3  # "A" has two contours, "1" one: the font did load
    assert seen["full"] == []


def test_the_collector_is_on_again_after_the_load_and_what_it_made_is_not_walked_again():
    seen = load_in_a_fresh_process("enabled")
    assert seen["enabled"] is True
    assert seen["frozen"] > 0


def test_a_collector_the_caller_had_turned_off_stays_off():
    assert load_in_a_fresh_process("disabled")["enabled"] is False

"""The example graphs are what tools/build_examples.py writes, byte for byte: an example is
edited in the tool and rebuilt, so the tool never drifts from the committed file."""

from __future__ import annotations

from pathlib import Path

import pytest

from tools import build_examples

EXAMPLES = Path(build_examples.__file__).resolve().parents[1] / "torsal" / "resources" / "examples"


@pytest.mark.parametrize("name", sorted(build_examples.EXAMPLES))
def test_the_tool_writes_the_committed_example(name, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(build_examples, "OUT", tmp_path)
    build_examples.EXAMPLES[name]()
    built = (tmp_path / f"{name}.graph").read_text(encoding="utf-8")
    committed = (EXAMPLES / f"{name}.graph").read_text(encoding="utf-8")
    assert built == committed, f"tools/build_examples.py no longer writes {name}.graph as committed"

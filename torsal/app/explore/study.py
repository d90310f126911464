"""A graph opened for exploration: its text (what travels to workers) and its parsed form."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from torsal.app.explore.variables import Target, Variable, parse_target, parse_vary
from torsal.app.headless import UsageError, refuse_missing
from torsal.engine.graph import Graph
from torsal.engine.graphfile import GraphFileError, loads, read_file


@dataclass
class Study:
    """The graph file, its text and graph, the varied sliders and the collected outputs."""

    path: Path
    text: str
    graph: Graph
    variables: list[Variable]
    targets: list[Target]


def open_study(path: Path, vary: list[str], collect: list[str], steps: bool, collect_flag: str = "--collect"
               ) -> Study:
    """Read ``path`` and check every ``--vary`` and ``--collect`` against it (UsageError when wrong)."""

    try:
        text = read_file(path).decode("utf-8")
    except GraphFileError as exc:
        raise UsageError(f"{path}: {exc}") from None
    except UnicodeDecodeError:
        raise UsageError(f"{path}: the file is not UTF-8 text, so not a graph file") from None
    return study_from_text(text, path, vary, collect, steps, collect_flag)


def study_from_text(text: str, path: Path, vary: list[str], collect: list[str], steps: bool,
                    collect_flag: str = "--collect") -> Study:
    """As :func:`open_study`, for a graph's text (the app's open document, saved or not)."""
    from torsal.app.explore.evaluate import _registry

    try:
        graph = loads(text, _registry())
    except GraphFileError as exc:
        raise UsageError(f"{path}: {exc}") from None
    refuse_missing(graph, path)
    if not vary:
        raise UsageError("give at least one --vary ID=LO:HI" + (":N" if steps else ""))
    variables = [parse_vary(text_, graph, steps) for text_ in vary]
    seen = [v.node_id for v in variables]
    twice = sorted({n for n in seen if seen.count(n) > 1})
    if twice:
        raise UsageError(f"--vary: {', '.join(twice)} is varied twice")
    if not collect:
        raise UsageError(f"give at least one {collect_flag} NODE.OUTPUT")
    targets = [parse_target(text_, graph, collect_flag) for text_ in collect]
    return Study(path, text, graph, variables, targets)

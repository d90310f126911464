"""Plug-ins as the commands see them: a graph that needs one that is not installed, and
plug-ins that could not be loaded (docs/plugins.md).

A node whose type no installed package provides is kept as a placeholder, so the app can
open the file and save it back unchanged. A headless command must not pass it off as
solved: ``run``, ``check``, ``sweep`` and ``optimise`` stop with exit code 2 naming each
missing type and, from the file's own record of it (the node's ``plugin`` field), the
package to install.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import TYPE_CHECKING, TextIO

from torsal.engine.cluster import reachable_definitions
from torsal.engine.graph import Graph, is_placeholder

if TYPE_CHECKING:
    from torsal.engine.registry import Registry


@dataclass(frozen=True)
class MissingType:
    """A node type the graph uses that is not installed, where, and who provides it."""

    type_id: str
    package: str | None  # the distribution the file names, or None when it names none
    nodes: tuple[str, ...]

    def sentence(self) -> str:
        more = len(self.nodes) - 5
        shown = ", ".join(self.nodes[:5]) + (f" and {more} more" if more > 0 else "")
        where = f"node{'s' if len(self.nodes) > 1 else ''} {shown}"
        if self.package:
            return (f"node type {self.type_id!r} ({where}) is not installed: it comes from the plug-in "
                    f"package {self.package!r} (pip install {self.package})")
        return (f"node type {self.type_id!r} ({where}) is not installed, and the file does not say which "
                f"plug-in package provides it")


def missing_types(graph: Graph) -> list[MissingType]:
    """Every node type of ``graph`` and its cluster definitions that is not installed."""
    found: dict[str, tuple[set[str], list[str]]] = {}
    scopes = [("", graph), *((f"{d.id}/", d.graph) for d in reachable_definitions(graph))]
    for prefix, scope in scopes:
        for node_id, record in scope.nodes.items():
            if is_placeholder(record.node):
                packages, nodes = found.setdefault(record.type_id, (set(), []))
                nodes.append(prefix + node_id)
                named = record.raw.get("plugin")
                if isinstance(named, str) and named:
                    packages.add(named)
    return [MissingType(type_id, " or ".join(sorted(packages)) or None, tuple(nodes))
            for type_id, (packages, nodes) in sorted(found.items())]


def problems() -> list[str]:
    """What went wrong loading the installed plug-ins (a broken one, a type-id clash)."""
    from torsal.nodes.catalogue import default_registry

    return default_registry().problems


def report_problems(stream: TextIO | None = None) -> Registry:
    """Print each plug-in problem on stderr (the ``torsal`` command does it once a command);
    returns the registry they were found in, for the command to use (``torsal gui`` does:
    the plug-ins are looked up once)."""
    from torsal.nodes.catalogue import default_registry

    registry = default_registry()
    for problem in registry.problems:
        print(f"torsal: {problem}", file=stream or sys.stderr)
    return registry

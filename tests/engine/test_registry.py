"""The node registry: lazy palettes, type ids, and third-party plug-ins by entry point."""

from __future__ import annotations

import subprocess
import sys
import types
from pathlib import Path

import pytest

from engine import registry as registry_module
from engine.node import Node, Out
from engine.registry import Registry
from engine.types import NUMBER
from nodes.catalogue import MODULES, default_registry

ROOT = Path(__file__).resolve().parents[2]


class Seven(Node):
    """Always seven."""

    type_id = "plugin.Seven"
    outputs = (Out("Value", NUMBER, "V", "Seven."),)

    def solve(self) -> float:
        return 7.0


class FakeEntryPoint:
    def __init__(self, name: str, loaded: object) -> None:
        self.name, self._loaded = name, loaded

    def load(self) -> object:
        if isinstance(self._loaded, Exception):
            raise self._loaded
        return self._loaded


def test_plugins_register_classes_modules_and_factories(monkeypatch):
    module = types.ModuleType("fake_plugin")
    module.Seven = Seven
    Seven.__module__ = "fake_plugin"
    points = [
        FakeEntryPoint("module", module),
        FakeEntryPoint("broken", ImportError("no module named 'wobble'")),
    ]
    monkeypatch.setattr(registry_module, "entry_points", lambda group: points)
    registry = Registry()
    registry.load_entry_points()
    assert registry.get("plugin.Seven") is Seven
    assert registry.problems == ["plug-in 'broken' could not be loaded: no module named 'wobble'"]


def test_type_ids_must_be_palette_dot_name():
    class Bad(Node):
        type_id = "NoPalette"

    with pytest.raises(ValueError, match=r"<palette>\.<NodeName>"):
        Registry().register(Bad)


def test_every_catalogue_module_holds_only_its_own_palette():
    registry = default_registry(plugins=False)
    for cls in registry:
        module_palette = cls.__module__.split(".")[1]
        assert cls.palette() == module_palette, cls.type_id
    assert all(name.startswith("nodes.") and name.count(".") == 2 for name in MODULES)


def test_a_run_of_sliders_and_expressions_imports_no_geometry_library():
    fixture = ROOT / "tests" / "fixtures" / "twenty-nodes.graph"
    script = (
        "import sys, io, contextlib\n"
        "from app.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    assert main(['run', {str(fixture)!r}]) == 0\n"
        "print(sorted({m.split('.')[0] for m in sys.modules} & {'trimesh', 'shapely', 'matplotlib'}))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def lazy_registry() -> Registry:
    """Two promised palettes whose modules are fakes that record being imported."""
    registry = Registry()
    registry.register_lazy("params", "fake_params_nodes")
    registry.register_lazy("maths", "fake_maths_nodes")
    return registry


@pytest.fixture
def fake_modules(monkeypatch) -> list[str]:
    """``fake_params_nodes`` and ``fake_maths_nodes``, each holding one node type."""
    imported: list[str] = []
    for palette in ("params", "maths"):
        module = types.ModuleType(f"fake_{palette}_nodes")
        cls = type("One", (Node,), {"type_id": f"{palette}.One", "__module__": module.__name__})
        module.One = cls
        monkeypatch.setitem(sys.modules, module.__name__, module)
    real_import = registry_module.importlib.import_module

    def recording(name: str) -> types.ModuleType:
        imported.append(name)
        return real_import(name)

    monkeypatch.setattr(registry_module.importlib, "import_module", recording)
    return imported


def test_palettes_lists_promised_palettes_without_importing_them(fake_modules):
    assert lazy_registry().palettes() == ["maths", "params"]
    assert fake_modules == []


def test_types_in_imports_only_that_palettes_modules(fake_modules):
    registry = lazy_registry()
    assert [c.type_id for c in registry.types_in("maths")] == ["maths.One"]
    assert fake_modules == ["fake_maths_nodes"]

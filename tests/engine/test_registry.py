"""The registry: palettes found by their declarations and loaded lazily, type ids,
value types, and third-party plug-ins by entry point."""

from __future__ import annotations

import json
import subprocess
import sys
import types
from pathlib import Path

import pytest

from torsal.engine import registry as registry_module
from torsal.engine.node import Node, Out
from torsal.engine.registry import Registry
from torsal.engine.types import NUMBER, TypeTable, ValueType
from torsal.nodes.catalogue import default_registry

ROOT = Path(__file__).resolve().parents[2]


class Seven(Node):
    """Always seven."""

    type_id = "plugin.Seven"
    outputs = (Out("Value", NUMBER, "V", "Seven."),)

    def solve(self) -> float:
        return 7.0


class FakeEntryPoint:
    def __init__(self, name: str, loaded: object, dist: str | None = None) -> None:
        self.name, self._loaded = name, loaded
        self.dist = types.SimpleNamespace(name=dist) if dist else None

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
    assert registry.problems == ["plug-in 'broken' (entry point 'broken') could not be loaded: "
                                 "ImportError: no module named 'wobble'"]


def test_a_plugin_reusing_a_built_in_type_id_is_refused_naming_both_packages(monkeypatch):
    impostor = type("Expression", (Node,), {"type_id": "maths.Expression", "__module__": "impostor_nodes"})
    extra = type("Extra", (Node,), {"type_id": "impostor.Extra", "__module__": "impostor_nodes"})
    module = types.ModuleType("impostor_nodes")
    module.Expression, module.Extra = impostor, extra
    monkeypatch.setattr(registry_module, "entry_points",
                        lambda group: [FakeEntryPoint("nodes", module, dist="torsal-impostor")])
    registry = default_registry()
    # refused whole: the built-in stays, the plug-in's other type is not half-loaded
    assert registry.get("maths.Expression").__module__ == "torsal.nodes.maths.expression"
    assert registry.get("impostor.Extra") is None
    (problem,) = registry.problems
    assert "'torsal-impostor'" in problem and "'maths.Expression'" in problem
    assert "provided by 'torsal'" in problem


def test_of_two_plugins_with_one_type_id_the_first_by_name_is_kept(monkeypatch):
    first = type("Tile", (Node,), {"type_id": "tiles.Tile", "__module__": "a_nodes"})
    second = type("Tile", (Node,), {"type_id": "tiles.Tile", "__module__": "b_nodes"})
    points = [FakeEntryPoint("b", second, dist="torsal-b"), FakeEntryPoint("a", first, dist="torsal-a")]
    monkeypatch.setattr(registry_module, "entry_points", lambda group: points)
    registry = Registry()
    registry.load_entry_points()
    assert registry.get("tiles.Tile") is first
    assert registry_module.provider(first) == "torsal-a"
    (problem,) = registry.problems
    assert "'torsal-b'" in problem and "provided by 'torsal-a'" in problem


def test_type_ids_must_be_palette_dot_name():
    class Bad(Node):
        type_id = "NoPalette"

    with pytest.raises(ValueError, match=r"<palette>\.<NodeName>"):
        Registry().register(Bad)


def test_every_catalogue_module_holds_only_its_own_palette():
    registry = default_registry(plugins=False)
    for cls in registry:
        module_palette = cls.__module__.split(".")[2]
        assert cls.palette() == module_palette, cls.type_id
    modules = {cls.__module__ for cls in registry}
    assert all(name.startswith("torsal.nodes.") and name.count(".") == 3 for name in modules)


def test_every_module_with_node_types_is_declared_by_its_palette():
    """A node module left out of its palette's NODE_TYPES would vanish from the app."""
    declared = {name for names in default_registry(plugins=False)._lazy.values() for name in names}
    holding = set()
    for path in (ROOT / "torsal" / "nodes").glob("*/*.py"):
        if 'type_id = "' in path.read_text(encoding="utf-8"):
            holding.add(".".join(path.relative_to(ROOT).with_suffix("").parts))
    assert holding == declared


def test_finding_the_palettes_imports_no_node_module():
    script = (
        "import sys\n"
        "from torsal.nodes.catalogue import default_registry\n"
        "registry = default_registry(plugins=False)\n"
        "print(len(registry.palettes()), sorted(m for m in sys.modules if m.count('.') == 3 "
        "and m.startswith('torsal.nodes.')))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.split(maxsplit=1) == ["11", "[]\n"]


def test_a_run_of_sliders_and_expressions_imports_no_geometry_library():
    fixture = ROOT / "tests" / "fixtures" / "twenty-nodes.graph"
    script = (
        "import sys, io, contextlib\n"
        "from torsal.app.cli import main\n"
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


def test_an_indexed_type_imports_only_its_module(fake_modules):
    registry = lazy_registry()
    registry.register_lazy("params", "fake_more_params_nodes")  # never imported: not in sys.modules
    registry.add_index({"params.One": "fake_params_nodes"})
    assert registry.get("params.One").type_id == "params.One"
    assert fake_modules == ["fake_params_nodes"]
    assert registry.palettes() == ["maths", "params"]


def test_a_type_the_index_misplaces_or_omits_loads_its_whole_palette(fake_modules):
    registry = lazy_registry()
    registry.add_index({"maths.One": "fake_params_nodes"})  # stale: the module moved
    assert registry.get("maths.One").type_id == "maths.One"
    assert registry.get("params.One").type_id == "params.One"  # not in the index
    assert fake_modules == ["fake_maths_nodes", "fake_params_nodes"]
    assert registry.get("params.Missing") is None


def plugin_package(monkeypatch, name: str, declarations: dict) -> types.ModuleType:
    """A fake palette package ``name`` with a node module ``name.nodes`` (holding Seven-like
    ``tiles.Eight`` with an ``Octagon`` output) and a value-type module ``name.values``."""
    octagon = ValueType("Octagon", (tuple,), "Eight sides.")
    values = types.ModuleType(f"{name}.values")
    values.OCTAGON = octagon
    nodes_module = types.ModuleType(f"{name}.nodes")
    eight = type("Eight", (Node,), {
        "type_id": "tiles.Eight", "__module__": nodes_module.__name__,
        "outputs": (Out("Shape", octagon, "S", "An octagon."),),
    })
    nodes_module.Eight = eight
    package = types.ModuleType(name)
    package.__path__ = []
    vars(package).update(declarations)
    for module in (package, values, nodes_module):
        monkeypatch.setitem(sys.modules, module.__name__, module)
    return package


def test_a_plugin_palette_package_loads_whole_with_its_value_types(monkeypatch, fake_modules):
    """Unlike Torsal's own palettes, a plug-in's modules are imported when it is loaded, so
    every command can tell whether it is broken or clashes (docs/plugins.md)."""
    package = plugin_package(monkeypatch, "torsal_tiles",
                             {"PALETTE": "tiles", "NODE_TYPES": ("nodes",), "VALUE_TYPES": ("values",)})
    monkeypatch.setattr(registry_module, "entry_points", lambda group: [FakeEntryPoint("tiles", package)])
    registry = Registry(value_types=TypeTable())
    registry.load_entry_points()
    assert fake_modules == ["torsal_tiles.values", "torsal_tiles.nodes"]
    assert registry.palettes() == ["tiles"]
    assert registry.get("tiles.Eight").__name__ == "Eight"
    assert registry.value_types.find("Octagon").description == "Eight sides."


def test_a_value_type_asked_for_by_name_loads_the_module_declaring_it(monkeypatch):
    table = TypeTable()
    values = types.ModuleType("fake_values")
    values.OCTAGON = ValueType("Octagon", (tuple,), "Eight sides.")
    monkeypatch.setitem(sys.modules, "fake_values", values)
    table.declare("fake_values")
    assert table.find("Octagon") is values.OCTAGON
    assert table.find("Nonagon") is None


def test_the_ports_of_a_registered_node_type_make_their_value_types_known():
    table = TypeTable()
    Registry(value_types=table).register(Seven)
    assert table.find("Number") is NUMBER


def test_a_line_in_a_file_is_read_though_no_geometry_palette_is_loaded(tmp_path):
    """The geometry types are the library's (nodes/__init__.py): a Line kept on a Panel's
    input is read and passed on, in a run that loads only the params palette."""
    line = {"type": "Line", "from": [0, 0, 0], "to": [3, 4, 0]}
    path = tmp_path / "line.graph"
    path.write_text(json.dumps({"format": "torsal.graph", "version": 1, "nodes": [
        {"id": "p", "type": "params.Panel", "inputs": {"Input": {"value": line}}}]}))
    script = (
        "import io, contextlib, json\n"
        "from torsal.app.cli import main\n"
        "out = io.StringIO()\n"
        "with contextlib.redirect_stdout(out):\n"
        f"    main(['run', {str(path)!r}, '--json'])\n"
        "print(json.dumps(json.loads(out.getvalue())['nodes']['p']['outputs']))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True, cwd=ROOT)
    (summary,) = json.loads(out.stdout)["Output"]["{0}"]
    assert summary["type"] == "Line" and summary["length"] == 5.0


def test_a_value_in_a_file_is_read_with_the_type_its_palette_declares():
    """A Tag is a display value type: reading one needs no display node in the graph."""
    script = (
        "import sys\n"
        "from torsal.nodes.catalogue import default_registry\n"
        "from torsal.engine.types import decode_value\n"
        "default_registry(plugins=False)\n"
        "tag = decode_value({'type': 'Tag', 'text': 'north', 'location': [1, 2, 3]})\n"
        "print(type(tag).__name__, tag.text)\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.split() == ["Tag", "north"]


def test_a_value_made_without_a_registry_finds_the_type_its_imported_package_declares(monkeypatch):
    """A node used on its own (no registry): its package's VALUE_TYPES, already imported, is read."""
    class Octagon(tuple):
        pass

    table = TypeTable()
    values = types.ModuleType("fake_library.values")
    values.OCTAGON = ValueType("Octagon", (Octagon,), "Eight sides.")
    package = types.ModuleType("fake_library")
    package.__path__ = []
    package.VALUE_TYPES = ("values",)
    for module in (package, values):
        monkeypatch.setitem(sys.modules, module.__name__, module)
    assert [t for t in table.values() if t.name == "Octagon"] == [values.OCTAGON]

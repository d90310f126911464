"""Every node in the catalogue documents itself: help text, ids, port descriptions."""

from __future__ import annotations

import json

import pytest

from torsal.nodes.catalogue import default_registry

REGISTRY = default_registry(plugins=False)
NODE_CLASSES = list(REGISTRY)
FIRST_NODES = {
    "params.NumberSlider", "params.IntegerSlider", "params.Toggle", "params.Panel",
    "params.ValueList", "params.Point", "params.Vector", "params.UnitX", "params.UnitY",
    "params.UnitZ", "maths.Expression", "maths.Series", "maths.Range", "maths.Domain",
    "maths.Random", "lists.ListItem", "lists.ListLength", "lists.Shift", "lists.Reverse",
    "lists.Flatten", "lists.Graft", "lists.Merge", "lists.Partition", "lists.CullPattern",
    "lists.Sort",
}


def ids(cls) -> str:
    return cls.type_id


def test_catalogue_holds_every_first_node():
    assert FIRST_NODES - {cls.type_id for cls in NODE_CLASSES} == set()


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=ids)
def test_node_has_a_docstring(cls):
    assert cls.__doc__ and len(cls.help()) > 20


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=ids)
def test_type_id_is_palette_dot_class_name_and_palette_is_the_module_folder(cls):
    palette, name = cls.type_id.split(".")
    assert name == cls.__name__
    assert cls.__module__.split(".")[2] == palette


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=ids)
def test_every_port_has_a_nickname_and_a_description(cls):
    ports = [*cls.inputs, *cls.outputs, *cls().input_ports(), *cls().output_ports()]
    for port in ports:
        assert port.nickname, f"{cls.type_id}.{port.name} has no nickname"
        assert port.description.strip().endswith("."), f"{cls.type_id}.{port.name}"


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=ids)
def test_port_names_are_unique_per_side(cls):
    node = cls()
    for ports in (node.input_ports(), node.output_ports()):
        names = [p.name for p in ports]
        assert len(names) == len(set(names))


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=ids)
def test_every_setting_has_a_description(cls):
    for setting in cls.settings_spec:
        assert setting.description, f"{cls.type_id} setting {setting.name}"


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=ids)
def test_catalogue_entry_is_json(cls):
    entry = json.loads(json.dumps(cls.catalogue_entry()))
    assert entry["type"] == cls.type_id


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=ids)
def test_port_names_are_pascal_case_except_expression_variables(cls):
    inputs = () if cls.type_id == "maths.Expression" else cls.inputs
    for port in (*inputs, *cls.outputs):
        assert port.name[0].isupper() and " " not in port.name, f"{cls.type_id}.{port.name}"

"""Sliders and toggles: values from settings, clamped and rounded."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts
from torsal.nodes.params.sliders import IntegerSlider, NumberSlider, Toggle


def test_number_slider_defaults_to_half_between_0_and_1_with_2_decimals():
    node = NumberSlider()
    assert node.settings == {"value": 0.5, "min": 0.0, "max": 1.0, "decimals": 2}
    result = run(node)
    assert result.state == "ok"
    assert out(result) == {(0,): [0.5]}


def test_number_slider_rounds_value_to_decimals():
    result = run(NumberSlider({"value": 3.14159, "min": 0, "max": 10, "decimals": 3}))
    assert out(result) == {(0,): [3.142]}


def test_number_slider_with_0_decimals_gives_whole_float():
    result = run(NumberSlider({"value": 2.6, "min": 0, "max": 10, "decimals": 0}))
    assert out(result) == {(0,): [3.0]}
    assert isinstance(out(result)[(0,)][0], float)


def test_number_slider_clamps_value_above_max_with_warning():
    result = run(NumberSlider({"value": 12.34, "min": 0, "max": 10, "decimals": 1}))
    assert out(result) == {(0,): [10.0]}
    assert result.state == "warning"
    assert texts(result) == ["Value 12.3 is above the maximum 10: using 10"]


def test_number_slider_clamps_value_below_min_with_warning():
    result = run(NumberSlider({"value": -5, "min": -1, "max": 1, "decimals": 2}))
    assert out(result) == {(0,): [-1.0]}
    assert texts(result) == ["Value -5 is below the minimum -1: using -1"]


def test_number_slider_reads_text_value_set_from_command_line():
    result = run(NumberSlider({"value": "0.25"}))
    assert out(result) == {(0,): [0.25]}


def test_number_slider_with_min_above_max_is_an_error():
    result = run(NumberSlider({"value": 1, "min": 5, "max": 2}))
    assert result.state == "error"
    assert texts(result) == ["The slider's min (5) is greater than its max (2)"]
    assert out(result) == {}


def test_number_slider_rejects_nan_value():
    result = run(NumberSlider({"value": float("nan")}))
    assert result.state == "error"
    assert texts(result) == ["The slider's value must be a finite number, not nan"]


def test_number_slider_rejects_negative_decimals():
    result = run(NumberSlider({"decimals": -1}))
    assert texts(result) == ["The slider's decimals must be a whole number from 0 to 15, not -1"]


def test_number_slider_rejects_text_that_is_not_a_number():
    result = run(NumberSlider({"value": "tall"}))
    assert result.state == "error"
    assert "could not read Text 'tall' as a Number" in texts(result)[0]


def test_integer_slider_gives_an_integer():
    result = run(IntegerSlider({"value": 7, "min": 0, "max": 10}))
    assert out(result) == {(0,): [7]}
    assert type(out(result)[(0,)][0]) is int


def test_integer_slider_clamps_value_above_max_with_warning():
    result = run(IntegerSlider({"value": 50, "min": 0, "max": 10}))
    assert out(result) == {(0,): [10]}
    assert texts(result) == ["Value 50 is above the maximum 10: using 10"]


def test_integer_slider_rounds_a_fractional_value_with_warning():
    result = run(IntegerSlider({"value": 2.6, "min": 0, "max": 10}))
    assert out(result) == {(0,): [3]}
    assert texts(result) == ["Value 2.6 is not a whole number: using 3"]


def test_toggle_gives_its_boolean():
    assert out(run(Toggle({"value": True}))) == {(0,): [True]}
    assert out(run(Toggle())) == {(0,): [False]}


def test_toggle_reads_true_written_as_text():
    assert out(run(Toggle({"value": "true"}))) == {(0,): [True]}


def test_toggle_rejects_a_number():
    result = run(Toggle({"value": 3}))
    assert result.state == "error"
    assert texts(result) == ["The toggle's value must be true or false, not 3"]

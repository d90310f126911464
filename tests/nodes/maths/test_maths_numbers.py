"""Series, Range, Domain and Random."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from tests.support.node_helpers import out, run, texts
from torsal.engine.values import Domain
from torsal.nodes.maths.domains import Domain as DomainNode
from torsal.nodes.maths.random_numbers import Random
from torsal.nodes.maths.sequences import Range, Series

ROOT = Path(__file__).resolve().parents[3]


def items(result) -> list:
    return [x for branch in out(result).values() for x in branch]


def test_series_counts_up_from_start_by_step():
    assert items(run(Series(), Start=1, Step=0.5, Count=4)) == [1.0, 1.5, 2.0, 2.5]


def test_series_defaults_to_ten_numbers_from_zero():
    assert items(run(Series())) == [float(i) for i in range(10)]


def test_series_with_several_counts_makes_one_branch_per_count():
    result = run(Series(), Count=[2, 3])
    assert out(result) == {(0, 0): [0.0, 1.0], (0, 1): [0.0, 1.0, 2.0]}


def test_series_with_count_zero_is_empty():
    result = run(Series(), Count=0)
    assert result.state == "ok"
    assert items(result) == []


def test_series_with_negative_count_warns():
    result = run(Series(), Count=-1)
    assert result.state == "warning"
    assert texts(result) == ["Count must be at least 0, not -1"]
    assert items(result) == []


def test_series_with_absurd_count_warns_instead_of_filling_memory():
    result = run(Series(), Count=10**12)
    assert texts(result) == ["Count is 1,000,000,000,000; at most 1,000,000 can be made at once"]


def test_series_with_nan_step_warns():
    result = run(Series(), Step="nan")
    assert texts(result) == ["Step is not a number (NaN)"]


def test_range_gives_steps_plus_one_numbers_including_both_ends():
    result = run(Range(), Domain=Domain(0, 10), Steps=4)
    assert items(result) == [0.0, 2.5, 5.0, 7.5, 10.0]


def test_range_over_a_reversed_domain_counts_down():
    assert items(run(Range(), Domain=Domain(1, 0), Steps=2)) == [1.0, 0.5, 0.0]


def test_range_ends_exactly_at_the_domain_end():
    values = items(run(Range(), Domain=Domain(0.1, 0.7), Steps=3))
    assert values[-1] == 0.7
    assert len(values) == 4


def test_range_with_zero_steps_warns():
    result = run(Range(), Steps=0)
    assert texts(result) == ["Steps must be at least 1, not 0"]


def test_range_from_a_number_uses_zero_to_that_number():
    assert items(run(Range(), Domain=2.0, Steps=2)) == [0.0, 1.0, 2.0]


def test_domain_from_start_and_end():
    assert out(run(DomainNode(), Start=2, End=5)) == {(0,): [Domain(2.0, 5.0)]}


def test_domain_with_nan_end_warns():
    result = run(DomainNode(), End="nan")
    assert texts(result) == ["End is not a number (NaN)"]


def test_random_numbers_fall_in_the_range():
    values = items(run(Random(), Range=Domain(5, 7), Number=1000, Seed=3))
    assert len(values) == 1000
    assert all(5.0 <= v < 7.0 for v in values)
    assert max(values) - min(values) > 1.9


def test_random_with_same_seed_gives_same_numbers():
    first = items(run(Random(), Number=5, Seed=42))
    second = items(run(Random(), Number=5, Seed=42))
    assert first == second


def test_random_with_another_seed_gives_other_numbers():
    assert items(run(Random(), Number=5, Seed=1)) != items(run(Random(), Number=5, Seed=2))


def test_random_is_the_same_in_a_fresh_python_process():
    script = (
        "import json\n"
        "from torsal.engine.values import Domain\n"
        "from torsal.nodes.maths.random_numbers import Random\n"
        "from tests.support.node_helpers import run\n"
        "r = run(Random(), Range=Domain(0, 10), Number=4, Seed=7)\n"
        "print(json.dumps(r.output('Random').all_items()))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], cwd=ROOT, capture_output=True, text=True, check=True
    )
    here = items(run(Random(), Range=Domain(0, 10), Number=4, Seed=7))
    assert json.loads(done.stdout) == here


def test_random_with_negative_seed_warns():
    result = run(Random(), Seed=-3)
    assert texts(result) == ["Seed must be at least 0, not -3"]


def test_random_with_negative_number_warns():
    result = run(Random(), Number=-1)
    assert texts(result) == ["Number must be at least 0, not -1"]

"""Right-click → Match outputs gives Explode Tree one output per branch, in one undo step."""

from __future__ import annotations

from tests.support.fixtures_gui import right_click, title_point, wait_solved
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.nodes.lists.explode import ExplodeTree
from torsal.nodes.lists.trees import Partition
from torsal.nodes.params.panel import Panel


def outputs_drawn(window, node_id: str) -> list[str]:
    return sorted(name for is_input, name in window.scene.nodes[node_id].ports if not is_input)


def test_match_outputs_from_the_node_menu_gives_one_output_per_branch(qtbot, window, tmp_path):
    graph = Graph()
    graph.add_node(Panel({"text": "1\n2\n3\n4\n5\n6\n7"}), "numbers", position=(0.0, 0.0))
    graph.add_node(Partition(), "chunks", position=(220.0, 0.0))
    graph.set_input_value("chunks", "Size", 2)
    graph.add_node(ExplodeTree(), "bang", position=(440.0, 0.0))
    graph.connect("numbers", "Output", "chunks", "List")
    graph.connect("chunks", "Chunks", "bang", "Data")
    write_graph(graph, tmp_path / "bang.graph")
    assert window.open_file(tmp_path / "bang.graph", ask=False)
    wait_solved(qtbot, window)
    assert window.doc.results["bang"].state == "warning"  # 4 chunks, 2 outputs
    assert outputs_drawn(window, "bang") == ["Branch0", "Branch1"]

    catcher = right_click(window, title_point(window, "bang"), pick="Match outputs")
    assert "Match outputs" in catcher.entries
    wait_solved(qtbot, window)
    assert outputs_drawn(window, "bang") == ["Branch0", "Branch1", "Branch2", "Branch3"]
    assert window.doc.results["bang"].state == "ok"
    assert window.doc.results["bang"].output("Branch3").all_items() == ["7"]
    assert window.doc.undo_stack.undoText() == "Match outputs"
    window.doc.undo_stack.undo()
    wait_solved(qtbot, window)
    assert outputs_drawn(window, "bang") == ["Branch0", "Branch1"]


def test_nodes_without_outputs_to_match_offer_no_match_outputs(window, qtbot, tmp_path):
    graph = Graph()
    graph.add_node(Partition(), "chunks")
    write_graph(graph, tmp_path / "plain.graph")
    assert window.open_file(tmp_path / "plain.graph", ask=False)
    wait_solved(qtbot, window)
    assert "Match outputs" not in right_click(window, title_point(window, "chunks")).entries

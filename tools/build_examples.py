"""Write the example graphs in ``torsal/resources/examples/`` through the engine's own API.

Run ``.venv/bin/python tools/build_examples.py [NAME ...]`` after changing a node's
ports. The files are data and are committed; this script writes each one byte for byte
as committed (``tests/resources/test_examples_built.py`` builds them all and compares), so
an edit to an example is made here and the file rebuilt. Positions are in columns, left
to right, with groups around each stage, laid out so that each example opens on something
readable (the app frames the region around the last previewed node and what feeds it:
``torsal/app/gui/canvas/opening_focus.py``): a slider that feeds only the result sits
beside it, in its group, as a Grasshopper user places it. Previews never fight: a flat
development lies beside the model (Placement 0) or has its preview off, and a check that
would draw the same geometry again has its preview off.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from torsal.engine.graph import Graph, Group
from torsal.engine.graphfile import write_graph
from torsal.nodes.catalogue import default_registry

OUT = Path(__file__).resolve().parent.parent / "torsal" / "resources" / "examples"
REGISTRY = default_registry(plugins=False)
COLUMN, ROW = 260.0, 110.0


def point(x: float, y: float, z: float) -> dict[str, Any]:
    return {"type": "Point", "xyz": [round(x, 6), round(y, 6), round(z, 6)]}


class Builder:
    """A graph under construction: nodes placed on a grid of columns and rows."""

    def __init__(self, description: str) -> None:
        self.graph = Graph()
        self.graph.meta = {"description": description, "created_with": "torsal 0.1.0"}

    def node(self, type_id: str, node_id: str, column: float, row: float, label: str = "",
             settings: dict[str, Any] | None = None, **values: Any) -> str:
        self.graph.add_node(REGISTRY.create(type_id, settings), node_id, label=label,
                            position=(40.0 + column * COLUMN, 40.0 + row * ROW))
        for port, value in values.items():
            self.graph.set_input_value(node_id, port, value)
        return node_id

    def slider(self, node_id: str, row: float, label: str, value: float, low: float, high: float,
               decimals: int = 2, column: float = 0) -> str:
        return self.node("params.NumberSlider", node_id, column, row, label,
                         {"value": value, "min": low, "max": high, "decimals": decimals})

    def integer(self, node_id: str, row: float, label: str, value: int, low: int, high: int,
                column: float = 0) -> str:
        return self.node("params.IntegerSlider", node_id, column, row, label,
                         {"value": value, "min": low, "max": high})

    def wire(self, source: str, target: str, modifiers: list[str] | None = None) -> None:
        (a, port_a), (b, port_b) = source.split("."), target.split(".")
        self.graph.connect(a, port_a, b, port_b)
        if modifiers:
            self.graph.set_modifiers(b, port_b, modifiers)

    def group(self, group_id: str, title: str, colour: str, members: list[str]) -> None:
        self.graph.groups.append(Group(group_id, title, colour, members))

    def save(self, name: str) -> None:
        write_graph(self.graph, OUT / f"{name}.graph")
        print(f"wrote {name}.graph: {len(self.graph.nodes)} nodes, {len(self.graph.wires)} wires")


INPUTS, GEOMETRY, RESULT = "#e8e0f4", "#dceee2", "#f6e6d0"


def kaohsiung() -> None:
    """Kaohsiung Solar Stadium (Toyo Ito): a horseshoe base curve, copied up and scaled in;
    edge curves through points shifted by n and 2n along the three curves; a
    RulingDevelopable strip between each pair of neighbouring edges."""
    kaohsiung_roof().save("kaohsiung-stadium")


def kaohsiung_cut_sheets() -> None:
    """The Kaohsiung roof as a 1:50 study model: every strip unrolled and laid out on
    2500 × 1250 mm sheets with its ID engraved."""
    b = kaohsiung_roof(
        "Kaohsiung Solar Stadium roof as a 1:50 study model: the developable strips of the case "
        "study are unrolled with IsoMapping, scaled to 1:50 and laid out on 2500 × 1250 mm sheets"
        " by ExportCutSheet, each strip's ID engraved. Export headless with: torsal run "
        "kaohsiung-cut-sheets.graph --export cut.Layout=roof.dxf --export cut.Layout=roof.svg "
        "--export cut.Layout=roof.3dm. The sheets are nested TrueShape (sparrow, the graph's Seed"
        " and TimeBudget 20: about 72 % of the stock used, the last sheet counted to its parts' "
        "reach); in the app the rows (Shelf) show at once and the true-shape sheets replace them "
        "when the background search finds them (Esc keeps the best so far); headless, torsal run "
        "waits for the search (15-50 s on two busy cores), or --nesting-time S keeps the rows and"
        " searches for at most S s. --set cut.Nesting=Shelf lays them out in rows at once (about "
        "half the stock) (for full-size panels, panelise each development with SurfacePatching as"
        " in development-and-panels.graph).",
        count=16, shift=1,
    )
    b.node("analysis.IsoMapping", "unroll", 9, 3, "Unrolled strips", Placement=1)  # at the origin
    b.wire("strip.Surface", "unroll.Surface")
    b.wire("segments.Value", "unroll.Segments")
    b.slider("model_scale", 6.5, "Model scale (1:n)", 50.0, 10.0, 200.0, 0, column=9)
    b.node("maths.Expression", "factor", 9, 5, "1 / n", {"expression": "1 / n", "variables": ["n"]})
    b.wire("model_scale.Value", "factor.n")
    b.node("transform.Scale", "model", 10, 3, "Scaled to the model", Centre=point(0, 0, 0))
    b.wire("unroll.Development", "model.Geometry")
    b.wire("factor.Result", "model.Factor")
    b.node("io.ExportCutSheet", "cut", 11, 3, "Cut sheets (mm)", Path="out/kaohsiung-roof.dxf",
           SheetWidth=2500.0, SheetHeight=1250.0, Gap=10.0, Kerf=0.0, TextHeight=12.0, Units="m",
           Nesting="TrueShape", TimeBudget=20.0, Write=False)
    b.wire("model.Geometry", "cut.Surfaces", ["flatten"])
    b.wire("strip.Surface", "cut.Strips")  # neighbouring strips' shared edges become seams
    # the flat parts are for the cutter; the cut node previews its sheets at the roof's scale,
    # beside it (its Preview output)
    for flat in ("unroll", "model"):
        b.graph.set_preview(flat, False)
    b.group("fabrication", "Unrolled, scaled, laid out", RESULT,
            ["unroll", "model_scale", "factor", "model", "cut"])
    b.save("kaohsiung-cut-sheets")


def kaohsiung_roof(description: str | None = None, count: int = 24, shift: int = 2) -> Builder:
    """The Kaohsiung roof graph, up to its developable strips."""
    b = Builder(
        "Kaohsiung Solar Stadium roof (after Toyo Ito), as in the 2011 TU Delft toolbox case "
        "study: a horseshoe base curve is copied up and scaled inwards, and edge curves run "
        "through points shifted by n and 2n along the three curves (gathering at the curves' "
        "ends, so the roof tapers to both ends of the horseshoe). Between neighbouring edges, "
        "RulingDevelopable makes developable strips: each strip bends one way only, yet together "
        "they read as a double-curved roof; neighbouring strips share their edge curve exactly, and "
        "each strip's ends are closed by smooth cones where its rims admit no torsal ruling. Drag "
        "'Inward scale' or 'Shift n' and watch the strips re-form."
        if description is None else description
    )
    # a horseshoe: an ellipse open towards +x
    angles = [math.radians(a) for a in range(40, 321, 35)]
    horseshoe = [point(60 * math.cos(a), 42 * math.sin(a), 0.0) for a in angles]
    b.slider("height", 0, "Roof height (m)", 14.0, 4.0, 30.0, 1)
    b.slider("scale", 1, "Inward scale", 0.72, 0.4, 0.95, 2)
    b.integer("count", 2, "Edge points", count, 8, 60)
    b.integer("shift", 3, "Shift n", shift, 0, 6)
    # beside the strips it refines, in their group (a slider by the node it drives)
    b.integer("segments", 5, "Segments per strip", 12, 2, 60, column=7)
    b.node("curves.Interpolate", "base", 1, 0, "Horseshoe base curve", Vertices=horseshoe, Degree=3)
    b.node("params.UnitZ", "up", 1, 1.5, "Up")
    b.node("transform.Move", "top", 2, 0, "Copied up")
    b.node("params.Point", "centre", 2, 1.5, "Scale centre", X=0.0, Y=0.0, Z=28.0)
    b.node("transform.Scale", "inner", 3, 0, "Scaled inwards")
    b.wire("height.Value", "up.Factor")
    b.wire("base.Curve", "top.Geometry")
    b.wire("up.Vector", "top.Motion")
    b.wire("top.Geometry", "inner.Geometry")
    b.wire("centre.Point", "inner.Centre")
    b.wire("scale.Value", "inner.Factor")
    # Edge curve j runs through the base and inner curves at parameters shifted by 2n and 0
    # steps of 1/count, clamped to the curves' ends, and through the top curve midway: in the
    # middle it is the thesis's point-shifted edge (shifts 2n, n, 0); towards both ends of the
    # horseshoe the edges gather at the curves' end points, so the strips taper there and the
    # roof reaches the ends of the horseshoe.
    b.node("maths.Expression", "edges", 1, 3, "Edge count",
           {"expression": "count + 1 + 2 * n", "variables": ["count", "n"]})
    b.wire("count.Value", "edges.count")
    b.wire("shift.Value", "edges.n")
    b.node("maths.Series", "edge_index", 2, 3, "Edge numbers j", Start=0)
    b.wire("edges.Result", "edge_index.Count")
    on_base, on_inner = "min(max((j - 2 * n) / count, 0), 1)", "min(max(j / count, 0), 1)"
    # the top point midway between the other two, so two edges share at most their end point
    expressions = [on_base, f"({on_base} + {on_inner}) / 2", on_inner]
    for k, (source, expression) in enumerate(zip(["base.Curve", "top.Geometry", "inner.Geometry"],
                                                 expressions, strict=True)):
        b.node("maths.Expression", f"param{k}", 3, 3 + k, f"t on curve {k}",
               {"expression": expression, "variables": ["j", "n", "count"]})
        b.wire("edge_index.Series", f"param{k}.j")
        b.wire("shift.Value", f"param{k}.n")
        b.wire("count.Value", f"param{k}.count")
        b.node("curves.EvaluateCurve", f"pick{k}", 4, 3 + k, f"Points on curve {k}")
        b.wire(source, f"pick{k}.Curve")
        b.wire(f"param{k}.Result", f"pick{k}.Parameter", ["graft"])  # one branch per edge curve
    b.node("curves.Interpolate", "edge_curves", 5, 3, "Strip edge curves", Degree=2)
    for k in range(3):
        b.wire(f"pick{k}.Point", "edge_curves.Vertices")
    b.node("maths.Expression", "strips", 6, 4.5, "Strip count",
           {"expression": "edges - 1", "variables": ["edges"]})
    b.wire("edges.Result", "strips.edges")
    b.node("maths.Series", "left_index", 6, 5.7, "Left edges", Start=0)
    b.node("maths.Series", "right_index", 6, 6.9, "Right edges", Start=1)
    b.wire("strips.Result", "left_index.Count")
    b.wire("strips.Result", "right_index.Count")
    b.node("lists.ListItem", "left", 7, 3, "Left edge")
    b.node("lists.ListItem", "right", 7, 4, "Right edge")
    b.wire("edge_curves.Curve", "left.List", ["flatten"])
    b.wire("edge_curves.Curve", "right.List", ["flatten"])
    b.wire("left_index.Series", "left.Index")
    b.wire("right_index.Series", "right.Index")
    b.node("developable.RulingDevelopable", "strip", 8, 3, "Developable strips", WarpTolerance=0.01)
    b.wire("left.Item", "strip.CurveA")
    b.wire("right.Item", "strip.CurveB")
    b.wire("segments.Value", "strip.Segments")
    # as a Grasshopper user would: preview off on the helpers, so the viewport shows the
    # three guide curves, the edge curves and the strips (and a drag redraws only those)
    helpers = ("up", "centre", "top", "pick0", "pick1", "pick2", "left", "right")
    for helper in helpers:
        b.graph.set_preview(helper, False)
    b.group("inputs", "Inputs", INPUTS, ["height", "scale", "count", "shift"])
    b.group("roof", "Base curve, copied up and in", GEOMETRY, ["base", "up", "top", "centre", "inner"])
    b.group("edges", "Edge curves through shifted points", GEOMETRY,
            ["edges", "edge_index", "param0", "param1", "param2", "pick0", "pick1", "pick2", "edge_curves"])
    b.group("strips", "Developable strips", RESULT,
            ["strips", "left_index", "right_index", "left", "right", "strip", "segments"])
    return b


def guggenheim() -> None:
    """Guggenheim Museum New York (Frank Lloyd Wright): stacked conical rings that widen as
    they rise, and a cylindrical elevator shaft beside them."""
    b = Builder(
        "Guggenheim Museum New York (after Frank Lloyd Wright), as in the 2011 TU Delft toolbox "
        "case study: a stack of conical rings, each wider than the one below, plus a cylindrical "
        "elevator shaft. Ring height, flare and count are sliders; every ring is a cone, so it "
        "unrolls flat without stretching."
    )
    b.integer("rings", 0, "Ring count", 5, 1, 9)
    b.slider("ring_height", 1, "Ring height (m)", 3.2, 1.0, 6.0, 1)
    b.slider("flare", 2, "Flare per ring (m)", 1.1, 0.2, 3.0, 2)
    b.slider("radius", 3, "Base radius (m)", 14.0, 6.0, 25.0, 1)
    b.slider("shaft_radius", 4, "Shaft radius (m)", 3.0, 1.0, 6.0, 1)
    # beside the rings it refines, in their group (a slider by the node it drives)
    b.integer("segments", 2, "Segments", 48, 8, 128, column=4)
    b.node("maths.Series", "index", 1, 0, "Ring index", Start=0, Step=1)
    b.wire("rings.Value", "index.Count")
    b.node("maths.Expression", "ring_z", 2, 0, "Ring base height",
           {"expression": "k * h", "variables": ["k", "h"]})
    b.node("maths.Expression", "ring_r", 2, 1, "Ring base radius",
           {"expression": "r + k * d", "variables": ["k", "r", "d"]})
    b.node("maths.Expression", "apex_z", 2, 2, "Apex height (below: the rings flare out)",
           {"expression": "k * h - h * (r + k * d) / d", "variables": ["k", "h", "r", "d"]})
    b.node("maths.Expression", "slant", 2, 3, "Ruling length (negative: away from the apex)",
           {"expression": "-sqrt(h**2 + d**2)", "variables": ["h", "d"]})
    for target in ("ring_z", "ring_r", "apex_z"):
        b.wire("index.Series", f"{target}.k")
    for target in ("ring_z", "apex_z", "slant"):
        b.wire("ring_height.Value", f"{target}.h")
    for target in ("ring_r", "apex_z"):
        b.wire("radius.Value", f"{target}.r")
    for target in ("ring_r", "apex_z", "slant"):
        b.wire("flare.Value", f"{target}.d")
    b.node("params.Point", "ring_centre", 3, 0, "Ring centre", X=0.0, Y=0.0)
    b.wire("ring_z.Result", "ring_centre.Z")
    b.node("curves.Circle", "ring_circle", 4, 0, "Ring base circle")
    b.wire("ring_centre.Point", "ring_circle.Plane")
    b.wire("ring_r.Result", "ring_circle.Radius")
    b.node("params.Point", "apex", 3, 2, "Apex", X=0.0, Y=0.0)
    b.wire("apex_z.Result", "apex.Z")
    b.node("developable.ConicalSurface", "rings_surface", 5, 0, "Conical rings")
    b.wire("ring_circle.Circle", "rings_surface.Curve")
    b.wire("apex.Point", "rings_surface.Apex")
    b.wire("slant.Result", "rings_surface.Height")
    b.wire("segments.Value", "rings_surface.Segments")
    b.node("maths.Expression", "shaft_height", 2, 5, "Shaft height",
           {"expression": "n * h + 2", "variables": ["n", "h"]})
    b.wire("rings.Value", "shaft_height.n")
    b.wire("ring_height.Value", "shaft_height.h")
    b.node("maths.Expression", "shaft_x", 2, 4, "Shaft position",
           {"expression": "-(r + s + 2)", "variables": ["r", "s"]})
    b.wire("radius.Value", "shaft_x.r")
    b.wire("shaft_radius.Value", "shaft_x.s")
    b.node("params.Point", "shaft_centre", 3, 4, "Shaft centre", Y=0.0, Z=0.0)
    b.wire("shaft_x.Result", "shaft_centre.X")
    b.node("curves.Circle", "shaft_circle", 4, 4, "Shaft section")
    b.wire("shaft_centre.Point", "shaft_circle.Plane")
    b.wire("shaft_radius.Value", "shaft_circle.Radius")
    b.node("developable.CylindricalSurface", "shaft", 5, 4, "Elevator shaft")
    b.wire("shaft_circle.Circle", "shaft.Curve")
    b.wire("shaft_height.Result", "shaft.Height")
    b.wire("segments.Value", "shaft.Segments")
    b.group("inputs", "Inputs", INPUTS,
            ["rings", "ring_height", "flare", "radius", "shaft_radius"])
    b.group("rings", "Conical rings", GEOMETRY,
            ["index", "ring_z", "ring_r", "apex_z", "slant", "ring_centre", "ring_circle", "apex",
             "rings_surface", "segments"])
    b.group("shaft", "Cylindrical shaft", RESULT,
            ["shaft_height", "shaft_x", "shaft_centre", "shaft_circle", "shaft"])
    b.save("guggenheim-ny")


def zve_roof_edge() -> None:
    """ZVE roof edge (UNStudio, Stuttgart): the developable between a façade curve and an
    inset top curve whose middle sections are straight lines at an angle: two triangles."""
    b = Builder(
        "ZVE roof edge (after UNStudio, Fraunhofer ZVE Stuttgart), as in the 2011 TU Delft "
        "toolbox case study: the bottom edge lies in the façade, the top edge is set inwards. "
        "A loft between them is not developable; RulingDevelopable finds the torsal rulings. "
        "In the middle both edges are straight lines at an angle, so the only developable "
        "there is two triangles: a fan of rulings through each corner."
    )
    b.slider("inset", 0, "Top inset (m)", 3.0, 1.0, 6.0, 1)
    b.slider("rise", 1, "Top rise (m)", 2.0, 0.5, 4.0, 1)
    b.integer("segments", 31 / 11, "Segments", 40, 4, 200, column=5)  # beside the strip it refines
    bottom = [point(0, 0, 6), point(4, 0, 7.2), point(9, 0, 8), point(21, 0, 8), point(26, 0, 7.2),
              point(30, 0, 6)]
    b.node("curves.Polyline", "bottom", 1, 0, "Façade edge (bottom)", Vertices=bottom)
    # the top edge: each façade point moved in and up by (0, inset, rise) × its factor; in the
    # middle the factors differ, so the two straight middles lie in one plane at an angle
    plan = [point(1, 0, 6), point(5, 0, 7.2), point(11, 0, 8), point(19, 0, 8), point(25, 0, 7.2),
            point(29, 0, 6)]
    b.node("maths.Expression", "lift_y", 1, 1, "Inset per point",
           {"expression": "inset * f", "variables": ["inset", "f"]}, f=[1.0, 1.0, 1.0, 1.45, 1.0, 1.0])
    b.node("maths.Expression", "lift_z", 1, 2, "Rise per point",
           {"expression": "rise * f", "variables": ["rise", "f"]}, f=[1.0, 1.0, 1.0, 1.45, 1.0, 1.0])
    b.wire("inset.Value", "lift_y.inset")
    b.wire("rise.Value", "lift_z.rise")
    b.node("params.Vector", "lift", 2, 1, "Move in and up", X=0.0)
    b.wire("lift_y.Result", "lift.Y")
    b.wire("lift_z.Result", "lift.Z")
    b.node("transform.Move", "top_points", 3, 1, "Top edge points", Geometry=plan)
    b.wire("lift.Vector", "top_points.Motion")
    b.node("curves.Polyline", "top", 4, 1, "Roof edge (top)")
    b.wire("top_points.Geometry", "top.Vertices")
    b.node("developable.RulingDevelopable", "edge", 5, 0, "Developable roof edge", WarpTolerance=0.01)
    b.wire("bottom.Polyline", "edge.CurveA")
    b.wire("top.Polyline", "edge.CurveB")
    b.wire("segments.Value", "edge.Segments")
    b.node("surfaces.RuledSurface", "loft", 5, 2, "Plain loft, for comparison")
    b.wire("bottom.Polyline", "loft.CurveA")
    b.wire("top.Polyline", "loft.CurveB")
    # the developable roof edge and the plain loft share their rims and most of their middle:
    # the loft's preview is off (turn it on to compare)
    b.graph.set_preview("loft", False)
    b.group("inputs", "Inputs", INPUTS, ["inset", "rise"])
    b.group("curves", "Edge curves", GEOMETRY, ["bottom", "lift_y", "lift_z", "lift", "top_points", "top"])
    b.group("surface", "Developable roof edge", RESULT, ["edge", "loft", "segments"])
    b.save("zve-roof-edge")


def _points_from(b: Builder, prefix: str, column: float, row: float, label: str,
                 x: str, y: str, z: str, source: str) -> str:
    """Three Expression nodes in u feeding a Point node: the points (x(u), y(u), z(u))."""
    point_id = f"{prefix}_points"
    b.node("params.Point", point_id, column + 1, row, label)
    for offset, (axis, formula) in enumerate(zip("XYZ", (x, y, z), strict=True)):
        node_id = f"{prefix}_{axis.lower()}"
        b.node("maths.Expression", node_id, column, row + offset * 0.5, f"{label} {axis.lower()}(u)",
               {"expression": formula, "variables": ["u"]})
        b.wire(source, f"{node_id}.u")
        b.wire(f"{node_id}.Result", f"{point_id}.{axis}")
    return point_id


def textbook() -> None:
    """Textbook ruled surfaces: a cylinder, a helicoid and a Möbius strip from their
    equations with ParametricRuledSurface, and SurfaceAnalysis of a hyperbolic paraboloid
    and a torus."""
    b = Builder(
        "Textbook ruled surfaces, S(u, v) = C(u) + v·a(u): a cylinder (developable), a helicoid "
        "and a Möbius strip (ruled but not developable: their warp angles are not zero), each "
        "from its textbook equations. Beside them, SurfaceAnalysis colours a hyperbolic paraboloid "
        "(nowhere single-curved) and a torus (elliptic outside, hyperbolic inside, parabolic on "
        "the top and bottom circles). Select a chart node to read it in the inspector: WarpChart "
        "draws each strip's warp along it against the tolerance (0 on the cylinder), "
        "CurvatureHistogram how the torus's min(|k1|, |k2|) is spread (only the points left of the "
        "tolerance line are single-curved)."
    )
    b.integer("steps", 0, "Rulings - 1", 48, 8, 200)
    b.node("maths.Domain", "turn", 0, 1, "One turn", Start=0.0, End=2 * math.pi)
    b.node("maths.Range", "u", 1, 0, "Parameter u")
    b.wire("turn.Domain", "u.Domain")
    b.wire("steps.Value", "u.Steps")
    rows = {"cylinder": 0.0, "helicoid": 2.0, "mobius": 4.5}
    # side by side along x, 3.5 m apart, so the viewport shows each one on its own
    surfaces = {
        "cylinder": (("cos(u) - 7", "sin(u)", "0"), None, (0.0, 2.0), "Cylinder"),
        "helicoid": (("-3.5", "0", "0.4 * u"), ("cos(u)", "sin(u)", "0"), (-1.0, 1.0), "Helicoid"),
        "mobius": (("cos(u)", "sin(u)", "0"),
                   ("cos(u / 2) * cos(u)", "cos(u / 2) * sin(u)", "sin(u / 2)"), (-0.3, 0.3), "Möbius strip"),
    }
    for name, (directrix, direction, extent, label) in surfaces.items():
        row = rows[name]
        points = _points_from(b, f"{name}_c", 2, row, f"{label} directrix", *directrix, source="u.Range")
        surface = b.node("developable.ParametricRuledSurface", name, 6, row, label,
                         VValues={"type": "Domain", "min": extent[0], "max": extent[1]})
        b.wire(f"{points}.Point", f"{surface}.Directrix")
        b.graph.set_preview(points, False)  # the surface shows its directrix; the dots would clutter
        if direction is None:
            b.node("params.UnitZ", f"{name}_a", 5, row + 1, f"{label} ruling direction")
            b.wire(f"{name}_a.Vector", f"{surface}.Direction")
            b.graph.set_preview(f"{name}_a", False)  # directions, not positions: drawn from the origin
        else:
            vector = f"{name}_a_vectors"
            b.node("params.Vector", vector, 5, row + 1, f"{label} ruling direction")
            for offset, (axis, formula) in enumerate(zip("XYZ", direction, strict=True)):
                node_id = f"{name}_a_{axis.lower()}"
                b.node("maths.Expression", node_id, 4, row + 0.5 + offset * 0.5, f"a_{axis.lower()}(u)",
                       {"expression": formula, "variables": ["u"]})
                b.wire("u.Range", f"{node_id}.u")
                b.wire(f"{node_id}.Result", f"{vector}.{axis}")
            b.wire(f"{vector}.Vector", f"{surface}.Direction")
            b.graph.set_preview(vector, False)
        chart = b.node("analysis.WarpChart", f"{name}_warp", 8, row, f"{label}: warp along the strip",
                       Tolerance=0.01, Title=f"{label}: warp along the strip")
        b.wire(f"{surface}.WarpAngles", f"{chart}.WarpAngles")
        b.wire(f"{surface}.Rulings", f"{chart}.Rulings")
    b.node("surfaces.ParametricSurface", "hypar", 1, 7.5, "Hyperbolic paraboloid z = xy",
           X="u + 3.5", Y="v", Z="u * v", UDomain={"type": "Domain", "min": -1.0, "max": 1.0},
           VDomain={"type": "Domain", "min": -1.0, "max": 1.0})
    b.node("surfaces.Torus", "torus", 1, 9.5, "Torus", MajorRadius=1.5, MinorRadius=0.5,
           Plane={"type": "Plane", "origin": [7.5, 0, 0], "x": [1, 0, 0], "y": [0, 1, 0]})
    for name, source in (("hypar_analysis", "hypar.Surface"), ("torus_analysis", "torus.Torus")):
        b.node("analysis.SurfaceAnalysis", name, 3, 7.5 if name.startswith("hypar") else 9.5,
               "Curvature analysis", UDensity=24, VDensity=24, Scale=0.3,
               CurvatureTolerance=0.01, WarpTolerance=0.01)
        b.wire(source, f"{name}.Surface")
    b.node("analysis.CurvatureHistogram", "torus_histogram", 5, 9.5, "Torus: curvature histogram",
           Measure="min|k|", UDensity=48, VDensity=24, Bins=24, Tolerance=0.01,
           Title="Torus: min(|k1|, |k2|), 1/m")
    b.wire("torus.Torus", "torus_histogram.Surface")
    b.group("parameter", "Parameter u", INPUTS, ["steps", "turn", "u"])
    for name in rows:
        members = [n for n in b.graph.nodes if n.startswith(f"{name}_") or n == name]
        b.group(name, surfaces[name][3], GEOMETRY, members)
    b.group("analysis", "Curvature analysis", RESULT,
            ["hypar", "torus", "hypar_analysis", "torus_analysis", "torus_histogram"])
    b.save("textbook-ruled-surfaces")


def paper_strip() -> None:
    """A paper strip: planar quads folded ruling by ruling; exactly developable by construction."""
    b = Builder(
        "A paper strip (after Lachauer): a strip of flat quads, each next ruling found by turning "
        "the bending direction about the previous one by the local curvature and tilting it by "
        "(90° − iso angle). It is developable by construction; the Development output is the "
        "flat sheet to cut. The curvature follows a wave along the strip."
    )
    b.slider("length", 0, "Length (m)", 6.0, 1.0, 20.0, 1)
    b.slider("width", 1, "Width (m)", 0.6, 0.1, 2.0, 2)
    b.slider("iso", 2, "Iso angle (rad)", 1.5, 0.6, 1.57, 2)
    b.slider("bend", 3, "Bending per segment (rad)", 0.1, 0.0, 0.4, 3)
    b.integer("segments", 4, "Segments", 40, 4, 200)
    b.node("maths.Series", "index", 1, 3, "Segment index", Start=0, Step=1)
    b.wire("segments.Value", "index.Count")
    b.node("maths.Expression", "curvature", 2, 3, "Curvature per segment: a wave",
           {"expression": "b * sin(2 * pi * k / n)", "variables": ["b", "k", "n"]})
    b.wire("bend.Value", "curvature.b")
    b.wire("index.Series", "curvature.k")
    b.wire("segments.Value", "curvature.n")
    # its Development beside the bent strip (Placement 0), not under it
    b.node("developable.PaperStrip", "strip", 3, 0, "Paper strip", Placement=0)
    b.wire("length.Value", "strip.Length")
    b.wire("width.Value", "strip.Width")
    b.wire("iso.Value", "strip.IsoAngle")
    b.wire("curvature.Result", "strip.Curvature")
    b.wire("segments.Value", "strip.Segments")
    # at the origin, preview off: it would lie exactly on the strip's own Development
    b.node("analysis.IsoMapping", "unroll", 4, 0, "Check: unroll it again", Placement=1)
    b.graph.set_preview("unroll", False)
    b.wire("strip.Surface", "unroll.Surface")
    b.wire("segments.Value", "unroll.Segments")
    b.group("inputs", "Inputs", INPUTS, ["length", "width", "iso", "bend", "segments"])
    b.group("strip", "Folded strip", GEOMETRY, ["index", "curvature", "strip"])
    b.group("check", "Unrolled", RESULT, ["unroll"])
    b.save("paper-strip")


def spline_approximation() -> None:
    """SplineApproximation: turn the rulings of a twisted ruled surface about its fixed edge
    until the strip is (nearly) developable, optimised in the node."""
    b = Builder(
        "SplineApproximation with optimisation: a twisted ruled surface between two skew edges is "
        "not developable. Keeping the lower edge fixed, each ruling is turned about the edge "
        "tangent; Optimise finds the angles that minimise the summed warp in a fraction of a "
        "second (the thesis drove the same angles with an evolutionary solver for minutes). "
        "RulingDevelopable then finishes the strip between the fixed edge and the new free edge."
    )
    b.slider("twist", 0, "Twist of the top edge (m)", 1.5, 0.0, 4.0, 2)
    b.integer("segments", 20 / 11, "Segments", 20, 4, 100, column=6)  # beside the approximation
    b.node("params.Toggle", "optimise", 0, 2, "Optimise", {"value": True})
    lower = [point(0, 0, 0), point(3, 0.8, 0), point(6, 0, 0), point(9, -0.8, 0), point(12, 0, 0)]
    upper = [point(0, 0, 3), point(3, 0, 3), point(6, 0, 3), point(9, 0, 3), point(12, 0, 3)]
    b.node("curves.Interpolate", "edge_a", 3, 0, "Fixed edge", Vertices=lower, Degree=3)
    b.node("params.Vector", "skew", 1, 2, "Twist", X=0.0, Z=0.0)
    b.wire("twist.Value", "skew.Y")
    b.node("maths.Expression", "skew_factor", 1, 3, "Twist grows along the edge",
           {"expression": "t * 2 - 1", "variables": ["t"]}, t=[0.0, 0.3, 0.55, 0.8, 1.0])
    b.node("params.Vector", "skew_each", 2, 3, "Twist per point", X=0.0, Z=0.0)
    b.node("maths.Expression", "skew_y", 2, 2, "Twist y",
           {"expression": "w * s", "variables": ["w", "s"]})
    b.wire("twist.Value", "skew_y.w")
    b.wire("skew_factor.Result", "skew_y.s")
    b.wire("skew_y.Result", "skew_each.Y")
    b.node("transform.Move", "upper_points", 3, 1, "Top edge points", Geometry=upper)
    b.wire("skew_each.Vector", "upper_points.Motion")
    b.node("curves.Interpolate", "edge_b", 4, 1, "Twisted top edge", Degree=3)
    b.wire("upper_points.Geometry", "edge_b.Vertices")
    b.node("surfaces.RuledSurface", "twisted", 5, 0, "Twisted ruled surface")
    b.wire("edge_a.Curve", "twisted.CurveA")
    b.wire("edge_b.Curve", "twisted.CurveB")
    b.node("developable.SplineApproximation", "approx", 6, 0, "Spline approximation")
    b.wire("twisted.Surface", "approx.Surface")
    b.wire("edge_a.Curve", "approx.Curve")
    b.wire("segments.Value", "approx.Segments")
    b.wire("optimise.Value", "approx.Optimise")
    b.node("developable.RulingDevelopable", "finish", 7, 0, "Finished developable strip")
    b.wire("edge_a.Curve", "finish.CurveA")
    b.wire("approx.FreeEdge", "finish.CurveB")
    b.wire("segments.Value", "finish.Segments")
    # the first approximation and the finished strip lie within millimetres of each other: the
    # finished strip is shown
    b.graph.set_preview("approx", False)
    b.group("inputs", "Inputs", INPUTS, ["twist", "optimise"])
    b.group("edges", "Twisted ruled surface", GEOMETRY,
            ["edge_a", "skew", "skew_factor", "skew_each", "skew_y", "upper_points", "edge_b", "twisted"])
    b.group("approx", "Approximation", RESULT, ["approx", "finish", "segments"])
    b.save("spline-approximation")


def panels() -> None:
    """IsoMapping + SurfacePatching: unroll a conical façade and map a staggered
    (running-bond) panel pattern onto it, ready for cutting."""
    b = Builder(
        "Development and panels: a conical façade strip is unrolled with IsoMapping (lengths and "
        "area kept), a staggered running-bond pattern (as on the Guggenheim Bilbao) is laid over "
        "the development and clipped to it, and the panels are mapped back onto the 3D surface. "
        "The flat panels, with their IDs, are what goes to the cutter. The value list Development "
        "placement lays the development and the flat panels beside the façade (Beside model); "
        "choose Origin to see them where they were unrolled."
    )
    b.slider("panel_w", 0, "Panel width (m)", 1.2, 0.3, 3.0, 2)
    b.slider("panel_h", 1, "Panel height (m)", 0.6, 0.2, 2.0, 2)
    b.slider("rotation", 2, "Pattern rotation (°)", 0.0, -45.0, 45.0, 1)
    arc = [point(8 * math.cos(a), 8 * math.sin(a), 0.0) for a in (0.0, 0.4, 0.8, 1.2, 1.6)]
    b.node("curves.Interpolate", "base", 1, 0, "Façade base curve", Vertices=arc, Degree=3)
    b.node("developable.ConicalSurface", "facade", 2, 0, "Conical façade", Apex=point(0, 0, 14),
           Height=6.0, Segments=32)
    b.wire("base.Curve", "facade.Curve")
    b.node("analysis.IsoMapping", "unroll", 3, 0, "Development", Segments=32)
    b.wire("facade.Surface", "unroll.Surface")
    b.node("maths.Expression", "offset", 1, 2, "Half a panel",
           {"expression": "w / 2", "variables": ["w"]})
    b.wire("panel_w.Value", "offset.w")
    b.node("patching.StaggeredPattern", "pattern", 2, 2, "Running bond")
    b.wire("panel_w.Value", "pattern.Width")
    b.wire("panel_h.Value", "pattern.Height")
    b.wire("offset.Result", "pattern.Offset")
    b.node("patching.SurfacePatching", "patching", 3, 2, "Panels on the façade", Scale=1.0)
    b.wire("facade.Surface", "patching.Surface")
    b.wire("unroll.Map", "patching.Development")
    b.wire("pattern.Pattern", "patching.Pattern")
    b.wire("pattern.Tile", "patching.Tile")
    b.wire("rotation.Value", "patching.Rotation")
    b.node("params.ValueList", "placement", 0, 3, "Development placement",
           {"items": [{"name": "Beside model", "value": 0}, {"name": "Origin", "value": 1},
                      {"name": "On plane", "value": 2}], "selected": 0})
    b.wire("placement.Value", "unroll.Placement")
    b.wire("placement.Value", "patching.Placement")
    b.group("inputs", "Inputs", INPUTS, ["panel_w", "panel_h", "rotation", "placement"])
    b.group("surface", "Façade and its development", GEOMETRY, ["base", "facade", "unroll"])
    b.group("panels", "Panels", RESULT, ["offset", "pattern", "patching"])
    b.save("development-and-panels")


def rationalise_roof() -> None:
    """Rationalise: a freeform saddle roof as developable strips within a tolerance, unrolled,
    checked for bending and laid out on cut sheets as a 1:50 model."""
    b = Builder(
        "Rationalise a freeform roof: a saddle (anticlastic) roof 10 m across is covered by "
        "developable strips, each within the Tolerance of the design and sharing its boundary "
        "curves exactly with its neighbours. Each strip is unrolled with IsoMapping, checked "
        "against 0.5 mm card with BendingCheck at 1:50, and the developments are scaled to "
        "1:50 and laid out on 2500 × 1250 mm sheets by ExportCutSheet. Export headless with: "
        "torsal run rationalise-roof.graph --export strips.Strips=strips.3dm "
        "--export cut.Layout=roof.dxf"
    )
    b.slider("tolerance", 0, "Tolerance (m)", 0.02, 0.005, 0.1, 3)
    b.integer("max_strips", 1, "Most strips", 40, 1, 120)
    b.slider("model_scale", 2, "Model scale (1:n)", 50.0, 10.0, 200.0, 0)
    b.node("surfaces.ParametricSurface", "design", 1, 0, "Freeform roof (saddle)",
           X="u", Y="v", Z="4 + (u * u - v * v) / 20",
           UDomain={"type": "Domain", "min": -5.0, "max": 5.0},
           VDomain={"type": "Domain", "min": -5.0, "max": 5.0})
    # boundaries along y, on the design: the lifted default (fewer strips) closes each strip's
    # ends with cones, whose apexes BendingCheck reports as bent tighter than card allows
    b.node("developable.Rationalise", "strips", 2, 0, "Developable strips",
           Direction={"type": "Vector", "xyz": [0.0, 1.0, 0.0]})
    b.wire("design.Surface", "strips.Surface")
    b.wire("tolerance.Value", "strips.Tolerance")
    b.wire("max_strips.Value", "strips.MaxStrips")
    b.node("analysis.BendingCheck", "bending", 3, 2, "Bending at 1:50", Material="Card 0.5 mm")
    b.wire("strips.Strips", "bending.Strips")
    b.wire("model_scale.Value", "bending.ModelScale")
    # the developments at the origin (Placement 1), where they were unrolled
    b.node("analysis.IsoMapping", "unroll", 3, 0, "Unrolled strips", Segments=24, Placement=1)
    b.wire("strips.Strips", "unroll.Surface")
    b.node("maths.Expression", "factor", 3, 4, "1 / n", {"expression": "1 / n", "variables": ["n"]})
    b.wire("model_scale.Value", "factor.n")
    b.node("transform.Scale", "model", 4, 0, "Scaled to the model", Centre=point(0, 0, 0))
    b.wire("unroll.Development", "model.Geometry")
    b.wire("factor.Result", "model.Factor")
    b.node("io.ExportCutSheet", "cut", 5, 0, "Cut sheets (mm)", Path="out/rationalised-roof.dxf",
           SheetWidth=2500.0, SheetHeight=1250.0, Gap=10.0, Kerf=0.0, TextHeight=12.0, Units="m",
           Nesting="Shelf", Write=False)
    b.wire("model.Geometry", "cut.Surfaces", ["flatten"])
    for flat in ("unroll", "model", "cut"):  # the flat parts are for the cutter, not the 3D view
        b.graph.set_preview(flat, False)
    b.group("inputs", "Inputs", INPUTS, ["tolerance", "max_strips", "model_scale"])
    b.group("surface", "Design and its strips", GEOMETRY, ["design", "strips"])
    b.group("fabrication", "Unrolled, checked, laid out", RESULT,
            ["bending", "unroll", "factor", "model", "cut"])
    b.save("rationalise-roof")


def rationalise_canopy() -> None:
    """Rationalise a design brought from Rhino: canopy.3dm (tools/build_design_3dm.py)."""
    b = Builder(
        "Rationalise a design drawn in Rhino: canopy.3dm, beside this graph, holds a canopy "
        "12 × 8 m as one NURBS surface in millimetres. Import3dm reads it into metres (the path "
        "is relative to this graph's folder, with or without --out), Rationalise covers it with "
        "developable strips within the Tolerance, and Export3dm writes them back for Rhino face "
        "by face along their rulings (set its Write to true, or: torsal run "
        "rationalise-canopy.graph --allow-writes --set export.Write=true)."
    )
    b.slider("tolerance", 0, "Tolerance (m)", 0.02, 0.005, 0.1, 3)
    b.integer("max_strips", 1, "Most strips", 40, 1, 120)
    b.node("io.Import3dm", "design", 1, 0, "Design from Rhino", Path="canopy.3dm", Units="m")
    b.node("developable.Rationalise", "strips", 2, 0, "Developable strips")
    b.wire("design.Surfaces", "strips.Surface")
    b.wire("tolerance.Value", "strips.Tolerance")
    b.wire("max_strips.Value", "strips.MaxStrips")
    b.node("io.Export3dm", "export", 3, 0, "Strips to Rhino", Path="out/canopy-strips.3dm",
           Layer="Torsal", Units="m", Write=False)
    b.wire("strips.Strips", "export.Surfaces")
    b.wire("strips.Rulings", "export.Rulings")
    b.graph.set_preview("design", False)
    b.group("inputs", "Inputs", INPUTS, ["tolerance", "max_strips"])
    b.group("surface", "Design and its strips", GEOMETRY, ["design", "strips"])
    b.group("out", "Back to Rhino", RESULT, ["export"])
    b.save("rationalise-canopy")


EXAMPLES: dict[str, Callable[[], None]] = {
    "kaohsiung-stadium": kaohsiung,
    "kaohsiung-cut-sheets": kaohsiung_cut_sheets,
    "guggenheim-ny": guggenheim,
    "zve-roof-edge": zve_roof_edge,
    "textbook-ruled-surfaces": textbook,
    "paper-strip": paper_strip,
    "spline-approximation": spline_approximation,
    "development-and-panels": panels,
    "rationalise-roof": rationalise_roof,
    "rationalise-canopy": rationalise_canopy,
}

if __name__ == "__main__":
    for name in sys.argv[1:] or list(EXAMPLES):
        EXAMPLES[name]()

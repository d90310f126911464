"""The ``torsal`` command: solve graphs headless, check them, list nodes, open the app.

    torsal --version
    torsal run (FILE.graph | --example NAME) [--set ID=VALUE ...] [--json] [--out DIR]
               [--export ID.PORT=PATH ...] [--allow-writes]
        (--set CLUSTER/ID=VALUE sets a node inside a cluster: CLUSTER is an instance's id or its
        definition's id; the definition is shared, so every instance of it gets the value)
    torsal check (FILE.graph | --example NAME)
    torsal nodes [--json]
    torsal sweep FILE.graph --vary ID=LO:HI:N ... --collect NODE.OUTPUT ... --out DIR  (see app/explore)
    torsal optimise FILE.graph --vary ID=LO:HI ... (--minimise | --maximise) NODE.OUTPUT ...
    torsal examples
    torsal gui [FILE.graph | --example NAME]

Exit codes: 0 every node ok or in warning; 1 at least one node in error; 2 the file or
the command line could not be used (the reason on stderr, never a traceback).
Only ``gui`` imports Qt or VTK.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from pathlib import Path

from torsal.app.headless import Run, UsageError


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    try:
        if args.command in _LOADING_NODES:
            from torsal.app.plugins import report_problems

            # a broken plug-in, or one refused, is said by every command, once; torsal gui
            # opens its window with the registry they were found in
            args.registry = report_problems()
        return args.handler(args)
    except UsageError as exc:
        print(f"torsal: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("torsal: interrupted", file=sys.stderr)
        return 2
    except BrokenPipeError:
        return 0


#: The commands that load node types (and so plug-ins).
_LOADING_NODES = frozenset({"run", "check", "nodes", "sweep", "optimise", "gui"})


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="torsal",
        description="Design with developable surfaces: solve node graphs headless or open the app.",
    )
    parser.add_argument("--version", action="version", version=f"torsal {_version()}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")

    run = commands.add_parser("run", help="solve a .graph file and report its results")
    run.add_argument("file", type=Path, nargs="?", help="the .graph file")
    run.add_argument("--example", metavar="NAME", help="solve one of the examples (see torsal examples)")
    run.add_argument("--set", action="append", default=[], metavar="ID=VALUE",
                     help="override a slider/toggle/panel value (height=4.5) or an input (cyl.Segments=48); "
                     "inside a cluster, CLUSTER/ID=VALUE (CLUSTER: an instance's or its definition's id; "
                     "deeper: A/B/ID): it changes the definition, so every instance of it")
    run.add_argument("--json", action="store_true", help="print the results as one JSON object")
    run.add_argument("--verbose", "-v", action="store_true",
                     help="also print how long each node took (slowest first)")
    run.add_argument("--out", type=Path, metavar="DIR",
                     help="also write results.json into DIR; the graph's own file nodes write into DIR too")
    run.add_argument("--allow-writes", action="store_true",
                     help="let the graph's file nodes (ExportCSV, Export3dm, ExportCutSheet, ExportMesh) "
                     "write their files, inside the graph's folder (or DIR of --out) only")
    run.add_argument("--export", action="append", default=[], metavar="ID.PORT=PATH",
                     help="write one output to PATH: .json/.csv (data), .3dm, .dxf/.svg (cut sheets), "
                     ".obj/.stl/.ply/.glb")
    run.add_argument("--nesting-time", type=float, metavar="S",
                     help="answer with row layouts at once, then nest TrueShape cut sheets for at most S "
                     "seconds in all, keeping the best found (default: each node's TimeBudget, in steps)")
    run.add_argument("--preview", action="store_true",
                     help="with --export of cut sheets (.dxf/.svg), also write a PNG of each sheet beside it")
    run.set_defaults(handler=_run)

    check = commands.add_parser("check", help="parse and validate a .graph file without solving")
    check.add_argument("file", type=Path, nargs="?")
    check.add_argument("--example", metavar="NAME", help="check one of the examples (see torsal examples)")
    check.set_defaults(handler=_check)

    nodes = commands.add_parser("nodes", help="list the node catalogue")
    nodes.add_argument("--json", action="store_true", help="types, ports and help as JSON")
    nodes.set_defaults(handler=_nodes)

    from torsal.app.explore.commands import add_commands as add_exploration

    add_exploration(commands)  # torsal sweep, torsal optimise

    examples = commands.add_parser("examples", help="list the example graphs that ship with Torsal")
    examples.set_defaults(handler=_examples)

    gui = commands.add_parser("gui", help="open the desktop app")
    gui.add_argument("file", type=Path, nargs="?", help="a .graph file to open")
    gui.add_argument("--example", metavar="NAME", help="open one of the examples (see torsal examples)")
    gui.set_defaults(handler=_gui)
    return parser


def _version() -> str:
    import torsal

    return torsal.__version__


def _run(args: argparse.Namespace) -> int:
    from torsal.app.examples import choose
    from torsal.app.exports import ExportError, export_tree
    from torsal.app.headless import run_file, summary
    from torsal.app.results_folder import out_folder, write_results

    args.file = choose(args.file, args.example, "run")
    out = out_folder(args.out) if args.out is not None else None  # resolved once; a link is refused
    from torsal.app.progress import reporting

    if args.nesting_time is not None and not (args.nesting_time >= 0 and math.isfinite(args.nesting_time)):
        raise UsageError(f"--nesting-time must be a number of seconds from 0, not {args.nesting_time:g}")
    with reporting(sys.stderr) as node_progress:  # rich's line on a terminal, else a heartbeat
        run = run_file(args.file, args.set, allow_writes=args.allow_writes, write_folder=out,
                       node_progress=node_progress, anytime=args.nesting_time is not None)
        if args.nesting_time is not None:  # the background searches, for at most that long
            from torsal.engine.improve import run_improvements

            run_improvements(run.solver, args.nesting_time, node_progress=node_progress)
    for note in run.notes:
        print(f"torsal: note: {note}", file=sys.stderr)
    for request in args.export:
        target, sep, destination = request.partition("=")
        node_id, dot, port = target.partition(".")
        if not (sep and dot and destination):
            raise UsageError(f"--export wants ID.PORT=PATH, not {request!r}")
        if node_id not in run.graph.nodes:
            raise UsageError(f"--export {request}: there is no node with id {node_id!r}")
        result = run.solver.result(node_id)
        if port not in result.outputs:
            raise UsageError(f"--export {request}: {node_id!r} has no output {port!r}")
        try:
            written = export_tree(result.outputs[port], Path(destination), units=run.graph.units,
                                  preview=args.preview)
        except (ExportError, OSError) as exc:
            raise UsageError(f"--export {request}: {exc}") from None
        run.exported += written
        if not args.json:
            for file in written:
                print(f"wrote {file}")
    data = run.to_json() if (args.out or args.json) else None
    if out is not None:
        write_results(out, "results.json", json.dumps(data, indent=2) + "\n")
    if args.json:
        print(json.dumps(data, indent=2))
    else:
        print(summary(run))
        if args.verbose:
            print(_timings(run))
    return run.exit_code


def _timings(run: Run) -> str:
    """Per-node solve times, slowest first: ``  12.345 ms  ok       id  (type)``."""
    rows = sorted(((run.solver.result(node_id), node_id, record.type_id)
                   for node_id, record in run.graph.nodes.items()), key=lambda row: -row[0].seconds)
    lines = [f"per-node time ({len(rows)} nodes, solve {run.report.seconds * 1000:.3f} ms):"]
    lines += [f"  {result.seconds * 1000:10.3f} ms  {result.state:8s} {node_id}  ({type_id})"
              for result, node_id, type_id in rows]
    return "\n".join(lines)


def _check(args: argparse.Namespace) -> int:
    from torsal.app.examples import choose
    from torsal.app.headless import open_graph
    from torsal.engine.graphfile import GraphFileError

    args.file = choose(args.file, args.example, "check")
    try:
        graph, _ = open_graph(args.file)
    except GraphFileError as exc:
        raise UsageError(f"{args.file}: {exc}") from None
    from torsal.engine.cluster import reachable_definitions

    definitions = reachable_definitions(graph)  # a type not installed was refused by open_graph (exit 2)
    clusters = f", {len(definitions)} cluster definition{'s' if len(definitions) != 1 else ''}"
    from torsal.app.budget_check import check_budget

    budget = check_budget(graph)  # the calls a solve would make, counted without the long work
    for refusal in budget.refusals:
        print(f"torsal: {args.file}: too many calls: {refusal}", file=sys.stderr)
    if budget.refusals:
        return 2
    print(f"{args.file}: valid — {len(graph.nodes)} nodes, {len(graph.wires)} wires, "
          f"{len(graph.groups)} groups{clusters if definitions else ''}; {budget.summary()}")
    return 0


def _nodes(args: argparse.Namespace) -> int:
    from torsal.engine.registry import provider
    from torsal.nodes.catalogue import default_registry

    registry = default_registry()  # its problems were reported by main
    if args.json:  # a plug-in's types say which package provides them
        entries = [cls.catalogue_entry() for cls in registry]
        for cls, entry in zip(registry, entries, strict=True):
            if provider(cls):
                entry["plugin"] = provider(cls)
        print(json.dumps(entries, indent=2))
        return 0
    for cls in registry:
        summary_line = cls.help().splitlines()[0] if cls.help() else ""
        print(f"{cls.type_id:40s} {summary_line}")
    return 0


def has_display() -> bool:
    if sys.platform.startswith("linux"):
        return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    return True


def _examples(args: argparse.Namespace) -> int:
    from torsal.app import examples

    for name in examples.names():
        text = examples.description(name).split(". ")[0]
        print(f"{name:26s} {examples.path(name)}")
        print(f"{'':26s} {text if len(text) <= 90 else text[:89] + '…'}")
    return 0


def _gui(args: argparse.Namespace) -> int:
    from torsal.app import examples
    from torsal.app.headless import run_file, summary

    # neither: a blank document
    file = examples.choose(args.file, args.example, "gui") if args.file or args.example else None
    if not has_display():
        if file is None:
            print("No display found (DISPLAY is not set), and no FILE to solve headless.")
            return 2
        print(f"No display found (DISPLAY is not set): solving {file} headless instead.")
        run = run_file(file)
        print(summary(run))
        return run.exit_code
    from torsal.app.gui.availability import Unavailable
    from torsal.app.gui.main import launch
    from torsal.app.install import install_command

    try:
        return launch(file, args.registry)
    except Unavailable as reason:
        print(f"torsal: the desktop app cannot start: {reason}.\n"
              f"        Install it with: {install_command('gui')}\n"
              f"        (or solve the graph headless: torsal run {file or 'FILE.graph'})", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

"""The ``torsal sweep`` and ``torsal optimise`` subcommands (parsers and handlers).

Only argparse is imported at module level: ``torsal --help`` stays quick.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from torsal.app.headless import UsageError

if TYPE_CHECKING:
    from torsal.engine.write_path import OutFolder

SWEEP_USAGE = (
    "torsal sweep FILE --vary ID=LO:HI:N [--vary ...] [--sampler grid|lhs|sobol --samples N] "
    "--collect NODE.OUTPUT [--collect ...] --out DIR [--workers N | --scheduler ADDRESS] [--seed S] "
    "[--images]"
)
OPTIMISE_USAGE = (
    "torsal optimise FILE --vary ID=LO:HI [--vary ...] (--minimise | --maximise) NODE.OUTPUT [...] "
    "[--budget N] [--seed S] [--json] [--workers N | --scheduler ADDRESS]"
)


class _Objective(argparse.Action):
    """``--minimise A.X B.Y --maximise C.Z``: objectives in the order given, each with its sense."""

    def __call__(self, parser, namespace, values, option_string=None):
        sense = -1 if option_string == "--maximise" else 1
        objectives = list(getattr(namespace, "objectives", None) or [])
        objectives.extend((sense, value) for value in values)
        namespace.objectives = objectives


def _workers(parser: argparse.ArgumentParser) -> None:
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, metavar="N",
                       help="N local worker processes, one thread each (default: the machine's cores)")
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="a running dask.distributed scheduler, e.g. tcp://10.0.0.5:8786")


def add_commands(commands: argparse._SubParsersAction) -> None:
    """Add ``sweep`` and ``optimise`` to the ``torsal`` command."""
    sweep = commands.add_parser("sweep", help="solve many variants and write a Design Explorer CSV",
                                usage=SWEEP_USAGE)
    sweep.add_argument("file", type=Path, help="the .graph file")
    sweep.add_argument("--vary", action="append", default=[], metavar="ID=LO:HI:N",
                       help="a slider and its range (N steps for a grid; ID=LO:HI with lhs/sobol)")
    sweep.add_argument("--sampler", choices=("grid", "lhs", "sobol"), default="grid")
    sweep.add_argument("--samples", type=int, metavar="N", help="how many variants lhs/sobol draw")
    sweep.add_argument("--collect", action="append", default=[], metavar="NODE.OUTPUT",
                       help="an output to record (NODE.OUTPUT:mean|sum|min|max|count for several items)")
    sweep.add_argument("--out", type=Path, metavar="DIR",
                       help="folder for results.csv, Design Explorer's data.csv and the cache")
    sweep.add_argument("--seed", type=int, default=0, metavar="S", help="seed of lhs/sobol (default 0)")
    sweep.add_argument("--allow-writes", action="store_true",
                       help="let the graph's file nodes write, variant N into DIR/variants/N only")
    sweep.add_argument("--images", action="store_true",
                       help="draw each variant's previewed geometry into DIR/N.png and add "
                            "Design Explorer's img column")
    _workers(sweep)
    sweep.set_defaults(handler=_sweep)

    optimise = commands.add_parser(
        "optimise", help="find the slider values that minimise or maximise outputs", usage=OPTIMISE_USAGE
    )
    optimise.add_argument("file", type=Path, help="the .graph file")
    optimise.add_argument("--vary", action="append", default=[], metavar="ID=LO:HI",
                          help="a slider (gene) and the range searched")
    optimise.add_argument("--minimise", action=_Objective, nargs="+", metavar="NODE.OUTPUT",
                          help="an output to make as small as possible")
    optimise.add_argument("--maximise", action=_Objective, nargs="+", metavar="NODE.OUTPUT",
                          help="an output to make as large as possible")
    optimise.add_argument("--budget", type=int, default=400, metavar="N",
                          help="at most N evaluations (default 400)")
    optimise.add_argument("--seed", type=int, default=0, metavar="S", help="seed (default 0)")
    optimise.add_argument("--method", choices=("cma", "de"), default="cma",
                          help="one objective: CMA-ES (default) or differential evolution")
    optimise.add_argument("--json", action="store_true", help="print the result as one JSON object")
    optimise.add_argument("--out", type=Path, metavar="DIR",
                          help="write DIR/evaluations.csv (and DIR/front.csv for several objectives)")
    _workers(optimise)
    optimise.set_defaults(handler=_optimise, objectives=None)


def _folder(out: Path, flag: str = "--out") -> OutFolder:
    """``--out`` resolved once: created if missing, refused if it is a link or a file."""
    from torsal.engine.write_path import OutFolder

    try:
        return OutFolder.resolve(out, flag)
    except OSError as exc:
        raise UsageError(str(exc)) from None


def _sweep(args: argparse.Namespace) -> int:
    from torsal.app.explore.option_bounds import bounded_executor, check_count, check_seed, grid_size
    from torsal.app.explore.progress import Progress
    from torsal.app.explore.samplers import sample
    from torsal.app.explore.study import open_study
    from torsal.app.explore.sweep import run_sweep

    grid = args.sampler == "grid"
    if grid and args.samples is not None:
        raise UsageError("--samples is for --sampler lhs or sobol; a grid has N steps per --vary")
    if not grid and (args.samples is None or args.samples < 1):
        raise UsageError(f"--sampler {args.sampler} needs --samples N (1 or more)")
    if args.out is None:
        raise UsageError("give --out DIR: the folder for results.csv")
    check_seed(args.seed)
    study = open_study(args.file, args.vary, args.collect, steps=grid)
    count = grid_size([v.steps for v in study.variables]) if grid else args.samples
    check_count(count, "the grid" if grid else f"--samples {args.samples}")
    variants = sample(study.variables, args.sampler, args.samples or 0, args.seed)
    out = _folder(args.out)
    progress = Progress("sweep", len(variants))
    try:
        with bounded_executor(args.workers, args.scheduler, len(variants)) as executor:
            result = run_sweep(study, variants, executor, out, allow_writes=args.allow_writes,
                               images=args.images, progress=progress)
    except OSError as exc:  # a read-only or full --out, a link planted in it: one line, exit 2
        raise UsageError(f"--out {out.path}: {exc.strerror or exc}") from None
    for note in result.notes:
        print(f"torsal: note: {note}", file=sys.stderr)
    print(f"{args.file}: {len(result.outcomes)} variants — {result.solved} solved, {result.cached} from "
          f"the cache, {result.failed} in error → {result.csv_path}")
    return 1 if result.failed else 0


def _optimise(args: argparse.Namespace) -> int:
    from torsal.app.explore.optimise import optimise
    from torsal.app.explore.option_bounds import bounded_executor, check_count, check_seed
    from torsal.app.explore.progress import Progress
    from torsal.app.explore.report import write_evaluations, write_front
    from torsal.app.explore.study import open_study

    if not args.objectives:
        raise UsageError("give --minimise NODE.OUTPUT or --maximise NODE.OUTPUT")
    if args.budget < 1:
        raise UsageError(f"--budget {args.budget}: give 1 or more evaluations")
    check_count(args.budget, f"--budget {args.budget}")
    check_seed(args.seed)
    names = [name for _, name in args.objectives]
    flag = "--minimise" if args.objectives[0][0] == 1 else "--maximise"
    study = open_study(args.file, args.vary, names, steps=False, collect_flag=flag)
    out = _folder(args.out) if args.out is not None else None
    senses = [sense for sense, _ in args.objectives]
    progress = Progress("optimise", args.budget)
    with bounded_executor(args.workers, args.scheduler, args.budget) as executor:
        result = optimise(study, executor, senses, budget=args.budget, seed=args.seed, method=args.method,
                          progress=progress)
    progress.stream.write("\n" if progress.tty else "")
    if out is not None:
        try:
            write_evaluations(out, "evaluations.csv", study, result)
            if len(senses) > 1:
                write_front(out, "front.csv", study, result)
        except OSError as exc:
            raise UsageError(f"--out {out.path}: {exc.strerror or exc}") from None
    if args.json:
        print(json.dumps(result.to_json(study, args.seed), indent=2))
    elif len(senses) == 1:
        best = result.best
        if best is None:
            print(f"{args.file}: no feasible variant in {result.evaluations} evaluations")
        else:
            values = ", ".join(f"{k}={v!r}" for k, v in best.values.items())
            print(f"{args.file}: best {values} → {names[0]} = {best.objectives[0]!r} "
                  f"({result.evaluations} evaluations, {result.method}, seed {args.seed})")
    else:
        print(f"{args.file}: a front of {len(result.front)} designs in {result.evaluations} evaluations "
              f"(nsga2, seed {args.seed})" + (f" → {out / 'front.csv'}" if out else ""), file=sys.stdout)
    found = result.best is not None if len(senses) == 1 else bool(result.front)
    return 0 if found else 1

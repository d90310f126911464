"""Fuzzing the ``.3dm`` reader: seeded byte mutants of valid Rhino files, read as Import3dm reads.

The seed files are made here with rhino3dm (curves of every kind, a NURBS surface, a brep
and a trimmed planar brep, an extrusion, a mesh, on layers, in millimetres). Each mutant
changes one of them as a damaged download or a hostile file would: bytes flipped, a run
overwritten with 0x00 or 0xFF, bytes inserted or deleted, a chunk repeated, the file cut
short. Every mutant is read by :func:`torsal.nodes.io.formats.threedm_read.read_3dm`, whose
rhino3dm runs in a fenced child process (:mod:`torsal.nodes.io.formats.fenced`).

The rule: this process survives every mutant, and each read either returns the file's
geometry or raises a :class:`FileFailure` with a sentence naming the file (a crash of the
reader is one of those: "could not read FILE: the reader crashed (SIGSEGV)"). Any other
exception is a failure, and the mutant is kept in ``--out`` to be read again.

``python -m tools.fuzz_3dm --mutants 5000 --seed 0`` (``make fuzz``); ``--readers N`` reads
with N children side by side.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import uuid
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import rhino3dm as rh

from torsal.nodes.common.files import FileFailure
from torsal.nodes.io.formats import threedm_read
from torsal.nodes.io.formats.fenced import FencedReader

#: How one mutant changes its seed file.
MUTATIONS = ("flip", "overwrite", "insert", "delete", "repeat", "truncate")


def _attributes(number: int, layer: int = 0, name: str = "") -> rh.ObjectAttributes:
    """Attributes with a fixed id (rhino3dm would draw a random one: the bytes would differ)."""
    attributes = rh.ObjectAttributes()
    attributes.Id = uuid.UUID(int=number)
    attributes.LayerIndex, attributes.Name = layer, name
    return attributes


def seed_files(folder: Path) -> list[Path]:
    """Valid .3dm files, made with rhino3dm, holding every kind Import3dm reads; the same
    bytes on every run (fixed ids, bare file names) but for the time stamp openNURBS writes
    near the start, so a seed's mutants are the same but for those bytes."""
    folder.mkdir(parents=True, exist_ok=True)
    files = []
    curves = rh.File3dm()
    curves.Settings.ModelUnitSystem = rh.UnitSystem.Millimeters
    layer = rh.Layer()
    layer.Name, layer.Id = "Edges", uuid.UUID(int=1)
    index = curves.Layers.Add(layer)
    curves.Objects.AddLine(rh.Point3d(0, 0, 0), rh.Point3d(1000, 0, 0), _attributes(2, index, "edge"))
    curves.Objects.AddPolyline([rh.Point3d(0, 0, 0), rh.Point3d(500, 300, 0), rh.Point3d(900, 100, 50)],
                               _attributes(3))
    curves.Objects.AddCircle(rh.Circle(rh.Point3d(0, 0, 0), 250.0), _attributes(4))
    curves.Objects.AddArc(rh.Arc(rh.Point3d(0, 0, 0), rh.Point3d(100, 100, 0), rh.Point3d(200, 0, 0)),
                          _attributes(5))
    surfaces = rh.File3dm()
    surfaces.Settings.ModelUnitSystem = rh.UnitSystem.Meters
    shell = rh.Layer()
    shell.Name, shell.Id = "Shell", uuid.UUID(int=11)
    surfaces.Layers.Add(shell)
    grid = rh.NurbsSurface.Create(3, True, 4, 3, 5, 4)
    for i in range(5):
        for j in range(4):
            grid.Points[(i, j)] = rh.Point4d(i, j, np.sin(i) * np.cos(j), 1.0 + 0.1 * (i + j))
    for k in range(len(grid.KnotsU)):
        grid.KnotsU[k] = min(max(k - 2, 0), 2)
    for k in range(len(grid.KnotsV)):
        grid.KnotsV[k] = min(max(k - 1, 0), 2)
    surfaces.Objects.AddSurface(grid, _attributes(6))
    surfaces.Objects.AddBrep(rh.Brep.CreateFromSurface(grid), _attributes(7))
    disc = rh.Circle(rh.Point3d(0, 0, 0), 2.0).ToNurbsCurve()
    surfaces.Objects.AddBrep(rh.Brep.CreateTrimmedPlane(rh.Plane.WorldXY(), disc), _attributes(8))
    surfaces.Objects.AddExtrusion(rh.Extrusion.Create(disc, 3.0, True), _attributes(9))
    mesh = rh.Mesh()
    for x, y, z in ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0.5)):
        mesh.Vertices.Add(x, y, z)
    mesh.Faces.AddFace(0, 1, 2, 3)
    mesh.Faces.AddFace(0, 2, 3)
    surfaces.Objects.AddMesh(mesh, _attributes(10))
    here = os.getcwd()
    os.chdir(folder)  # rhino3dm stores the path it is given: a bare name makes the same bytes anywhere
    try:
        for name, model in (("curves.3dm", curves), ("surfaces.3dm", surfaces)):
            if not model.Write(name, 7):
                raise RuntimeError(f"rhino3dm could not write the seed file {folder / name}")
            files.append(folder / name)
    finally:
        os.chdir(here)
    return files


def mutate(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    """One seeded mutant of ``data`` and the name of its mutation."""
    kind = MUTATIONS[int(rng.integers(len(MUTATIONS)))]
    buffer = bytearray(data)
    size = len(buffer)
    at = int(rng.integers(size))
    if kind == "flip":
        for spot in rng.integers(0, size, int(rng.integers(1, 9))):
            buffer[int(spot)] ^= 1 << int(rng.integers(8))
    elif kind == "overwrite":
        run = int(rng.integers(1, 64))
        buffer[at:at + run] = bytes([0xFF if rng.random() < 0.5 else 0x00]) * len(buffer[at:at + run])
    elif kind == "insert":
        buffer[at:at] = rng.integers(0, 256, int(rng.integers(1, 64)), dtype=np.uint8).tobytes()
    elif kind == "delete":
        del buffer[at:at + int(rng.integers(1, 64))]
    elif kind == "repeat":
        run = int(rng.integers(1, 256))
        buffer[at:at] = buffer[at:at + run]
    else:
        del buffer[max(32, at):]
    return bytes(buffer), kind


@dataclass
class Report:
    """What a fuzz run saw: outcomes by kind, and the mutants that broke the rule."""

    mutants: int = 0
    outcomes: Counter[str] = field(default_factory=Counter)
    failures: list[tuple[Path, str]] = field(default_factory=list)
    seconds: float = 0.0

    def summary(self) -> str:
        counts = ", ".join(f"{n} {kind}" for kind, n in sorted(self.outcomes.items()))
        return (f"{self.mutants} .3dm mutants in {self.seconds:.1f} s: {counts}; "
                f"{len(self.failures)} broke the rule")


def read_one(path: Path, fence: FencedReader) -> str:
    """How reading ``path`` ended: "read", "refused", "crashed" or "timed out" (refusals that
    say the reader crashed or took too long), or raises whatever unexpected exception came."""
    try:
        threedm_read.read_3dm(path, "m", fence=fence)
    except FileFailure as exc:
        text = str(exc)
        if path.name not in text:
            raise AssertionError(f"the refusal does not name the file: {text}") from None
        return "crashed" if "crashed" in text else "timed out" if "took longer" in text else "refused"
    return "read"


def fuzz(mutants: int, seed: int = 0, folder: Path | None = None, readers: int = 1,
         seconds: float = 5.0) -> Report:
    """Read ``mutants`` seeded mutants with ``readers`` fenced children; the report."""
    work = Path(tempfile.mkdtemp(prefix="torsal-fuzz-3dm-")) if folder is None else folder
    seeds = [path.read_bytes() for path in seed_files(work / "seeds")]
    rng = np.random.default_rng(seed)
    fences = [FencedReader(threedm_read.CHILD, seconds=seconds) for _ in range(max(1, readers))]
    report = Report()
    start = time.perf_counter()

    def job(k: int, data: bytes, kind: str) -> tuple[int, str, Path, str]:
        path = work / "mutants" / f"{k:05d}-{kind}.3dm"
        path.write_bytes(data)
        try:
            outcome, problem = read_one(path, fences[k % len(fences)]), ""
        except Exception as exc:  # the rule is broken: keep the mutant, say how
            outcome, problem = "failed", f"{type(exc).__name__}: {exc}"
        if not problem:
            path.unlink()
        return k, outcome, path, problem

    (work / "mutants").mkdir(parents=True, exist_ok=True)
    made = [mutate(seeds[k % len(seeds)], rng) for k in range(mutants)]
    try:
        with ThreadPoolExecutor(len(fences)) as pool:
            for _, outcome, path, problem in pool.map(lambda a: job(a[0], *a[1]), enumerate(made)):
                report.mutants += 1
                report.outcomes[outcome] += 1
                if problem:
                    report.failures.append((path, problem))
    finally:
        for fence in fences:
            fence.close()
    report.seconds = time.perf_counter() - start
    return report


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mutants", type=int, default=5000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--readers", type=int, default=2, help="fenced children reading side by side")
    parser.add_argument("--out", type=Path, default=None, help="where to keep failing mutants")
    args = parser.parse_args(argv)
    report = fuzz(args.mutants, args.seed, args.out, args.readers)
    print(report.summary())
    for path, problem in report.failures[:20]:
        print(f"  {path}: {problem}")
    return 1 if report.failures else 0


if __name__ == "__main__":
    sys.exit(main())

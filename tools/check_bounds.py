"""Install the lowest versions pyproject.toml allows in a scratch venv and import every module.

    .venv/bin/python -m tools.check_bounds [--keep DIR] [--gui]

Each ``name>=X`` in ``[project] dependencies`` becomes ``name==X`` (``--gui`` adds the
``gui`` extra's lower bounds: then app/gui is imported too, and the app is opened on an
example until its 3D viewport is ready); the project is installed
from this checkout into a new venv under the temporary folder with those pins as
constraints — without extras, as a headless install — then every module of engine/,
nodes/ and app/ is imported there, every example graph is solved with ``torsal run`` and
a few outputs are exported (CSV, JSON, 3dm, OBJ, DXF, SVG). Exit 0 when all of that
worked. It downloads the old wheels, so it takes minutes: ``make check-bounds`` runs it,
``make test`` does not (``TORSAL_CHECK_BOUNDS=1`` makes tests/test_packaging.py run it).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("torsal.engine", "torsal.nodes", "torsal.app")

_IMPORT_ALL = r"""
import importlib, pkgutil, sys, traceback
skip_gui = {skip_gui!r}
failed = 0
count = 0
for top in {packages!r}:
    package = importlib.import_module(top)
    names = [top] + [m.name for m in pkgutil.walk_packages(package.__path__, top + ".")]
    for name in names:
        if skip_gui and name.startswith("torsal.app.gui"):
            continue
        count += 1
        try:
            importlib.import_module(name)
        except Exception:
            failed += 1
            print("FAILED", name)
            traceback.print_exc(limit=2)
print(f"imported {{count - failed}} of {{count}} modules")
sys.exit(1 if failed else 0)
"""


def lower_bounds(extras: tuple[str, ...] = ()) -> list[str]:
    """``name==X`` for every ``name>=X`` requirement (extras of a requirement dropped)."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    requirements = list(project["dependencies"])
    for extra in extras:
        requirements += project["optional-dependencies"][extra]
    pins = []
    for requirement in requirements:
        match = re.match(r"^\s*([A-Za-z0-9_.-]+)(\[[^\]]*\])?\s*>=\s*([^,;\s]+)", requirement)
        if match is None:
            continue  # e.g. "torsal[gui]", or a requirement without a lower bound
        pins.append(f"{match.group(1)}=={match.group(3)}")
    return pins


def _step(title: str, command: list[str], **kwargs: object) -> subprocess.CompletedProcess[str]:
    start = time.perf_counter()
    print(f"-- {title}", flush=True)
    done = subprocess.run(command, text=True, capture_output=True, **kwargs)  # type: ignore[call-overload]
    print(done.stdout[-4000:], end="")
    if done.returncode:
        print(done.stderr[-4000:], end="")
    print(f"   ({time.perf_counter() - start:.0f} s, exit {done.returncode})", flush=True)
    return done


def check(folder: Path, gui: bool = False) -> int:
    """Build the venv in ``folder`` and run the checks; returns the number of failed steps."""
    pins = lower_bounds(("gui",) if gui else ())
    constraints = folder / "lower-bounds.txt"
    constraints.write_text("\n".join(pins) + "\n", encoding="utf-8")
    print("lower bounds:", " ".join(pins))
    python = folder / "venv" / "bin" / "python"
    failures = 0
    if _step("venv", [sys.executable, "-m", "venv", str(folder / "venv")]).returncode:
        return 1
    target = f"{ROOT}[gui]" if gui else str(ROOT)
    install = _step("install", [str(python), "-m", "pip", "install", "--quiet", "--no-cache-dir",
                                "-c", str(constraints), target])
    if install.returncode:
        return 1
    _step("installed versions", [str(python), "-m", "pip", "list", "--format=freeze"])
    code = _IMPORT_ALL.format(packages=PACKAGES, skip_gui=not gui)
    # From a folder outside the checkout, so the modules come from the installed wheel.
    failures += bool(_step("import every module", [str(python), "-c", code], cwd=folder).returncode)
    torsal = folder / "venv" / "bin" / "torsal"
    for example in sorted((ROOT / "torsal" / "resources" / "examples").glob("*.graph")):
        run = _step(f"torsal run {example.name}", [str(torsal), "run", str(example)], cwd=folder)
        failures += run.returncode not in (0,)
    exports = {"first-steps": ["heights.Result=heights.csv", "heights.Result=heights.json"],
               "textbook-ruled-surfaces": ["cylinder.Surface=cylinder.3dm", "helicoid.Surface=helicoid.obj"],
               "kaohsiung-cut-sheets": ["cut.Layout=roof.dxf", "cut.Layout=roof.svg"]}
    for name, requests in exports.items():
        command = [str(torsal), "run", str(ROOT / "torsal" / "resources" / "examples" / f"{name}.graph")]
        for request in requests:
            command += ["--export", request.replace("=", f"={folder}/", 1)]
        run = _step(f"torsal run {name} --export …", command, cwd=folder)
        written = [folder / r.split("=", 1)[1] for r in requests]
        # a layout over several sheets is written as NAME-1.dxf, NAME-2.dxf, …
        empty = [file.name for file in written if not any(
            f.is_file() and f.stat().st_size > 0 for f in [file, *folder.glob(f"{file.stem}-*{file.suffix}")]
        )]
        if empty:
            print(f"   not written or empty: {', '.join(empty)}")
        failures += run.returncode != 0 or bool(empty)
    if gui:
        failures += not _app_starts(torsal, folder)
    else:  # no Qt here: torsal gui must say how to install it, and exit 2
        env = {**os.environ, "DISPLAY": os.environ.get("DISPLAY") or ":99"}
        run = _step("torsal gui without the gui extra", [str(torsal), "gui", "--example", "first-steps"],
                    cwd=folder, env=env)
        # installed from the checkout as a wheel is: the hint names the gui extra's own packages
        failures += run.returncode != 2 or "-m pip install 'PySide6-Essentials" not in run.stderr or \
            "Traceback" in run.stderr
    return failures


def _app_starts(torsal: Path, folder: Path, timeout: float = 90.0) -> bool:
    """Open the app on an example (under xvfb-run when there is no display) and wait for
    its viewport to be ready; then close it."""
    print("-- torsal gui --example textbook-ruled-surfaces (until the viewport is ready)", flush=True)
    command = [str(torsal), "gui", "--example", "textbook-ruled-surfaces"]
    if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
        command = ["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", *command]
    env = {**os.environ, "TORSAL_REPORT_STARTUP": "1", "TORSAL_CONFIG_DIR": str(folder / "config")}
    start = time.perf_counter()
    with subprocess.Popen(command, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True, env=env,
                          cwd=folder, start_new_session=True) as app:
        lines: list[str] = []
        ready = False
        assert app.stderr is not None
        for line in app.stderr:
            lines.append(line)
            if "viewport-ready" in line:
                ready = True
                break
            if time.perf_counter() - start > timeout:
                break
        os.killpg(app.pid, signal.SIGTERM)
    if not ready:
        print("".join(lines[-30:]), end="")
    print(f"   ({time.perf_counter() - start:.0f} s, {'ready' if ready else 'did not start'})", flush=True)
    return ready


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="check_bounds", description=__doc__.splitlines()[0])
    parser.add_argument("--keep", type=Path, metavar="DIR", help="build the venv in DIR and keep it")
    parser.add_argument("--gui", action="store_true", help="also the gui extra's lower bounds, and app/gui")
    args = parser.parse_args(argv)
    if args.keep:
        args.keep.mkdir(parents=True, exist_ok=True)
        failures = check(args.keep, args.gui)
    else:
        with tempfile.TemporaryDirectory(prefix="torsal-bounds-") as folder:
            failures = check(Path(folder), args.gui)
    print("lower bounds: OK" if not failures else f"lower bounds: {failures} step(s) failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

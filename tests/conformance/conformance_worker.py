"""Worker process of the conformance harness: runs cases sent as JSON lines on stdin.

Protocol: one request per line ``{"id", "name", "source"}``; one ``Result`` JSON line per request on
the *original* stdout.  File descriptor 1 is redirected to stderr at start-up, and ``sys.stdout`` is
captured per case, so nothing a case prints can corrupt the protocol.  See ``conformance_harness``.
"""

from __future__ import annotations

import importlib
import inspect
import io
import json
import os
import shutil
import sys
import tempfile
import traceback
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from conformance_harness import Result  # noqa: E402


def _project_folder(source: Path, name: str, scratch: Path) -> Path:
    """The project folder to transpile: the case's own, or one made around a single .gpl file."""
    if source.is_dir():
        return source
    folder = scratch / "src" / name
    folder.mkdir(parents=True)
    shutil.copyfile(source, folder / source.name)
    (folder / "Project.gpr").write_text(
        "ProjectBegin\n"
        f'ProjectName="Conf_{name}"\n'
        'ProjectStart="Main"\n'
        f'ProjectSource="{source.name}"\n'
        "ProjectEnd\n",
        encoding="latin-1",
    )
    return folder


def _transpile(project: Path, out: Path) -> tuple[int, str]:
    from gpl2py.cli import main as gpl2py_main

    err = io.StringIO()
    with redirect_stdout(io.StringIO()), redirect_stderr(err):
        try:
            code = gpl2py_main([str(project), "-o", str(out)])
        except SystemExit as exc:  # defensive: the CLI promises to return, not exit
            code = exc.code if isinstance(exc.code, int) else 1
        except Exception:  # noqa: BLE001 - a transpiler crash is a result, not a worker crash
            return 1, traceback.format_exc()
    return code, err.getvalue()


def _package(out: Path) -> str | None:
    packages = sorted(p.name for p in out.iterdir() if (p / "__init__.py").is_file()) if out.is_dir() else []
    return packages[0] if len(packages) == 1 else None


def _reset_runtime() -> None:
    """Forget what earlier cases registered, so that lookups by name cannot find their procedures."""
    from gplrt.lang.mathlib import rnd_seed
    from gplrt.lang.procedures import clear_procedures

    clear_procedures()
    rnd_seed(1)


def _forget_modules(package: str) -> None:
    for mod in [m for m in sys.modules if m == package or m.startswith(package + ".")]:
        del sys.modules[mod]


def _run_package(pkg: object, sim: object) -> None:
    """Run the generated package on ``sim``: ``main(sim)`` when main takes the session (it then
    calls ``init()`` itself on the main GPL thread), else ``init()`` then ``main()``."""
    main = getattr(pkg, "main")
    try:
        takes_session = len(inspect.signature(main).parameters) >= 1
    except (TypeError, ValueError):
        takes_session = False
    if takes_session:
        main(sim)
    else:
        getattr(pkg, "init")()
        main()


def run_case(name: str, source: Path) -> Result:
    with tempfile.TemporaryDirectory(prefix="gplconf_") as tmp_name:
        scratch = Path(tmp_name)
        project = _project_folder(source, name, scratch)
        out = scratch / "out"
        code, diagnostics = _transpile(project, out)
        if code != 0:
            return Result("transpile_error", detail=f"gpl2py exit status {code}\n{diagnostics}")
        package = _package(out)
        if package is None:
            return Result("transpile_error", detail=f"no single package under {out}\n{diagnostics}")
        from gplrt.sim import Simulation

        _reset_runtime()
        (scratch / "flash").mkdir()
        sim = Simulation(capture=True, flash_root=scratch / "flash", project=f"Conf_{name}")
        printed = io.StringIO()
        errors = io.StringIO()
        sys.path.insert(0, str(out))
        status, detail = "ok", ""
        try:
            with redirect_stdout(printed), redirect_stderr(errors), sim:
                try:
                    pkg = importlib.import_module(package)
                except BaseException:  # noqa: BLE001
                    return Result("import_error", detail=traceback.format_exc())
                _run_package(pkg, sim)
        except BaseException:  # noqa: BLE001 - any escape is the case's failure, reported in full
            status, detail = "run_error", traceback.format_exc()
        finally:
            sys.path.remove(str(out))
            _forget_modules(package)
        log = sim.console.log_text + errors.getvalue()
        if status == "ok" and "Program stalled" in log:
            status = "stalled"
        return Result(status, output=sim.console.output + printed.getvalue(), log=log, detail=detail)


def main() -> None:
    protocol = os.fdopen(os.dup(1), "w", encoding="utf-8")
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    for line in sys.stdin:
        if not line.strip():
            continue
        request = json.loads(line)
        try:
            result = run_case(request["name"], Path(request["source"]))
        except BaseException:  # noqa: BLE001
            result = Result("worker_error", detail=traceback.format_exc())
        protocol.write(result.to_json() + "\n")
        protocol.flush()


if __name__ == "__main__":
    main()

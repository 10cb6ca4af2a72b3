"""What PyPI and a user installing gpl2py get: the wheel and the source distribution, built from
the files git tracks (what a fresh clone has), as a release would build them.

The licence in both, classifiers, keywords, one version (gpl2py.__version__), py.typed, a README
whose links work on PyPI (no relative ones; the files it names ship in the sdist), floors in
every dependency."""

from __future__ import annotations

import email
import re
import shutil
import subprocess
import sys
import tarfile
import tomllib
import zipfile
from email.message import Message
from pathlib import Path

import pytest

from gpl2py import __version__

REPO = Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((REPO / "pyproject.toml").read_text())


def _tracked() -> list[str]:
    out = subprocess.run(["git", "ls-files", "-z"], cwd=REPO, capture_output=True, check=True).stdout
    return [p for p in out.decode().split("\0") if p and (REPO / p).is_file()]


@pytest.fixture(scope="module")
def dists(tmp_path_factory: pytest.TempPathFactory) -> tuple[zipfile.ZipFile, tarfile.TarFile]:
    if shutil.which("git") is None or not (REPO / ".git").exists():
        pytest.skip("needs the git checkout to know which files a fresh clone has")
    tmp = tmp_path_factory.mktemp("dist")
    src = tmp / "src"
    for rel in _tracked():
        (src / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(REPO / rel, src / rel)
    # the build backend pyproject.toml asks for, in a folder of its own (as pip's isolated build)
    backend = tmp / "backend"
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--target", str(backend),
                    *PYPROJECT["build-system"]["requires"]], check=True, capture_output=True, timeout=600)
    out = tmp / "out"
    out.mkdir()
    for hook in ("build_sdist", "build_wheel"):  # each in a process of its own, as a frontend does
        subprocess.run([sys.executable, "-c", f"import sys; from setuptools import build_meta as b; b.{hook}(sys.argv[1])",
                        str(out)], cwd=src, check=True, capture_output=True, timeout=600,
                       env={"PYTHONPATH": str(backend), "PATH": "/usr/bin:/bin"})
    [wheel] = out.glob("*.whl")
    [sdist] = out.glob("*.tar.gz")
    return zipfile.ZipFile(wheel), tarfile.open(sdist)


def _metadata(wheel: zipfile.ZipFile) -> Message:
    [name] = [n for n in wheel.namelist() if n.endswith(".dist-info/METADATA")]
    return email.message_from_bytes(wheel.read(name))


def test_the_version_is_written_once() -> None:
    assert "version" not in PYPROJECT["project"] and "version" in PYPROJECT["project"]["dynamic"]
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "gpl2py.__version__"}


def test_wheel_metadata(dists: tuple[zipfile.ZipFile, tarfile.TarFile]) -> None:
    wheel, _ = dists
    meta = _metadata(wheel)
    assert meta["Name"] == "gpl2py" and meta["Version"] == __version__
    assert meta["License-Expression"] == "MIT"
    classifiers = meta.get_all("Classifier") or []
    assert "Typing :: Typed" in classifiers and "Programming Language :: Python :: 3.11" in classifiers
    assert not [c for c in classifiers if c.startswith("License ::")]  # PEP 639: the expression says it
    assert "PreciseFlex" in meta["Keywords"].split(",")
    assert meta["Description-Content-Type"] == "text/markdown"


def test_licence_and_py_typed_in_the_wheel(dists: tuple[zipfile.ZipFile, tarfile.TarFile]) -> None:
    wheel, sdist = dists
    names = wheel.namelist()
    [licence] = [n for n in names if n.endswith(".dist-info/licenses/LICENSE")]
    assert wheel.read(licence) == (REPO / "LICENSE").read_bytes()
    assert b"MIT License" in wheel.read(licence)
    assert {"gpl2py/py.typed", "gplrt/py.typed"} <= set(names)
    assert any(n.endswith("/LICENSE") for n in sdist.getnames())


def test_readme_links_work_on_pypi(dists: tuple[zipfile.ZipFile, tarfile.TarFile]) -> None:
    """PyPI shows the README without the repository around it: a relative link is a dead link
    there.  Every link is absolute; the files the README names are in the source distribution."""
    _, sdist = dists
    readme = (REPO / "README.md").read_text()
    relative = re.findall(r"\]\((?!https?://|#)([^)]*)\)", readme)
    assert relative == [], relative
    shipped = {n.split("/", 1)[1] for n in sdist.getnames() if "/" in n}
    named = set(re.findall(r"`((?:docs|samples|scripts|runtime)/[\w./-]+\.(?:md|py|sh))`", readme))
    assert {"docs/cli.md", "docs/diagnostics.md", "samples/notebook/cell_io.py"} <= named
    assert named <= shipped, named - shipped


def test_every_dependency_has_a_floor_that_ci_installs() -> None:
    project = PYPROJECT["project"]
    extras = project["optional-dependencies"]
    for req in [*project["dependencies"], *extras["plot"], *extras["sweep"]]:
        assert ">=" in req, req
    assert set(extras["sweep"]) <= set(extras["test"])  # CI installs what the sweep tests need
    floors = subprocess.run([sys.executable, str(REPO / "scripts" / "floors.py"), "constraints", "plot"],
                            capture_output=True, text=True, check=True).stdout.split()
    assert floors == sorted(floors) and "pin==3.3.1" in floors
    assert "bash scripts/floors.sh" in (REPO / ".ci" / "run").read_text()


def test_a_generated_package_records_the_gpl2py_version(tmp_path: Path) -> None:
    from gpltest import transpile, write_project

    proj = Path(write_project(tmp_path, {"Main.gpl": "Module Main\n    Public Sub Main()\n    End Sub\nEnd Module\n"}))
    done = transpile(proj, tmp_path / "out")
    assert done.package.PROJECT["gpl2py"] == __version__
    assert done.package.__doc__.splitlines()[0].endswith(f", transpiled by gpl2py {__version__}.")

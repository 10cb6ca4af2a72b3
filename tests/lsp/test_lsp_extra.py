"""``gpl2py lsp`` without its extra says which one to install, in one line, as ``--plot`` does."""

from __future__ import annotations

from pathlib import Path

from gpltest import gpl2py


def test_without_pygls_the_command_names_the_extra(tmp_path: Path) -> None:
    shadow = tmp_path / "shadow" / "pygls"
    shadow.mkdir(parents=True)
    (shadow / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'pygls'\", name='pygls')\n")
    done = gpl2py("lsp", cwd=tmp_path, env={"PYTHONPATH": str(tmp_path / "shadow")})
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.strip() == ("error GPL9001: gpl2py lsp needs pygls, which is not installed: "
                                   "pip install 'gpl2py[lsp]'")

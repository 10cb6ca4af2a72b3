"""Every call the vendor's TCP Command Server makes to a built-in member fits its signature.

TCS 3.0C1, plain and with the PARobot plug-in (``shared/corpus``, read in place), runs on real
controllers; each of its built-in member calls must translate: no wrong argument count (GPL2004),
no arguments on a member that takes none (GPL2012), no assignment the catalogue cannot express
(GPL2008), and no member the catalogue lacks (GPL3502, a stub).  Other diagnostics these projects
still get belong to other constructs and are not this test's business.
"""

from __future__ import annotations

import pytest
from gpltest import corpus_dir

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.transpile import transpile

SIGNATURE_CODES = {"GPL2004", "GPL2012", "GPL2008", "GPL3502"}


@pytest.mark.parametrize("project", ["tcs-3.0C1", "tcs-3.0C1-pa"])
def test_every_builtin_call_of_the_tcp_command_server_fits_its_signature(project: str) -> None:
    folder = corpus_dir() / project
    sink = DiagnosticSink()
    transpile(str(folder), sink)
    wrong = [d.header() for d in sink.sorted() if d.code in SIGNATURE_CODES]
    assert not wrong, "\n".join(wrong)

"""Lexer tests: token kinds, values and positions for every lexical rule in spec §1."""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink, Severity
from gpl2py.project import load_project
from gpl2py.source import SourceFile
from gpl2py.gpl.syntax.lexer import CHUNK, token_chunks, tokenize
from gpl2py.gpl.syntax.parser import parse
from gpl2py.gpl.syntax.tokens import Token, TokenKind as K


def lex(text: str) -> tuple[list[Token], DiagnosticSink]:
    sink = DiagnosticSink()
    return tokenize(SourceFile("t.gpl", text), sink), sink


def kinds(text: str) -> list[K]:
    toks, _ = lex(text)
    return [t.kind for t in toks]


def codes(sink: DiagnosticSink) -> list[str]:
    return [d.code for d in sink]


def test_keywords_are_case_insensitive_and_keep_their_spelling() -> None:
    toks, sink = lex("dIM x aS InTeGeR\n")
    assert [t.kind for t in toks] == [K.DIM, K.IDENT, K.AS, K.IDENT, K.NEWLINE, K.EOF]
    assert toks[0].text == "dIM"
    assert len(sink) == 0


def test_words_the_spec_keeps_usable_are_identifiers() -> None:
    # spec §1.8: these appear as variable names in the manual's examples
    words = "value str out inp err file send recv line input output bool node name count mode"
    toks, _ = lex(words + " GoSub With Enum Optional Each Preserve IsNot\n")
    assert all(t.kind is K.IDENT for t in toks[:-2])


def test_every_token_carries_file_line_and_column() -> None:
    toks, _ = lex("Module M\n\tDim  x As Integer\n")
    dim = toks[3]
    assert dim.kind is K.DIM
    assert (dim.span.file, dim.span.line, dim.span.col) == ("t.gpl", 2, 2)  # a tab is one column
    x = toks[4]
    assert (x.line, x.col, x.span.end_col) == (2, 7, 8)


def test_crlf_and_lf_give_identical_tokens() -> None:
    a, _ = lex("x = 1\r\ny = 2\r\n")
    b, _ = lex("x = 1\ny = 2\n")
    assert [(t.kind, t.text, t.line, t.col) for t in a] == [(t.kind, t.text, t.line, t.col) for t in b]


def test_blank_lines_produce_no_newline_tokens_and_last_line_needs_no_break() -> None:
    assert kinds("\n\n  \nx\n\n") == [K.IDENT, K.NEWLINE, K.EOF]
    assert kinds("x") == [K.IDENT, K.NEWLINE, K.EOF]
    assert kinds("") == [K.EOF]


@pytest.mark.parametrize(
    ("text", "kind", "value"),
    [
        ("100", K.INTEGER, 100),
        ("2.34", K.REAL, 2.34),
        (".9", K.REAL, 0.9),
        ("2.", K.REAL, 2.0),
        ("1E+32", K.REAL, 1e32),
        ("1.5e-3", K.REAL, 0.0015),
        ("&H20", K.INTEGER, 32),
        ("&h1000", K.INTEGER, 4096),
        ("&HFFFFFFFF", K.INTEGER, -1),
        ("&H7FFFFFFF", K.INTEGER, 2147483647),
        ("&O17", K.INTEGER, 15),
        ('"Joe\'s"', K.STRING, "Joe's"),
        ('"Tom said, ""Hello world"""', K.STRING, 'Tom said, "Hello world"'),
        ('""""', K.STRING, '"'),
        ('""', K.STRING, ""),
    ],
)
def test_literals(text: str, kind: K, value: object) -> None:
    toks, sink = lex(f"x = {text}\n")
    assert toks[2].kind is kind
    assert toks[2].value == value
    assert toks[2].text == text
    assert len(sink) == 0


def test_head_trap_lexes_a_hex_literal() -> None:
    # spec §1.9: 'String &HEAD' is String followed by the hex literal &HEAD (0xEAD), not & HEAD
    toks, _ = lex("s = String &HEAD\n")
    assert [t.kind for t in toks[2:4]] == [K.IDENT, K.INTEGER]
    assert toks[3].text == "&HEAD" and toks[3].value == 0xEAD
    toks, _ = lex("s = String &O2\n")
    assert toks[3].value == 2
    toks, _ = lex("s = a & HEAD\n")  # with a space it is concatenation
    assert [t.kind for t in toks[2:5]] == [K.IDENT, K.AMP, K.IDENT]
    toks, _ = lex("s = a &Hxyz\n")  # no hex digit after &H: '&' then a name
    assert [t.kind for t in toks[2:5]] == [K.IDENT, K.AMP, K.IDENT]


def test_hex_literal_out_of_range_is_reported() -> None:
    _, sink = lex("x = &H100000000\n")
    assert codes(sink) == ["GPL1007"]


def test_decimal_literal_past_the_double_range_is_reported() -> None:
    # a decimal literal past the Integer range is a Double, so one past the Double range is out of
    # range like 1E+400: 310 digits (once an OverflowError in the lowering of a Double store) and
    # 4,301 (once Python's ValueError for long int() strings in the lexer, a GPL9000)
    for digits in (310, 4301, 100_000):
        toks, sink = lex(f"x = {'9' * digits}\n")
        assert codes(sink) == ["GPL1007"], digits
        assert toks[2].kind is K.INTEGER and toks[2].value == 0
        assert f"({digits} characters)" in sink.errors[0].message and len(sink.errors[0].message) < 100
    toks, sink = lex(f"x = {'9' * 308}\n")  # within the range: the exact value
    assert codes(sink) == [] and toks[2].value == int("9" * 308)
    toks, sink = lex(f"x = {'0' * 5000}17\n")  # leading zeros count for nothing
    assert codes(sink) == [] and toks[2].value == 17
    toks, sink = lex(f"x = {'1' + '0' * 5000}.5\n")  # a real literal the same
    assert codes(sink) == ["GPL1007"] and "(5003 characters)" in sink.errors[0].message


def test_literal_suffix_is_reported() -> None:
    _, sink = lex("x = 725L\n")
    assert codes(sink) == ["GPL1006"]
    assert sink.errors[0].span.col == 5


@pytest.mark.parametrize(
    "op",
    ["+", "-", "*", "/", "\\", "^", "&", "=", "<>", "<", ">", "<=", ">=", "<<", ">>",
     "^=", "*=", "/=", "\\=", "+=", "-=", "<<=", ">>=", "&=", "(", ")", ",", ".", ":"],
)
def test_operators_longest_match(op: str) -> None:
    toks, sink = lex(f"a {op} b\n")
    assert toks[1].text == op
    assert toks[1].kind.value == op
    assert len(sink) == 0


def test_operators_without_spaces() -> None:
    toks, _ = lex("x<<=y>>=z<>w<=v\n")
    assert [t.text for t in toks[:-2]] == ["x", "<<=", "y", ">>=", "z", "<>", "w", "<=", "v"]


def test_comment_is_a_token_before_newline_and_apostrophe_in_string_is_not() -> None:
    toks, _ = lex('s1 = "Joe\'s" \' says hi\n')
    assert [t.kind for t in toks] == [K.IDENT, K.EQ, K.STRING, K.COMMENT, K.NEWLINE, K.EOF]
    assert toks[3].value == " says hi"
    assert toks[3].col == 14


def test_hash_lines_become_directives_and_conditional_ones_warn() -> None:
    toks, sink = lex('#Region "x"\n  #End Region\nx = 1\n')
    assert [t.kind for t in toks[:4]] == [K.DIRECTIVE, K.NEWLINE, K.DIRECTIVE, K.NEWLINE]
    assert toks[0].value == '#Region "x"'
    assert len(sink) == 0
    _, sink = lex("#If DEBUG Then\nx = 1\n#End If\n")
    assert codes(sink) == ["GPL1008", "GPL1008"]
    assert all(d.severity is Severity.WARNING for d in sink)


def test_hash_in_the_middle_of_a_line_is_an_error() -> None:
    _, sink = lex("x = 1 # 2\n")
    assert codes(sink) == ["GPL1010"]


def test_continuation_joins_lines_and_tolerates_trailing_blanks() -> None:
    toks, sink = lex("x = a + _   \n    b\ny = 2\n")
    assert [t.text for t in toks if t.kind is not K.NEWLINE][:5] == ["x", "=", "a", "+", "b"]
    assert [t.kind for t in toks].count(K.NEWLINE) == 2
    b = toks[4]
    assert (b.line, b.col) == (2, 5)  # tokens keep their physical position
    assert len(sink) == 0


def test_continuation_over_25_lines_is_one_logical_line() -> None:
    lines = ["x = 1 _"] + ["    + 1 _" for _ in range(24)] + ["    + 1"]
    toks, sink = lex("\n".join(lines) + "\nz = 0\n")
    newlines = [t for t in toks if t.kind is K.NEWLINE]
    assert len(newlines) == 2
    assert newlines[0].line == 26
    assert sum(1 for t in toks if t.kind is K.PLUS) == 25
    assert len(sink) == 0


def test_underscore_identifiers_are_not_continuations() -> None:
    toks, sink = lex("GoTo _exit\n_exit:\nx_ = __a1\n")
    names = [t.text for t in toks if t.kind is K.IDENT]
    assert names == ["_exit", "_exit", "x_", "__a1"]
    assert len(sink) == 0


@pytest.mark.parametrize("text", [
    "lcc.XYZ(a, b,_\n   c)\n",        # the vendor's TCS, Cmd.gpl: '_' glued to a comma
    "x = f(a)_\n+ 1\n",
    'x = "a"&_\n"b"\n',
    'x = "a" &_ \' blanks and a comment may follow\n"b"\n',
    "x = (a +_\t \nb)\n",
])
def test_underscore_after_a_character_that_cannot_end_a_name_is_a_continuation(text: str) -> None:
    """Real code glues the continuation to a comma (real-code.md): wherever the character before
    the '_' cannot be part of a name, the '_' (then only blanks or a comment) continues the line."""
    toks, sink = lex(text)
    assert [t.kind for t in toks].count(K.NEWLINE) == 1
    assert K.ERROR not in [t.kind for t in toks]
    assert [d.code for d in sink.errors] == []


def test_call_continued_after_a_glued_underscore_parses_as_one_call() -> None:
    sink = DiagnosticSink()
    unit = parse(SourceFile("t.gpl", "Module M\nSub S()\n    f(1, 2,_\n      3)\nEnd Sub\nEnd Module\n"), sink)
    assert len(sink) == 0
    call = unit.members[0].members[0].body.statements[0]
    assert len(call.expr.args) == 3


def test_underscore_glued_to_a_number_is_not_a_continuation() -> None:
    """A '_' right after a character that can be part of a name is never a continuation: after a
    number it is a bad suffix (GPL1006) and an invalid character, not a hidden line join."""
    _, sink = lex("x = 1_\n+ 1\n")
    assert codes(sink) == ["GPL1006", "GPL1001"]


def test_comment_after_continuation_is_a_warning_and_kept() -> None:
    toks, sink = lex("x = a + _ ' why\n    b ' end\n")
    assert codes(sink) == ["GPL1005"]
    assert sink.warnings[0].span.line == 1
    comments = [t.value for t in toks if t.kind is K.COMMENT]
    assert comments == [" why", " end"]  # source order, both before the NEWLINE
    assert [t.kind for t in toks][-4:] == [K.COMMENT, K.COMMENT, K.NEWLINE, K.EOF]


def test_comments_after_many_continuations_warn_once_per_statement() -> None:
    lines = ['s = "a" _ \' first part'] + [f'    & "x{i}" _ \' part {i}' for i in range(200)] + ['    & "end"']
    lines += ["t = 1 + _ ' again", "    2", "u = _", "    3 ' not after a continuation"]
    toks, sink = lex("\n".join(lines) + "\n")
    assert [(d.code, d.span.line) for d in sink] == [("GPL1005", 1), ("GPL1005", 203)]
    comments = [t.value for t in toks if t.kind is K.COMMENT]
    assert comments[:2] == [" first part", " part 0"] and comments[200] == " part 199"
    assert comments[201:] == [" again", " not after a continuation"]  # every comment is kept
    assert [t.kind for t in toks].count(K.NEWLINE) == 3


def test_labels_lex_as_name_or_number_then_colon() -> None:
    toks, _ = lex("retry:\n    _exit: x = 1\n100: GoTo 100\n")
    assert [(t.kind, t.text) for t in toks[:2]] == [(K.IDENT, "retry"), (K.COLON, ":")]
    assert [(t.kind, t.col) for t in toks[3:5]] == [(K.IDENT, 5), (K.COLON, 10)]
    assert toks[9].kind is K.INTEGER and toks[10].kind is K.COLON


def test_string_limits_and_errors() -> None:
    _, sink = lex('s = "' + "a" * 129 + '"\n')
    assert codes(sink) == ["GPL1003"] and sink.warnings
    _, sink = lex('s = "' + "a" * 128 + '"\n')
    assert len(sink) == 0
    toks, sink = lex('s = "abc\nx = 1\n')
    assert codes(sink) == ["GPL1002"]
    assert toks[2].kind is K.STRING and toks[3].kind is K.NEWLINE  # recovers on the next line
    _, sink = lex('s = "café"\n')
    assert codes(sink) == ["GPL1004"]


def test_an_unterminated_string_holding_doubled_quotes_is_reported_at_its_opening_quote() -> None:
    # '"ab""' has no closing quote: the '""' is a quote inside the string, so the string that
    # is not closed is the one that starts at column 5 (it was reported at the last quote)
    toks, sink = lex('s = "ab""\n')
    assert codes(sink) == ["GPL1002"] and sink.errors[0].span.col == 5
    assert [(t.kind, t.value) for t in toks[2:4]] == [(K.STRING, 'ab"'), (K.NEWLINE, None)]
    toks, sink = lex('s = "ab""" & "c""d"\n')  # closed strings are unchanged
    assert len(sink) == 0 and [t.value for t in toks if t.kind is K.STRING] == ['ab"', 'c"d']


def test_non_ascii_outside_comments_is_an_error_inside_comments_fine() -> None:
    _, sink = lex("x = 1 ' café – ok\n")
    assert len(sink) == 0
    _, sink = lex("x = a – b\n")  # en dash from a PDF
    assert codes(sink) == ["GPL1001"]
    assert (sink.errors[0].span.line, sink.errors[0].span.col) == (1, 7)
    _, sink = lex("dïm = 1\n")
    assert codes(sink) == ["GPL1001"]


def test_a_run_of_invalid_characters_is_one_diagnostic() -> None:
    _, sink = lex("x = ☃☃☃ + 1\n")
    assert codes(sink) == ["GPL1001"]


def test_long_identifier_is_reported() -> None:
    _, sink = lex("x" * 129 + " = 1\n")
    assert codes(sink) == ["GPL1009"]
    _, sink = lex("x" * 128 + " = 1\n")
    assert len(sink) == 0


def test_tokens_have_no_gaps_on_a_realistic_line() -> None:
    line = "        If (ep.IPAddress<>rem_ep.IPAddress) Or _"
    toks, _ = lex(line + "\n            (ep.Port<>rem_ep.Port) Then\n")
    texts = [t.text for t in toks if t.kind not in (K.NEWLINE, K.EOF)]
    assert "".join(texts[:11]) == "If(ep.IPAddress<>rem_ep.IPAddress)Or"
    assert toks[-3].kind is K.THEN and toks[-3].line == 2


def test_leading_byte_order_mark_is_ignored() -> None:
    toks, sink = lex("\ufeffModule M\nEnd Module\n")
    assert len(sink) == 0
    assert toks[0].kind is K.MODULE and (toks[0].line, toks[0].col) == (1, 1)
    _, sink = lex("x = 1\n\ufeffy = 2\n")  # anywhere else it is an invalid character
    assert [d.code for d in sink] == ["GPL1001"]


def test_trailing_dos_end_of_file_marker_is_ignored() -> None:
    toks, sink = lex("Module M\r\nEnd Module\r\n\x1a")
    assert len(sink) == 0
    assert [t.kind for t in toks] == [K.MODULE, K.IDENT, K.NEWLINE, K.END, K.MODULE, K.NEWLINE, K.EOF]
    assert (toks[-1].line, toks[-1].col) == (3, 1)
    toks, sink = lex("x = 1\x1a\x1a")  # right after the last token, without a line break
    assert len(sink) == 0 and [t.kind for t in toks][-2:] == [K.NEWLINE, K.EOF]
    assert toks[-2].col == 6
    _, sink = lex("x = 1\n\x1ay = 2\n")  # anywhere else it is an invalid character
    assert [(d.code, d.span.line, d.span.col) for d in sink] == [("GPL1001", 2, 1)]


def test_a_file_ending_in_ctrl_z_checks_clean_through_the_project_loader(tmp_path: Path) -> None:
    (tmp_path / "Old.gpl").write_bytes(b"Module Old\r\n    Public Sub Main()\r\n    End Sub\r\nEnd Module\r\n\x1a")
    sink = DiagnosticSink()
    project = load_project(tmp_path, sink)
    assert project is not None
    unit = parse(project.sources[0], sink)
    assert list(sink) == [] and [m.name for m in unit.members] == ["Old"]  # type: ignore[attr-defined]



def test_source_lines_are_the_lexers_lines_so_excerpts_match_positions() -> None:
    # Form feeds, U+0085, U+2028 and U+001C are not line breaks for GPL (str.splitlines says they
    # are), and a byte-order mark is not part of line 1: every token must be found where it says.
    text = "\ufeffModule M\n\f\n' caf\x85e \u2028 \x1c\nSub S()\r\n\tDim alpha As Integer\r\nx = (1 +\r\nEnd Sub\nEnd Module\r"
    src = SourceFile("t.gpl", text)
    toks, _ = lex(text)
    words = [t for t in toks if t.kind in (K.IDENT, K.MODULE, K.DIM, K.END, K.SUB)]
    assert [t.text for t in words] == ["Module", "M", "Sub", "S", "Dim", "alpha", "Integer", "x", "End", "Sub", "End", "Module"]
    for t in words:
        assert src.line_text(t.line)[t.col - 1 : t.span.end_col - 1] == t.text, (t.line, t.col)
    sink = DiagnosticSink()
    parse(src, sink)
    assert [d.code for d in sink.errors] == ["GPL1101"]
    assert sink.errors[0].render(src).splitlines()[1:] == ["    x = (1 +", "            ^"]


def test_one_long_line_is_handed_to_the_parser_in_chunks() -> None:
    # the parser holds one or two chunks at a time; a chunk used to end only at a line break, so
    # a file of one line of 100,000 terms was 200,000 tokens at once (~200 bytes each, 100 times
    # the two bytes of source they come from)
    text = "x = 1" + " + 1" * 100_000 + "\n"
    chunks = list(token_chunks(SourceFile("long.gpl", text), DiagnosticSink()))
    assert sum(map(len, chunks)) == 200_005  # x = 1, a '+' and a 1 per term, NEWLINE, EOF
    assert max(map(len, chunks)) <= CHUNK + 1

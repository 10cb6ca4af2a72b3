"""GPL ``Format(expression, format_s)``: a number as text by a format specification.

The GPL manuals give only the signature (gpl-dictionary.md §12, AMB-24): no GPL-verified
input/output pair exists.  The dictionary's provisional rule is VB.NET's numeric formatting, the
language GPL imitates, and that is what this module implements, every example of §12 included:

* **Custom patterns**: ``0`` (digit, zero-padded), ``#`` (digit if significant), ``.`` (decimal
  point), ``,`` (thousands separator between digit placeholders; directly left of the point it
  divides by 1000), ``%`` (x100), ``‰`` (x1000), ``E+0``/``E-0``/``e+0``/``e-0`` (scientific;
  the number of ``0`` is the minimum exponent width), ``\\c`` and ``"text"``/``'text'`` literals,
  and up to three ``;`` sections (positive; negative; zero).  A negative value formatted by the
  negative section loses its minus sign (``Format(-3.7, "0.0;(0.0)")`` = "(3.7)").
* **Standard specifiers** (a letter and an optional precision): ``C`` currency ($, 2),
  ``D`` decimal integer, ``E`` scientific (6, 3-digit exponent), ``F`` fixed (2), ``G`` general
  (the CStr rendering; with a precision, that many significant digits), ``N`` number with
  separators (2), ``P`` percent (2), ``R`` round-trip, ``X`` hexadecimal (32-bit two's complement
  for negatives).  An unknown specifier letter is -202 Invalid argument, as is ``D``/``X`` on a
  non-integral value (.NET raises FormatException there).
* **VB named formats**: "General Number", "Currency", "Fixed", "Standard", "Percent",
  "Scientific", "Yes/No", "True/False", "On/Off".

Rounding is half away from zero on the value first rounded to 15 significant digits (the .NET
Framework behaviour VB programs were written against: ``Format(2.675, "0.00")`` = "2.68" although
the nearest Double is slightly below 2.675).  A value that rounds to zero prints without a minus
sign.  Invariant culture: ``.`` and ``,``.
"""

from __future__ import annotations

import re
from decimal import ROUND_HALF_UP, Context, Decimal
from typing import Any, Final

from gplrt.lang.conversions import to_number, to_string
from gplrt.lang.errors import INVALID_ARGUMENT, GplException
from gplrt.lang.gpltypes import String

__all__ = ["Format"]

_STANDARD_RE: Final = re.compile(r"([A-Za-z])(\d{1,2})?\Z")

_NAMED: Final[dict[str, str]] = {
    "general number": "G",
    "currency": "C",
    "fixed": "F",
    "standard": "N",
    "percent": "0.00%",
    "scientific": "0.00E+00",
}
_BOOLEAN_NAMED: Final[dict[str, tuple[str, str]]] = {
    "yes/no": ("Yes", "No"),
    "true/false": ("True", "False"),
    "on/off": ("On", "Off"),
}


def _bad(detail: str) -> GplException:
    return GplException(INVALID_ARGUMENT, detail=detail)


def _dec(value: float | int) -> Decimal:
    """|value| as a Decimal rounded to 15 significant digits (ints exactly)."""
    if type(value) is int:
        return Decimal(abs(value))
    return Decimal("%.15e" % abs(value))


def _round(d: Decimal, places: int) -> Decimal:
    """``d`` rounded half away from zero to ``places`` decimals.

    The context's precision is sized to the result: the default 28 digits would make quantize
    raise ``InvalidOperation`` for a Double such as 1E+300 written out in full ("0" or "F0").
    """
    if not d.is_finite():
        return d
    digits = max(d.adjusted(), 0) + places + 2
    return d.quantize(Decimal(1).scaleb(-places), rounding=ROUND_HALF_UP, context=Context(prec=max(digits, 28)))


def _group(digits: str) -> str:
    head = len(digits) % 3 or 3
    parts = [digits[:head]] + [digits[i : i + 3] for i in range(head, len(digits), 3)]
    return ",".join(parts)


def _fixed_digits(d: Decimal, places: int) -> tuple[str, str]:
    """Integer and fraction digit strings of ``d`` rounded to ``places`` decimals."""
    text = f"{_round(d, places):f}"
    whole, _, frac = text.partition(".")
    return whole, frac.ljust(places, "0")[:places] if places else ""


# -- standard specifiers -------------------------------------------------------------------------


def _standard(value: float | int, letter: str, precision: int | None) -> str:
    upper = letter.upper()
    neg = value < 0
    if upper == "G":
        if precision is None or precision == 0:
            text = to_string(value)
        else:
            text = ("%." + str(precision) + "g") % value
            if "e" in text:
                mant, _, exp = text.partition("e")
                text = mant + "E" + exp[0] + exp[1:].rjust(2, "0")
        return text.lower() if letter == "g" else text
    if upper == "R":
        return to_string(value) if type(value) is int else repr(float(value)).replace("e", "E")
    if upper in "DX":
        if type(value) is not int:
            if value != int(value):
                raise _bad(f"format {letter} needs an integral value, not {value}")
            value = int(value)
        if upper == "D":
            digits = str(abs(value)).rjust(precision or 0, "0")
            return ("-" if value < 0 else "") + digits
        if not -0x80000000 <= value <= 0xFFFFFFFF:
            raise _bad(f"format X of {value}")
        text = format(value & 0xFFFFFFFF, "X" if letter == "X" else "x")
        return text.rjust(precision or 0, "0")
    d = _dec(value)
    if upper == "E":
        places = 6 if precision is None else precision
        if d == 0:
            exp = 0
            mant = Decimal(0)
        else:
            exp = d.adjusted()
            mant = _round(d.scaleb(-exp), places)
            if mant >= 10:
                exp += 1
                mant = _round(d.scaleb(-exp), places)
        whole, frac = _fixed_digits(mant, places)
        body = whole + ("." + frac if places else "")
        text = f"{body}{letter}{'-' if exp < 0 else '+'}{abs(exp):03d}"
    elif upper in "FNPC":
        places = 2 if precision is None else precision
        if upper == "P":
            d = d * 100
        whole, frac = _fixed_digits(d, places)
        if upper in "NPC":
            whole = _group(whole)
        text = whole + ("." + frac if places else "")
        if upper == "P":
            text += "%"
        if upper == "C":
            zero = set(whole + frac) <= {"0", ","}
            return ("($" + text + ")") if neg and not zero else "$" + text
    else:
        raise _bad(f"unknown format specifier {letter!r}")
    zero = set(text.split("E")[0].split("e")[0]) <= {"0", ".", ","}
    return ("-" if neg and not zero else "") + text


# -- custom patterns ------------------------------------------------------------------------------


def _split_sections(spec: str) -> list[list[tuple[str, str]]]:
    """Tokenise ``spec`` into sections of (kind, text) tokens; kinds: 0 # . , % ‰ E lit."""
    sections: list[list[tuple[str, str]]] = [[]]
    i = 0
    n = len(spec)
    while i < n:
        c = spec[i]
        cur = sections[-1]
        if c == ";":
            sections.append([])
        elif c == "\\" and i + 1 < n:
            i += 1
            cur.append(("lit", spec[i]))
        elif c in "\"'":
            end = spec.find(c, i + 1)
            if end < 0:
                end = n
            cur.append(("lit", spec[i + 1 : end]))
            i = end
        elif c in "0#.,%‰":
            cur.append((c, c))
        elif c in "Ee":
            j = i + 1
            sign = ""
            if j < n and spec[j] in "+-":
                sign = spec[j]
                j += 1
            k = j
            while k < n and spec[k] == "0":
                k += 1
            if k > j:
                cur.append(("E", f"{c}{sign or ' '}{k - j}"))
                i = k - 1
            else:
                cur.append(("lit", c))
        else:
            cur.append(("lit", c))
        i += 1
    return sections


def _custom_section(tokens: list[tuple[str, str]], value: float | int, signed: bool) -> tuple[str, bool]:
    """Format |value| by one section; returns (text, rounded_to_zero).  ``signed`` prefixes '-'."""
    point = next((k for k, (kind, _) in enumerate(tokens) if kind == "."), None)
    exp_at = next((k for k, (kind, _) in enumerate(tokens) if kind == "E"), None)
    int_end = point if point is not None else (exp_at if exp_at is not None else len(tokens))
    frac_end = exp_at if exp_at is not None else len(tokens)

    int_ph = [k for k in range(int_end) if tokens[k][0] in "0#"]
    frac_ph = [k for k in range(int_end, frac_end) if tokens[k][0] in "0#"]
    first_zero = next((n for n, k in enumerate(int_ph) if tokens[k][0] == "0"), len(int_ph))
    min_int = len(int_ph) - first_zero
    zero_fracs = [n for n, k in enumerate(frac_ph) if tokens[k][0] == "0"]
    min_frac = zero_fracs[-1] + 1 if zero_fracs else 0
    places = len(frac_ph)

    grouping = False
    scale_commas = 0
    if int_ph:
        last_int = int_ph[-1]
        grouping = any(tokens[k][0] == "," for k in range(int_ph[0], last_int))
        k = last_int + 1
        while k < int_end and tokens[k][0] == ",":
            scale_commas += 1
            k += 1

    d = _dec(value)
    for kind, _ in tokens:
        if kind == "%":
            d *= 100
        elif kind == "‰":
            d *= 1000
    if scale_commas:
        d = d.scaleb(-3 * scale_commas)

    exponent = 0
    if exp_at is not None:
        width = max(len(int_ph), 1)
        if d != 0:
            exponent = d.adjusted() - (width - 1)
            mant = _round(d.scaleb(-exponent), places)
            if mant >= Decimal(10) ** width:
                exponent += 1
                mant = _round(d.scaleb(-exponent), places)
            d = mant
    whole, frac = _fixed_digits(d, places)
    is_zero = set(whole + frac) <= {"0"}
    whole = whole.lstrip("0")
    whole = whole.rjust(min_int, "0")
    while len(frac) > min_frac and frac.endswith("0"):
        frac = frac[:-1]
    if grouping and whole:
        whole = _group(whole)

    out: list[str] = []
    leftmost = int_ph[0] if int_ph else None
    # Integer placeholders are filled right to left; the leftmost one takes any extra digits.
    fill: dict[int, str] = {}
    if grouping:
        if leftmost is not None:
            fill[leftmost] = whole
    else:
        rest = whole
        for k in reversed(int_ph):
            if k == leftmost:
                fill[k] = rest
            else:
                fill[k] = rest[-1:] if rest else ""
                rest = rest[:-1]
    frac_iter = iter(frac)
    for k, (kind, text) in enumerate(tokens):
        if kind in "0#":
            if k < int_end:
                out.append(fill.get(k, ""))
            elif k < frac_end:
                out.append(next(frac_iter, ""))
        elif kind == ".":
            if k == point:
                if leftmost is None and whole:
                    out.append(whole)
                if frac:
                    out.append(".")
        elif kind == ",":
            continue
        elif kind == "E":
            letter, sign_mode, width = text[0], text[1], int(text[2:])
            sign = "-" if exponent < 0 else ("+" if sign_mode == "+" else "")
            out.append(f"{letter}{sign}{abs(exponent):0{width}d}")
        elif kind == "%":
            out.append("%")
        elif kind == "‰":
            out.append("‰")
        else:
            out.append(text)
    if point is None and leftmost is None and whole and any(kind in "0#" for kind, _ in tokens):
        out.insert(0, whole)
    body = "".join(out)
    return (("-" + body) if signed and not is_zero else body), is_zero


def _custom(value: float | int, spec: str) -> str:
    sections = _split_sections(spec)
    if len(sections) > 3:
        sections = sections[:3]
    neg = value < 0
    if len(sections) == 1:
        return _custom_section(sections[0], value, neg)[0]
    if value == 0:
        if len(sections) == 3 and sections[2]:
            return _custom_section(sections[2], value, False)[0]
        return _custom_section(sections[0], value, False)[0]
    if neg:
        if sections[1]:
            text, zero = _custom_section(sections[1], value, False)
        else:
            text, zero = _custom_section(sections[0], value, True)
        if zero:
            target = sections[2] if len(sections) == 3 and sections[2] else sections[0]
            return _custom_section(target, 0, False)[0]
        return text
    text, zero = _custom_section(sections[0], value, False)
    if zero and len(sections) == 3 and sections[2]:
        return _custom_section(sections[2], 0, False)[0]
    return text


def Format(expression: Any, format_s: String) -> String:
    """GPL ``Format``: ``expression`` (a number, Boolean or numeric String) as text by ``format_s``
    (see module docstring).  ``Format(5, "000")`` = "005"; an empty spec gives the CStr text."""
    value = to_number(expression)
    if type(value) is float and (value != value or value in (float("inf"), float("-inf"))):
        return to_string(value)  # type: ignore[return-value]
    spec = format_s if type(format_s) is str else to_string(format_s)
    if spec == "":
        return to_string(value)  # type: ignore[return-value]
    low = spec.lower()
    if low in _BOOLEAN_NAMED:
        yes, no = _BOOLEAN_NAMED[low]
        return (yes if value != 0 else no)  # type: ignore[return-value]
    spec = _NAMED.get(low, spec)
    m = _STANDARD_RE.match(spec)
    if m is not None:
        letter, digits = m.groups()
        return _standard(value, letter, int(digits) if digits else None)  # type: ignore[return-value]
    return _custom(value, spec)  # type: ignore[return-value]

"""A file cut inside its last field is refused whatever the number format; a complete last
line without a final line end is accepted (issue 13, point 6).

Each format writes a 100 Hz record of a wave (a slowly varying signal with noise, as loggers
write) with 2000 rows and no final line end. The complete file must read back; every cut of
the last field that still parses as a number must be refused naming the line (or fail to
parse), except, for the formats that drop trailing zeros (%g), cuts that leave as many
significant digits as the column's own cells have (at least 0.1 % of them): the last two or
three digits of a %g cell, which change the value by less than 0.1 %.
"""

import numpy as np
import pytest

from flumekit.errors import InputError
from flumekit.io.tables import read_text

N = 2000


def _record(kind):
    rng = np.random.default_rng(1)
    t = np.arange(N) / 100.0
    x = 1.2345 + 0.8 * np.sin(2 * np.pi * t / 3.1) + 0.002 * rng.standard_normal(N)
    if kind == "integers":
        x = np.round(1500 * np.sin(2 * np.pi * t / 3.1 + 1.3))  # ends far from zero
    if kind == "scientific":
        x = x * 1e-5
    return t, x


FORMATS = {  # kind: (delimiter, decimal, cell format)
    "fixed": (",", ".", "{:.4f}"),
    "variable %g": (",", ".", "{:g}"),
    "shortest round-trip": (",", ".", "{!r}"),
    "scientific": (",", ".", "{:.6e}"),
    "integers": (",", ".", "{:.0f}"),
    "decimal comma, fixed": (";", ",", "{:.3f}"),
    "decimal comma, %g": (";", ",", "{:g}"),
}


def _text(kind):
    delim, dec, fmt = FORMATS[kind]
    t, x = _record("integers" if kind == "integers" else
                   "scientific" if kind == "scientific" else "wave")
    cell = (lambda v: fmt.format(float(v)).replace(".", dec)) if dec != "." else \
        (lambda v: fmt.format(float(v)))
    lines = [f"time [s]{delim}x [V]"] + [f"{ti:.2f}".replace(".", dec) + delim + cell(v)
                                          for ti, v in zip(t, x, strict=True)]
    return "\n".join(lines), delim, dec  # no final line end


def _digits(cell, dec):
    mant = cell.split("e")[0].lstrip("+-").replace(dec, "")
    return max(len(mant.lstrip("0")), 1)


@pytest.mark.parametrize("kind", list(FORMATS))
def test_complete_last_line_without_line_end_is_accepted(tmp_path, kind):
    text, delim, dec = _text(kind)
    p = tmp_path / "x.csv"
    p.write_text(text)
    tx = read_text(p, delimiter=delim, decimal=dec)
    assert tx.columns[1].size == N
    last = text.rsplit(delim, 1)[1]
    assert tx.columns[1][-1] == pytest.approx(float(last.replace(dec, ".")), rel=1e-15)


@pytest.mark.parametrize("kind", list(FORMATS))
def test_every_cut_inside_the_last_field_is_refused(tmp_path, kind):
    text, delim, dec = _text(kind)
    head, last = text.rsplit(delim, 1)
    p = tmp_path / "x.csv"
    missed = []
    for k in range(1, len(last)):
        cut = last[:k]
        try:
            float(cut.replace(dec, "."))
        except ValueError:
            continue  # '1.2e-' or '-': not a number, refused by the parser
        p.write_text(head + delim + cut)
        try:
            read_text(p, delimiter=delim, decimal=dec)
        except InputError as e:
            assert f"line {N + 1}" in str(e) and "truncated" in str(e)
            continue
        missed.append(cut)
    if "%g" in kind or kind == "shortest round-trip":
        # these formats drop trailing zeros, so a cut that leaves as many significant digits
        # as CUT_SIGNIFICANCE (0.1 %) of the column's own cells have is a complete-looking
        # cell: only those pass, and they are the last few digits (value off by < 0.1 %)
        cells = [line.rsplit(delim, 1)[1] for line in text.split("\n")[1:-1]]
        digits = np.array([_digits(c, dec) for c in cells])
        for c in missed:
            assert np.mean(digits <= _digits(c, dec)) >= 1e-3, c
            assert len(last) - len(c) <= (3 if "%g" in kind else 4), c
            v, w = float(last.replace(dec, ".")), float(c.replace(dec, "."))
            assert abs(w - v) < 1e-3 * abs(v)
        assert len(missed) <= 4
    else:
        assert not missed, missed

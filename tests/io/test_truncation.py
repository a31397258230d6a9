"""A file cut inside its last field is refused whatever the number format; a complete last
line without a final line end is accepted.

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


def _g_file(tmp_path, x, fmt="{:g}"):
    """A %g column (time in the first) without a final line end; returns (path, last cell)."""
    lines = ["time [s],x [V]"] + [f"{i / 100:.2f}," + fmt.format(float(v))
                                   for i, v in enumerate(x)]
    p = tmp_path / "g.csv"
    p.write_text("\n".join(lines))
    return p, lines[-1].rsplit(",", 1)[1]


def _short():
    """Twenty samples of a wave ending at 1.2345 (%g: '1.2345', a dropped sixth digit)."""
    rng = np.random.default_rng(4)
    x = 1.2345 + 0.02 * np.sin(2 * np.pi * (np.arange(20) - 19) / 20)
    x[:-1] += 1e-5 * rng.standard_normal(19)
    return x


def _ramp(start, end, n=N, seed=2):
    """A slowly rising record with noise that ends exactly at ``end``."""
    rng = np.random.default_rng(seed)
    x = np.linspace(start, end, n) + 1e-4 * abs(end - start) * rng.standard_normal(n)
    x[-1] = end
    return x


@pytest.mark.parametrize("end", [10.0012, -10.0012, 100.012, 1.00012])
def test_g_column_whose_last_value_reaches_the_next_decade_is_accepted(tmp_path, end):
    """%g keeps six significant digits: at the next power of ten it writes one decimal fewer
    than every cell before (9.99991 then 10.0012), which is not a cut."""
    p, last = _g_file(tmp_path, _ramp(0.9 * end, end))
    tx = read_text(p)
    assert tx.columns[1][-1] == float(last)


def test_g_column_leaving_exponent_notation_is_accepted(tmp_path):
    """%g writes values below 1e-4 with an exponent and 0.000100012 without: not a cut."""
    p, last = _g_file(tmp_path, _ramp(5e-5, 1.00012e-4))
    assert "e" not in last
    assert read_text(p).columns[1][-1] == float(last)


def test_short_g_column_with_trailing_zeros_dropped_is_accepted(tmp_path):
    """Twenty %g cells say nothing about a digit count: a last value written 1.2345 (its
    sixth digit a dropped zero) among cells of six digits reads."""
    p, last = _g_file(tmp_path, _short())
    assert last == "1.2345"
    assert read_text(p).columns[1][-1] == 1.2345


@pytest.mark.parametrize("case", ["decade", "exponent", "short"])
def test_cut_last_field_of_g_columns_is_refused(tmp_path, case):
    """The same columns cut inside their last field: every cut that moves the value beyond
    the column's course (twice its largest step) or, in a long column, leaves fewer
    significant digits than all but 0.1 % of the cells, is refused."""
    if case == "decade":
        x = _ramp(9.0, 10.0012)
    elif case == "exponent":
        x = _ramp(5e-5, 1.00012e-4)
    else:
        x = _short()
    p, last = _g_file(tmp_path, x)
    head = p.read_text().rsplit(",", 1)[0]
    step = np.max(np.abs(np.diff(x[:-1])))
    refused, kept = [], []
    for k in range(1, len(last)):
        cut = last[:k]
        try:
            v = float(cut)
        except ValueError:
            continue
        p.write_text(head + "," + cut)
        try:
            read_text(p)
            kept.append(cut)
        except InputError as e:
            assert f"line {x.size + 1}" in str(e) and "truncated" in str(e)
            refused.append(cut)
            continue
        # a cut that reads is within the column's course
        assert abs(v - x[-2]) <= 2 * step or len(x) >= 1000, cut
    assert refused, "no cut refused"
    if case == "decade":
        assert {"1", "10", "10."} <= set(refused) and len(kept) <= 3, kept
    if case == "exponent":
        assert {"0", "0.", "0.0001"} <= set(refused) and len(kept) <= 4, kept
    if case == "short":
        # twenty cells: three digits fewer than theirs, or a departure from their course
        assert {"1", "1.", "1.2", "1.23"} == set(refused) and kept == ["1.234"], kept


def test_short_g_column_without_dropped_zeros_reaching_the_next_decade_is_accepted(tmp_path):
    """Nineteen %g cells of five decimals, none with a dropped zero (as a %.5f column would
    be), then 10.0012: four decimals, but as many significant digits; not a cut. Cut to
    10.0 (three digits fewer) it is refused."""
    x = np.r_[9 + (51237 + 2410 * np.arange(19)) / 1e5, 10.0012]  # last digits all 7
    p, last = _g_file(tmp_path, x)
    cells = [line.rsplit(",", 1)[1] for line in p.read_text().split("\n")[1:-1]]
    assert {len(c.split(".")[1]) for c in cells} == {5}  # fixed decimals, like %.5f
    assert last == "10.0012"
    assert read_text(p).columns[1][-1] == 10.0012
    p.write_text(p.read_text()[:-len(last)] + "10.0")
    with pytest.raises(InputError, match="truncated"):
        read_text(p)

"""Delimited text tables (CSV/ASCII) in any declared dialect, read fast and checked thoroughly.

The raw campaign's own format (raw/README.md: one header line of ``name [unit]`` cells, comma,
decimal point) is the default dialect; a laboratory's files may use another delimiter (``;``,
tab, whitespace), a decimal comma, comment and preamble lines, no header row, datetime time
stamps. A UTF-8 byte-order mark, CRLF line ends and trailing blank lines are accepted; a file
cut inside its last field, a malformed cell or a wrong delimiter is an error naming the file,
the line and the column.
"""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from flumekit.docstrings import filler
from flumekit.errors import InputError
from flumekit.io.atomic import atomic_path

#: docstring text that several functions of this module share
_doc = filler(
    comment=("comment : str, optional\n"
             "    Lines starting with this are skipped."),
    delimiter=("delimiter : str, optional\n"
               "    One character, or ``\"whitespace\"``."),
    encoding=("encoding : str, optional\n"
              "    The file's text encoding."),
    path_for_messages=("path : pathlib.Path\n"
                       "    The file, for messages."))

_HEADER = re.compile(r"^\s*(.*?)\s*\[([^\]]*)\]\s*$")


@dataclass(frozen=True)
class Text:
    """A delimited text table: column labels, header units and the raw cells of each column."""

    labels: list[str]  # header names, or "1", "2", ... without a header
    units: list[str | None]  # unit from a 'name [unit]' header cell
    columns: list[np.ndarray]  # float64, or object (strings) for a non-numeric column
    first_line: int  # 1-based file line of the first data row


def _split(line: str, delimiter: str) -> list[str]:
    return line.split() if delimiter == "whitespace" else line.split(delimiter)


def _numeric_line(line: str, delimiter: str, decimal: str) -> bool:
    try:
        [float(c.replace(decimal, ".")) for c in _split(line, delimiter)]
    except ValueError:
        return False
    return True


def _wrong_delimiter(path: Path, line: str, number: int, delimiter: str) -> InputError | None:
    """Diagnose a line without the declared delimiter but with another one: say which to declare."""
    if delimiter == "whitespace" or delimiter in line:
        return None
    for other in (";", "\t", ",", "|"):
        if other != delimiter and other in line:
            shown = {"\t": "\\t"}.get(other, other)
            return InputError(path, f"no '{delimiter}' delimiter in this line, but '{shown}' "
                              f"separates its cells: declare delimiter = '{shown}' in the "
                              "file's dialect ([files.<instrument>] of campaign.toml)",
                              line=number)
    return None


#: a complete last line is refused with at most this probability by the digit-count tests
CUT_SIGNIFICANCE = 1e-3
#: probability that a complete %g cell keeps all its significant digits (its last one is not
#: a dropped zero)
_G_KEPT = 0.9


def _cut_last_cell(body: str, delimiter: str, decimal: str, comment: str,
                   column: np.ndarray) -> str | None:
    """Why the last cell of a file without a final line end looks cut, or None.

    A file cut inside its last field still parses: the cut only removes characters from the
    end of the last number. Whatever the writer's format, that leaves a cell unlike the others
    of its column, each test judging the cell against the format the column's own cells show:

    * an exponent shorter than every other cell's (C writes two digits at least), or none
      where every other cell has one and either the mantissas have fixed decimals (``%e``:
      ``1.234560e-05`` cut to ``1.234560``) or the value leaves the column's course (more than
      twice its largest step from the one before). A ``%g`` column switches to fixed notation
      at 1e-4 (``9.99991e-05`` then ``0.000100012``), its value continuous: accepted;
    * fewer decimals than every other cell, in a column of fixed decimals (``%.4f``:
      ``1.6000`` to ``1.60``). A ``%g`` column within one decade also shows fixed decimals
      when none of its cells has dropped a trailing zero, which a long one cannot do
      (probability ``_G_KEPT`` ** n below ``CUT_SIGNIFICANCE``: n >= 66) but a short one can,
      if none of its decimals ends in a zero (which only ``%f`` writes). There, ``%g`` writing
      the next decade with a decimal fewer (``9.99991`` then ``10.0001``) or a last digit
      that was a zero is no cut: the cell is refused only with three significant digits fewer
      than the others, which a complete ``%g`` cell has with probability 1e-3;
    * in a column of variable decimals (``%g``, shortest round-trip), fewer significant digits
      than nearly every other cell: refused when k of the n other cells have as few or fewer
      and (k + 1) / (n + 1) <= ``CUT_SIGNIFICANCE``, the probability of a complete cell ranking
      so low among cells like it. A column of fewer than 1 / ``CUT_SIGNIFICANCE`` cells cannot
      show that: there, three significant digits fewer than its longest cells (three dropped
      trailing zeros of ``%g``: probability 1e-3);
    * a value farther from the one before than twice the column's largest step between
      consecutive samples, written with fewer digits than the one before (integers, or a cut
      in the integer part: ``1234`` to ``123``).

    A cut that leaves a cell like its column's own (the last two or three digits of a ``%g``
    number, whose trailing zeros are dropped) changes the value by less than its last kept
    digit and cannot be told from a complete line; nor can an integer cut near zero that stays
    within twice the largest step.
    """
    rows = pd.Series(body.split("\n")).str.rstrip("\r")
    rows = rows[rows.str.strip() != ""]
    if comment:
        rows = rows[~rows.str.lstrip().str.startswith(comment)]
    cells = (rows.str.split().str[-1] if delimiter == "whitespace"
             else rows.str.rsplit(delimiter, n=1).str[-1]).str.strip()
    if cells.size < 2:
        return None
    sep = re.escape(decimal)
    parts = cells.str.extract(rf"^[+-]?(?P<i>\d*)(?:{sep}(?P<f>\d*))?(?:[eE][+-]?(?P<e>\d*))?$")
    frac = parts["f"].fillna("")
    has_exp = parts["e"].notna().to_numpy()
    exp = parts["e"].fillna("").str.len().to_numpy()
    dec = frac.str.len().to_numpy()
    digits = np.maximum((parts["i"].fillna("") + frac).str.lstrip("0").str.len().to_numpy(), 1)
    last, cell = cells.size - 1, cells.iloc[-1]
    x = np.asarray(column, dtype=float)
    step = float(np.max(np.abs(np.diff(x[:-1])))) if x.size >= 3 else np.inf
    jump = abs(x[-1] - x[-2]) > 2 * step
    fixed_dec = bool(np.all(dec[:last] == dec[0]))
    if has_exp[:last].all():
        if has_exp[last] and exp[last] < exp[:last].min():
            return (f"the last line ends in {cell!r}, with a shorter exponent than every other "
                    "value of its column")
        if not has_exp[last] and ((fixed_dec and dec[last] == dec[0]) or jump):
            return (f"the last line ends in {cell!r}, without the exponent every other value "
                    "of its column has")
    # k + 1 of n + 1 cells as short: with 1 / CUT_SIGNIFICANCE cells or more, the column's own
    # digit counts judge; with fewer, three digits fewer than its longest cells do
    k = int(np.count_nonzero(digits[:last] <= digits[last]))
    rare = ((k + 1) / (last + 1) <= CUT_SIGNIFICANCE if last + 1 >= 1 / CUT_SIGNIFICANCE
            else 10.0 ** -int(digits[:last].max() - digits[last]) <= CUT_SIGNIFICANCE)
    if fixed_dec:
        # %g never writes a trailing zero after the decimal point: one is proof of %f
        g_like = (bool(np.all(digits[:last] == digits[0])) and _G_KEPT ** last > CUT_SIGNIFICANCE
                  and not frac.iloc[:last].str.endswith("0").any())
        if dec[last] < dec[0] and (not g_like or rare):
            return (f"the last line ends in {cell!r}, with fewer decimals than every other "
                    "value of its column")
    elif rare:
        return (f"the last line ends in {cell!r}, with fewer significant digits "
                f"({digits[last]}) than all but {k} of the {last} other values of its column")
    if jump and digits[last] < digits[last - 1]:
        return (f"the last line ends in {cell!r}, {abs(x[-1] - x[-2]):.6g} from the value "
                f"before it, more than twice the largest step of its column ({step:.6g}), "
                "and with fewer digits")
    return None


def _codec(path: Path, encoding: str) -> str:
    """Return the Python codec of a declared encoding; UTF-8 with its byte-order mark tolerated."""
    import codecs

    try:
        name = codecs.lookup(encoding).name
    except LookupError:
        raise InputError(path, f"unknown encoding {encoding!r} (utf-8, cp1252, latin-1, ...)",
                         field="encoding") from None
    return "utf-8-sig" if name == "utf-8" else name


@_doc
def decode(path: Path, data: bytes, encoding: str = "utf-8") -> str:
    r"""Decode a text file's bytes; an undecodable byte is an error naming its line.

    Parameters
    ----------
    %(path_for_messages)s
    data : bytes
        Its content.
    encoding : str, optional
        The declared encoding (the ``encoding`` key of the file's dialect); a UTF-8
        byte-order mark is accepted.

    Returns
    -------
    str
        The text.

    Raises
    ------
    flumekit.errors.InputError
        For an unknown encoding, or a byte that is not text in it (naming its line).

    Examples
    --------
    >>> decode(Path("a.csv"), "level [m]\n0,5".encode("cp1252"), "cp1252")
    'level [m]\n0,5'
    """
    try:
        return data.decode(_codec(path, encoding))
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        byte = data[e.start:e.start + 1].hex()
        hint = ("declare the file's encoding in its dialect ([files.<instrument>] of "
                'campaign.toml), e.g. encoding = "cp1252" (Windows) or "latin-1"')
        raise InputError(path, f"byte 0x{byte} is not {encoding} text (a binary file, or "
                         f"another encoding?): {hint}", line=line) from None


@_doc
def data_line(path: Path, first_line: int, k: int, *, comment: str = "",
              encoding: str = "utf-8") -> int:
    """Return the file line of a table's data row ``k``, for messages.

    Blank and comment lines between rows are not rows. It reads the file again: for the
    message of an error only.

    Parameters
    ----------
    %(path)s
    first_line : int
        The 1-based file line of the first data row.
    k : int
        The data row, 0-based.
    comment : str, optional
        Lines starting with this are comments.
    %(encoding)s

    Returns
    -------
    int
        The 1-based file line.
    """
    lines = pd.Series(decode(path, path.read_bytes(), encoding).split("\n")[first_line - 1:])
    keep = lines.str.strip() != ""
    if comment:
        keep &= ~lines.str.lstrip().str.startswith(comment)
    rows = np.flatnonzero(keep.to_numpy())
    return first_line + int(rows[k] if k < rows.size else k)


@_doc
def header_labels(path: Path, *, delimiter: str = ",", comment: str = "", skip_lines: int = 0,
                  header: bool = True, encoding: str = "utf-8") -> list[str]:
    """Return the column labels of a table's header line.

    Parameters
    ----------
    path : pathlib.Path
        The file (its first 64 KiB are read).
    %(delimiter)s
    %(comment)s
    skip_lines : int, optional
        Preamble lines before the header.
    header : bool, optional
        Whether a header row names the columns.
    %(encoding)s

    Returns
    -------
    list of str
        The names without their ``[unit]``; ``"1"`` .. ``"n"`` without a header.

    Raises
    ------
    flumekit.errors.InputError
        When the file is missing or empty, or the header holds another delimiter than the
        declared one.
    """
    try:
        text = path.read_bytes()[:1 << 16].decode(_codec(path, encoding), errors="replace")
    except FileNotFoundError:
        raise InputError(path, "file not found") from None
    if not text.strip():
        raise InputError(path, "file is empty")
    lines = text.split("\n")
    i = skip_lines
    while i < len(lines) - 1 and (not lines[i].strip()
                                  or (comment and lines[i].lstrip().startswith(comment))):
        i += 1
    line = lines[i].rstrip("\r") if i < len(lines) else ""
    if header:
        bad = _wrong_delimiter(path, line, i + 1, delimiter)
        if bad:
            raise bad
    cells = _split(line, delimiter)
    if not header:
        return [str(j + 1) for j in range(len(cells))]
    return [_label(c)[0] for c in cells]


def _label(cell: str) -> tuple[str, str | None]:
    """Split a header cell 'name [unit]' into ('name', 'unit'); ('name', None) without brackets."""
    cell = cell.strip().strip('"').strip()
    m = _HEADER.match(cell)
    return (m.group(1), m.group(2).strip()) if m else (cell, None)


@_doc
def read_text(path: str | Path, *, delimiter: str = ",", decimal: str = ".", comment: str = "",
              skip_lines: int = 0, header: bool = True,
              text_columns: tuple[int, ...] = (), encoding: str = "utf-8") -> Text:
    r"""Read a delimited text table and check every cell.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    %(delimiter)s
    decimal : str, optional
        ``"."`` or ``","``.
    %(comment)s
    skip_lines : int, optional
        Preamble lines before the header (or the first row).
    header : bool, optional
        Whether a header row of ``name [unit]`` cells names the columns.
    text_columns : tuple of int, optional
        Columns (0-based) that may hold non-numbers (date-time stamps).
    encoding : str, optional
        The file's text encoding (UTF-8: a lab PC's byte-order mark is accepted).

    Returns
    -------
    Text
        Labels, header units, the columns (float64; object for ``text_columns``) and the
        file line of the first data row.

    Raises
    ------
    flumekit.errors.InputError
        For a missing, empty or undecodable file, a wrong delimiter, a malformed or
        non-finite cell, or a last line cut short; naming the line and the column.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     f = Path(folder) / "probes.csv"
    ...     _ = f.write_text("time [s];WP1 [V]\n0;1,5\n0,04;1,25\n")
    ...     t = read_text(f, delimiter=";", decimal=",")
    >>> t.labels, t.units, t.columns[1], t.first_line
    (['time', 'WP1'], ['s', 'V'], array([1.5 , 1.25]), 2)
    """
    path = Path(path)
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise InputError(path, "file not found") from None
    except IsADirectoryError:
        raise InputError(path, "is a folder, not a file") from None
    text = decode(path, data, encoding)
    if not text.strip():
        raise InputError(path, "file is empty")
    ended = text.endswith("\n")
    lines = text.split("\n", skip_lines + 64)
    # preamble, comment and blank lines before the header (or the first row)
    i = skip_lines
    while i < len(lines) - 1 and (not lines[i].strip()
                                  or (comment and lines[i].lstrip().startswith(comment))):
        i += 1
    if i >= len(lines) or not lines[i].strip():
        raise InputError(path, "no header or data line", line=i + 1)
    head = lines[i].rstrip("\r")
    bad = _wrong_delimiter(path, head, i + 1, delimiter)
    if bad and (header or not _numeric_line(head, delimiter, decimal)):
        raise bad
    if header:
        labels, units = (list(x) for x in zip(*[_label(c) for c in _split(head, delimiter)]))
        if len(set(labels)) != len(labels):
            raise InputError(path, f"duplicate column names in {labels}", line=i + 1)
        first = i + 1
    else:
        first = i
    offset = sum(len(line) + 1 for line in lines[:first])
    body = text[offset:].rstrip()  # trailing blank lines (and CR/LF) are not rows
    if not body:
        raise InputError(path, "no data rows after the header", line=first + 1)
    ncol = len(labels) if header else len(_split(body.split("\n", 1)[0].rstrip("\r"), delimiter))
    if not header:
        labels, units = [str(j + 1) for j in range(ncol)], [None] * ncol
    multi = len(comment) > 1
    rows_text = body
    if multi:  # pandas takes one comment character; longer markers are filtered here
        rows_text = "\n".join(x for x in body.split("\n") if not x.lstrip().startswith(comment))
    dtype = {j: (object if j in text_columns else np.float64) for j in range(ncol)}
    try:
        df = pd.read_csv(io.StringIO(rows_text), header=None, dtype=dtype, engine="c",
                         sep=r"\s+" if delimiter == "whitespace" else delimiter,
                         decimal=decimal, comment=(comment or None) if not multi else None,
                         skip_blank_lines=bool(comment), names=range(ncol))
    except (ValueError, pd.errors.ParserError):
        raise _locate_bad_cell(path, body, first, ncol, delimiter, decimal, text_columns,
                               comment) from None
    num = [j for j in range(ncol) if j not in text_columns]
    values = df[num].to_numpy(dtype=np.float64)
    if not np.all(np.isfinite(values)):
        raise _locate_bad_cell(path, body, first, ncol, delimiter, decimal, text_columns,
                               comment)
    if not ended and ncol - 1 in num:
        rows = body.split("\n")
        problem = _cut_last_cell(body, delimiter, decimal, comment, values[:, -1])
        if problem:
            raise InputError(path, problem + ", and the line has no line end: the file looks "
                             "cut (truncated)", line=first + len(rows))
    columns = [df[j].to_numpy() if j in text_columns else values[:, num.index(j)]
               for j in range(ncol)]
    return Text(labels, units, columns, first + 1)


def _locate_bad_cell(path: Path, body: str, first: int, ncol: int, delimiter: str,
                     decimal: str, text_columns: tuple[int, ...] = (),
                     comment: str = "") -> InputError:
    """Find the first malformed line, once the fast parser failed (the slow path).

    Blank and comment lines are no rows.
    """
    lines = body.split("\n")
    for k, line in enumerate(lines):
        i = first + k + 1
        if comment and (not line.strip() or line.lstrip().startswith(comment)):
            continue
        cells = _split(line.rstrip("\r"), delimiter)
        if len(cells) != ncol:
            bad = _wrong_delimiter(path, line, i, delimiter)
            if bad:
                return bad
            hint = " (truncated file?)" if k == len(lines) - 1 else ""
            return InputError(path, f"{len(cells)} fields, expected {ncol}{hint}", line=i)
        for j, c in enumerate(cells):
            if j in text_columns:
                continue
            try:
                v = float(c.replace(decimal, ".") if decimal != "." else c)
            except ValueError:
                hint = ""
                if decimal == "." and "," in c:
                    hint = " (a decimal comma? declare decimal = ',' in the file's dialect)"
                return InputError(path, f"column {j + 1}: {c!r} is not a number{hint}", line=i)
            if not np.isfinite(v):
                return InputError(path, f"column {j + 1}: non-finite value {c!r}", line=i)
    return InputError(path, "could not be parsed as a numeric table")


@_doc
def check_time(path: Path, time: np.ndarray, sampling_rate: float | None = None,
               first_line: int = 2) -> None:
    """Check that time increases strictly and, if a rate is given, steps by 1/rate (within 1 %).

    Parameters
    ----------
    %(path_for_messages)s
    time : numpy.ndarray
        Time stamps [s].
    sampling_rate : float, optional
        Declared sampling rate [Hz].
    first_line : int, optional
        The file line of the first sample, for messages.

    Raises
    ------
    flumekit.errors.InputError
        Naming the line where time stops increasing or steps otherwise than the rate says
        (an hour's jump is said to be a daylight-saving change).

    Examples
    --------
    >>> check_time(Path("a.csv"), np.array([0.0, 0.04, 0.08]), 25.0)
    >>> check_time(Path("a.csv"), np.array([0.0, 0.04, 0.04]), 25.0)
    Traceback (most recent call last):
    ...
    flumekit.errors.InputError: a.csv, line 4: time is not increasing (0.04 s then 0.04 s)
    """
    if time.size < 2:
        raise InputError(path, "fewer than two samples")
    dt = np.diff(time)

    def clocks(step: float) -> str:
        # local date-times without an offset jump by an hour when the clocks change
        return ("; an hour's jump: local date-times across a daylight-saving change? Declare "
                "timezone in the file's dialect, or write the stamps with their UTC offset"
                if abs(abs(step) - 3600.0) < 60.0 else "")

    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        raise InputError(path, f"time is not increasing ({time[bad[0]]} s then "
                         f"{time[bad[0] + 1]} s){clocks(dt[bad[0]])}",
                         line=int(bad[0]) + first_line + 1)
    if sampling_rate is not None:
        expected = 1.0 / sampling_rate
        off = np.flatnonzero(np.abs(dt - expected) > 0.01 * expected)
        if off.size:
            raise InputError(path, f"sampling interval {dt[off[0]]:.6g} s does not match the "
                             f"declared sampling rate {sampling_rate:g} Hz{clocks(dt[off[0]])}",
                             line=int(off[0]) + first_line + 1)


def write_table(path: str | Path, columns: list[tuple[str, str]], data: np.ndarray,
                fmt: str | list[str] = "%.6f") -> Path:
    """Write an instrument CSV atomically, in the raw campaign's own format.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write.
    columns : list of (str, str)
        (name, unit) of each column: the header cells ``name [unit]``.
    data : numpy.ndarray
        (sample, column), in those units.
    fmt : str or list of str, optional
        ``numpy.savetxt`` format of the cells: one per column, or one for every column.

    Returns
    -------
    pathlib.Path
        The file written, the bytes ``numpy.savetxt`` writes (latin-1).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_table(Path(folder) / "x.csv", [("time", "s"), ("encoder", "counts")],
    ...                        np.array([[0.0, 3.0], [0.01, -2.0]]), fmt=["%.2f", "%d"])
    ...     path.read_text().splitlines()
    ['time [s],encoder [counts]', '0.00,3', '0.01,-2']
    """
    path = Path(path)
    header = ",".join(f"{n} [{u}]" for n, u in columns)
    data = np.asarray(data)
    data = data[:, None] if data.ndim == 1 else data
    fmts = [fmt] * data.shape[1] if isinstance(fmt, str) else list(fmt)
    if len(fmts) != data.shape[1]:
        raise ValueError(f"{len(fmts)} formats for {data.shape[1]} columns")
    line = ",".join(fmts) + "\n"
    with atomic_path(path) as tmp, open(tmp, "w", encoding="latin-1", newline="") as out:
        out.write(header + "\n")
        # one %-formatting of a block of rows at a time (savetxt formats row by row, a Python
        # call per row): the same cells, as Python floats and ints format as numpy's do
        for start in range(0, data.shape[0], _ROWS_PER_BLOCK):
            block = data[start:start + _ROWS_PER_BLOCK]
            out.write((line * block.shape[0]) % tuple(block.ravel().tolist()))
    return path


#: rows formatted at once by :func:`write_table` (a few MB of text)
_ROWS_PER_BLOCK = 20000

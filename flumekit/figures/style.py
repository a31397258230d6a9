"""The package figure style, print sizes, human labels and deterministic figure saving.

Every figure function of :mod:`flumekit.figures` draws inside :func:`style` on a figure from
:func:`new_figure` (one column, 3.5 in, or two columns, 7 in, wide; text >= 8 pt at that size),
and :func:`save` writes it under the same style at 300 dpi (PNG) or as vector graphics (PDF,
SVG) with the same bytes for the same figure: no software version, creation date or random
hash salt in the file.
"""

from __future__ import annotations

import functools
import re
from contextlib import contextmanager
from pathlib import Path

from flumekit.docstrings import doc

#: page widths [in] of a two-column journal layout
ONE_COLUMN = 3.5
TWO_COLUMNS = 7.0
#: the smallest text at print size [pt]
MIN_FONT_SIZE = 8.0
#: the formats :func:`save` writes, with the metadata keys that would carry a version or a date
FORMATS = {
    "png": {"Software": None},
    "pdf": {"Creator": None, "Producer": None, "CreationDate": None},
    "svg": {"Creator": None, "Date": None},
}

STYLE = {
    "figure.dpi": 100,
    "savefig.dpi": 300,
    "font.size": MIN_FONT_SIZE,
    "axes.titlesize": MIN_FONT_SIZE,
    "axes.titlelocation": "left",
    "axes.labelsize": MIN_FONT_SIZE,
    "xtick.labelsize": MIN_FONT_SIZE,
    "ytick.labelsize": MIN_FONT_SIZE,
    "legend.fontsize": MIN_FONT_SIZE,
    "legend.title_fontsize": MIN_FONT_SIZE,
    "figure.titlesize": 9,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
    "lines.linewidth": 1.0,
    "lines.markersize": 4,
    # deterministic vector output: a fixed salt for SVG element ids; TrueType fonts in PDF
    # keep the text editable in a paper's figure
    "svg.hashsalt": "flumekit",
    "svg.fonttype": "path",
    "pdf.fonttype": 42,
    # zlib level of the PDF streams: level 1 writes files about a tenth larger than the
    # default level 6 in a quarter less time (the compression of a figure's dense lines)
    "pdf.compression": 1,
}

#: colours by role, so experiment/model/simulator look the same in every figure
COLOURS = {"experiment": "k", "analytical": "tab:blue", "simulator": "tab:red",
           "incident": "tab:blue", "reflected": "tab:orange", "truth": "tab:green"}


@contextmanager
def style():
    """Apply the package style (matplotlib rc parameters :data:`STYLE`) within the context.

    Yields
    ------
    None
        Figures are built and saved with the package style inside the ``with`` block.
    """
    import matplotlib

    with matplotlib.rc_context(STYLE):
        yield


def styled(function):
    """Make a figure function build its figure in the package style (:func:`style`).

    Text, titles and axes take their fonts and places from the style in force when they are
    made, so a figure drawn outside :func:`style` (in a notebook) would differ from the
    pipeline's. :func:`flumekit.figures.registry.register` applies this to every figure.

    Parameters
    ----------
    function : callable
        Returns a :class:`matplotlib.figure.Figure`.

    Returns
    -------
    callable
        ``function`` called within :func:`style`; same name, docstring and signature.

    Examples
    --------
    >>> import matplotlib
    >>> from flumekit.figures.style import STYLE, styled
    >>> size = styled(lambda: matplotlib.rcParams["font.size"])
    >>> size() == STYLE["font.size"]
    True
    """
    @functools.wraps(function)
    def in_style(*args, **kwargs):
        with style():
            return function(*args, **kwargs)

    return in_style


def new_figure(nrows: int = 1, ncols: int = 1, width: float = TWO_COLUMNS,
               height: float | None = None, row_height: float = 2.2, **kw):
    """Create a figure of ``nrows`` x ``ncols`` axes, not registered with pyplot.

    Parameters
    ----------
    nrows, ncols : int, optional
        Axes grid.
    width : float, optional
        Figure width [in]: :data:`ONE_COLUMN` or :data:`TWO_COLUMNS`.
    height : float, optional
        Figure height [in]; default ``row_height`` per row plus 0.5 in for the title and an
        outside legend.
    row_height : float, optional
        Height per row of axes [in], used when ``height`` is None.
    **kw
        Passed to :meth:`matplotlib.figure.Figure.subplots` (``sharex``, ...).

    Returns
    -------
    fig : matplotlib.figure.Figure
        The figure, constrained layout. No pyplot state: safe in worker processes.
    axes : numpy.ndarray of matplotlib.axes.Axes
        Shape (nrows, ncols).

    Examples
    --------
    >>> from flumekit.figures.style import ONE_COLUMN, new_figure
    >>> fig, axes = new_figure(2, 1, width=ONE_COLUMN)
    >>> axes.shape, [round(float(v), 2) for v in fig.get_size_inches()]
    ((2, 1), [3.5, 4.9])
    """
    from matplotlib.figure import Figure

    if height is None:
        height = row_height * nrows + 0.5  # + the figure title and an outside legend
    with style():
        fig = Figure(figsize=(width, height), layout="constrained")
        axes = fig.subplots(nrows, ncols, squeeze=False, **kw)
    return fig, axes


def figure_axes(ax=None, width: float = TWO_COLUMNS, height: float = 2.4):
    """Return the figure and axes of ``ax`` if given, else of a new one-axes figure.

    Parameters
    ----------
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.
    width : float, optional
        Width of a new figure [in].
    height : float, optional
        Height of a new figure [in].

    Returns
    -------
    fig : matplotlib.figure.Figure
        The figure.
    ax : matplotlib.axes.Axes
        The axes.
    """
    if ax is not None:
        return ax.figure, ax
    fig, axes = new_figure(width=width, height=height)
    return fig, axes[0, 0]


def thin(x, y, width: float = TWO_COLUMNS) -> tuple:
    """Thin a dense line, for drawing only, to the samples a ``width``-inch axes can show.

    At the PNG's resolution an axes at most ``width`` inches wide has ``width`` x 300 pixel
    columns; a line through more samples than four per column is drawn the same from, in each
    column, its first, lowest, highest and last samples (the M4 reduction: the line's vertical
    extent in every column and its joins to the neighbouring columns are kept), plus the
    samples around every gap (NaN), so the gaps stay. A sparser line is returned unchanged.

    Parameters
    ----------
    x : array_like
        Increasing coordinates of the samples (time) [any units].
    y : array_like
        Values, NaN where missing [any units].
    width : float, optional
        Widest the axes can be [in].

    Returns
    -------
    x, y : numpy.ndarray
        The samples kept, in order.

    References
    ----------
    Jugel, U., Jerzak, Z., Hackenbroich, G. & Markl, V. (2014). M4: a visualization-oriented
    time series data aggregation. Proc. VLDB Endowment 7(10), 797-808.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 600, 60001)
    >>> x, y = thin(t, np.sin(t))
    >>> x.size <= 4 * 2100
    True
    """
    import numpy as np

    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    columns = int(np.ceil(width * STYLE["savefig.dpi"]))
    n = x.size
    if n <= 4 * columns or not x[-1] > x[0]:
        return x, y
    col = np.minimum(((x - x[0]) * (columns / (x[-1] - x[0]))).astype(np.int64), columns - 1)
    first = np.flatnonzero(np.r_[True, col[1:] != col[:-1]])
    last = np.r_[first[1:] - 1, n - 1]
    finite = np.isfinite(y)
    sizes = np.diff(np.r_[first, n])

    def first_at(values, extreme):
        """Index of the first sample of each column where ``values`` reaches its extreme."""
        hit = np.flatnonzero(values == np.repeat(extreme.reduceat(values, first), sizes))
        return hit[np.r_[True, col[hit[1:]] != col[hit[:-1]]]]

    # the lowest and highest finite sample of each column (the first of equal ones; a column
    # without a finite sample gives its first sample), in one pass over the samples
    lowest = first_at(np.where(finite, y, np.inf), np.minimum)
    highest = first_at(np.where(finite, y, -np.inf), np.maximum)
    gap_first = np.flatnonzero(~finite & np.r_[True, finite[:-1]])
    gap_last = np.flatnonzero(~finite & np.r_[finite[1:], True])
    keep = np.unique(np.concatenate([first, last, lowest, highest, gap_first, gap_first - 1,
                                     gap_last + 1]))
    keep = keep[(keep >= 0) & (keep < n)]
    return x[keep], y[keep]


# --- human labels -------------------------------------------------------------------------

#: labels of categorical coordinate values (sources of a comparison, regions and control points
#: of the ball-screw PTO model) where replacing underscores by spaces does not read well
VALUE_LABELS = {
    "analytical": "linear model (Renzi & Dias)",
    "simulator": "time-domain simulator",
    "screw_generator": "screw in the generator",
    "screw_in_generator": "screw in the generator",
    "screw_free": "screw, free length",
    "screw_swept": "screw, swept by the nut",
    "screw_under_nut": "screw under the nut",
    "screw_swept_end": "screw, swept end",
}


def value_label(value) -> str:
    """Return a human label for a categorical value.

    Parameters
    ----------
    value : object
        The value (e.g. a PTO configuration's identifier).

    Returns
    -------
    str
        Its label in :data:`VALUE_LABELS`, else the identifier with spaces for underscores.

    Examples
    --------
    >>> from flumekit.figures.style import value_label
    >>> value_label("no_pto")
    'no pto'
    """
    value = str(value)
    return VALUE_LABELS.get(value, value.replace("_", " "))


_POWER = re.compile(r"([A-Za-z]+)(-?\d+)")


def units_text(units: str) -> str:
    """Convert a UDUNITS spelling to axis text: ``"m s-1"`` -> ``"m s$^{-1}$"``, ``"1"`` -> ``"-"``.

    Parameters
    ----------
    units : str
        Units in UDUNITS spelling.

    Returns
    -------
    str
        Mathtext for an axis label.

    Examples
    --------
    >>> from flumekit.figures.style import units_text
    >>> units_text("kg m2"), units_text("1")
    ('kg m$^{2}$', '-')
    """
    if units in ("1", "", None):
        return "-"
    return _POWER.sub(lambda m: f"{m.group(1)}$^{{{m.group(2)}}}$", units)


def long_name(name: str) -> str:
    """Return the registry's long name of a variable, up to its first comma, capitalised.

    Parameters
    ----------
    name : str
        A variable of :mod:`flumekit.conventions`.

    Returns
    -------
    str
        The label text.
    """
    from flumekit.conventions import VARIABLES

    text = VARIABLES[name].long_name.split(",")[0]
    return text[:1].upper() + text[1:]


def label(name: str | None = None, symbol: str | None = None, units: str | None = None,
          text: str | None = None) -> str:
    r"""Compose an axis label "Long name symbol [units]".

    Parameters
    ----------
    name : str, optional
        Registered variable (:mod:`flumekit.conventions`): its long name and units.
    symbol : str, optional
        Mathematical symbol appended to the name (``r"$\theta$"``).
    units : str, optional
        Units in UDUNITS spelling, overriding the registry's (e.g. ``"1"`` for a normalised
        quantity, ``"kN"`` for a scaled one).
    text : str, optional
        Description replacing the registry's long name.

    Returns
    -------
    str
        ``"text symbol [units]"``, with the units as :func:`units_text` writes them.

    Raises
    ------
    ValueError
        If both ``name`` and ``units`` are None.

    Examples
    --------
    >>> from flumekit.figures.style import label
    >>> label(text="Capture factor", symbol="$C_f$", units="1")
    'Capture factor $C_f$ [-]'
    """
    from flumekit.conventions import VARIABLES

    if text is None:
        text = long_name(name) if name is not None else ""
    if units is None:
        if name is None:
            raise ValueError("a label needs a registered name or explicit units")
        units = VARIABLES[name].units
    parts = [p for p in (text, symbol) if p]
    return f"{' '.join(parts)} [{units_text(units)}]"


@doc
def condition(ds) -> str:
    """Describe a run's wave condition, e.g. "T = 3.5 s, H = 0.25 m".

    From a run dataset's ``wave_period``/``wave_height`` (an irregular run's
    "Hm0 = 0.1 m, Tp = 2 s" from ``wave_hm0``, ``wave_tp``, ``wave_te``); undeclared (NaN)
    values are left out.

    Parameters
    ----------
    %(run_dataset)s

    Returns
    -------
    str
        The condition, empty if the dataset declares none.

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.figures.style import condition
    >>> condition(xr.Dataset(coords={"wave_period": 3.5, "wave_height": 0.25}))
    'T = 3.5 s, H = 0.25 m'
    """
    import math

    parts = []
    for name, symbol in (("wave_period", "T = {:g} s"), ("wave_height", "H = {:g} m"),
                         ("wave_hm0", "Hm0 = {:g} m"), ("wave_tp", "Tp = {:g} s"),
                         ("wave_te", "Te = {:g} s")):
        # a run file may leave the height undeclared (NaN): not shown
        if (name in ds.coords or name in ds.variables) and math.isfinite(float(ds[name])):
            parts.append(symbol.format(float(ds[name])))
    return ", ".join(parts)


def run_title(ds, what: str = "") -> str:
    """Compose a figure title naming a run and its condition.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's dataset (``run`` and the wave condition, :func:`condition`).
    what : str, optional
        What the figure shows.

    Returns
    -------
    str
        "What: run T3.50_H0.250_r0 (T = 3.5 s, ...)", capitalised.
    """
    run = str(ds["run"].values) if "run" in ds.variables else ""
    cond = condition(ds)
    who = f"run {run} ({cond})" if run and cond else (f"run {run}" if run else cond)
    text = f"{what}: {who}" if what and who else (what or who)
    return text[:1].upper() + text[1:]


def runs_title(datasets, what: str) -> str:
    """Compose the title of a campaign figure: the number of runs, the periods and heights.

    Parameters
    ----------
    datasets : iterable of xarray.Dataset
        The runs' datasets (:func:`flumekit.figures.groups.runs_of`).
    what : str
        What the figure shows.

    Returns
    -------
    str
        "What: n runs, T = ... s, H = ... m".
    """
    from flumekit.figures.groups import height_of, period_of, runs_of

    runs = runs_of(datasets)
    periods = sorted({period_of(r) for r in runs})
    heights = sorted({height_of(r) for r in runs})

    def span(v, unit):
        return f"{v[0]:g} {unit}" if len(v) == 1 else f"{v[0]:g}-{v[-1]:g} {unit}"

    n = len(runs)
    return (f"{what}: {n} run{'s' if n != 1 else ''}, T = {span(periods, 's')}, "
            f"H = {span(heights, 'm')}")


def title(fig, text: str) -> None:
    """Set the figure's title, left-aligned above every panel, wrapped to the figure's width.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    text : str
        The title; "x = v unit" groups are kept on one line.
    """
    import textwrap

    # about 13 characters per inch at 9 pt; "T = 3.8 s" stays on one line (no-break spaces
    # outside mathtext, where textwrap does not break)
    width = int(fig.get_size_inches()[0] * 13)
    parts = text.split("$")
    parts[::2] = [re.sub(r" ?= ", "\u00a0=\u00a0", p) for p in parts[::2]]
    parts[::2] = [re.sub(r"(\d) (s|m|%|°|K|min|W)\b", "\\1\u00a0\\2", p) for p in parts[::2]]
    text = "$".join(parts)
    lines = [textwrap.fill(line, width) for line in text.split("\n")]
    fig.suptitle("\n".join(lines), x=0.01, ha="left", fontsize=STYLE["figure.titlesize"])


def legend(fig, handles=None, labels=None, ncols: int | None = None, where: str = "lower"):
    """Add one legend for the figure, outside every axes (below them by default).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    handles : list of matplotlib.artist.Artist, optional
        Entries; by default those of all axes (duplicates by label dropped).
    labels : list of str, optional
        Their labels; by default the handles' own.
    ncols : int, optional
        Columns of the legend; by default 1 on the right, else up to 3.
    where : {"lower", "right", "upper"}, optional
        Below the axes, right of them, or above them (only for a figure without a title,
        which takes that place).

    Returns
    -------
    matplotlib.legend.Legend or None
        The legend, None when there is nothing to list.
    """
    if handles is None:
        seen: dict[str, object] = {}
        for ax in fig.axes:
            for h, lab in zip(*ax.get_legend_handles_labels()):
                if not lab.startswith("_"):
                    seen.setdefault(lab, h)
        handles, labels = list(seen.values()), list(seen)
    elif labels is None:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    loc = {"upper": "outside upper center", "right": "outside right center",
           "lower": "outside lower center"}[where]
    if ncols is None:
        ncols = 1 if where == "right" else min(len(handles), 3)
    with style():
        return fig.legend(handles, labels, loc=loc, ncols=ncols)


#: the metadata keys of a figure's title and description, per format
TEXT_KEYS = {"png": ("Title", "Description"), "pdf": ("Title", "Subject"),
             "svg": ("Title", "Description")}


def save(fig, *paths: str | Path, check=None, description: str | None = None) -> list[Path]:
    """Write a figure to each path atomically, in the format of its suffix (png, pdf, svg).

    Saved under the package style (PNG at 300 dpi) with the metadata that would carry a
    software version or a date removed, so the same figure gives the same bytes. The figure's
    title (its suptitle) and ``description`` are written into the file's metadata
    (:data:`TEXT_KEYS`), where the campaign report reads its captions.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    *paths : str or pathlib.Path
        Files to write, one per format.
    check : callable, optional
        Called with the figure once it is drawn at the PNG's resolution, before any file is
        written (e.g. :func:`flumekit.figures.check.assert_passes`); it sees the drawn figure,
        so the check and the PNG share one drawing.
    description : str, optional
        What the figure shows, a sentence.

    Returns
    -------
    list of pathlib.Path
        The paths written.

    Raises
    ------
    ValueError
        A suffix that is not a known format.
    """
    from flumekit.io.atomic import atomic_path

    title = fig._suptitle.get_text().replace("\n", " ") if fig._suptitle is not None else ""

    def metadata(fmt: str) -> dict:
        meta = dict(FORMATS[fmt])
        for key, text in zip(TEXT_KEYS[fmt], (title, description)):
            if text:
                meta[key] = text.replace("\u00a0", " ")
        return meta

    paths = [Path(p) for p in paths]
    for path in paths:
        fmt = path.suffix.lstrip(".").lower()
        if fmt not in FORMATS:
            raise ValueError(f"{path}: figure format '{fmt}' is not one of {sorted(FORMATS)}")
    with style(), _layout_once(fig), _font_subsets_cached(), _mathtext_cached():
        png = _drawn_png(fig, check, metadata("png")) if check is not None or any(
            p.suffix.lower() == ".png" for p in paths) else None
        for path in paths:
            fmt = path.suffix.lstrip(".").lower()
            with atomic_path(path) as tmp:
                if fmt == "png":
                    Path(tmp).write_bytes(png)
                else:
                    fig.savefig(tmp, format=fmt, dpi=STYLE["savefig.dpi"],
                                metadata=metadata(fmt))
    return paths


@contextmanager
def without_collector():
    """Run the block without Python's cyclic garbage collector, then collect what it left.

    A figure creates some hundred thousand small objects (artists, transforms, texts), which
    trigger the collector again and again, each time walking every object of the process:
    in a long-lived worker, a seventh of a figure's time. Here the block's objects are freed
    by their reference counts as usual, and its reference cycles (a figure and its artists)
    by one collection of the youngest generation at the end, which holds every object the
    block created. The collector is left as it was found (another thread's block may have
    switched it off).

    Yields
    ------
    None

    Examples
    --------
    >>> import gc
    >>> with without_collector():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True
    """
    import gc

    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.collect(0)
            gc.enable()


#: deflate level of the PNGs, compressed with zlib-ng: at level 3 it writes files a little
#: smaller than zlib's level 3 in half the time (zlib's default level 6 took twice as long
#: again for files 10 % smaller); encoding a 300 dpi figure cost as much as drawing it
PNG_COMPRESS_LEVEL = 3


def _drawn_png(fig, check=None, metadata=None) -> bytes:
    """Draw the figure once at the PNG's resolution on an Agg canvas, and encode it.

    ``check`` runs on that drawing. The PNG has the pixels ``savefig`` would write and the same
    metadata; an opaque drawing (every figure of the package style) is stored as RGB, without
    the alpha channel that would be 255 everywhere.
    """
    import numpy as np

    dpi = fig.get_dpi()
    canvas = _agg_canvas(fig)
    try:
        fig.set_dpi(STYLE["savefig.dpi"])
        canvas.draw()
        if check is not None:
            check(fig)
        rgba = np.asarray(canvas.buffer_rgba())
        pixels = rgba
        if (rgba[..., 3] == 255).all():
            # a drawing in greys alone (a QC figure without flags) as one grey channel
            grey = (rgba[..., 0] == rgba[..., 1]).all() and (rgba[..., 1] == rgba[..., 2]).all()
            pixels = rgba[..., :1] if grey else rgba[..., :3]
        texts = {k: v for k, v in (metadata or FORMATS["png"]).items() if v is not None}
        return png_bytes(pixels, fig.get_dpi(), texts)
    finally:
        fig.set_dpi(dpi)


def png_bytes(pixels, dpi: float, texts: dict | None = None) -> bytes:
    """Encode a grey, RGB or RGBA image as PNG, each row filtered from the row above.

    One filter for every row (PNG's "Up"), computed at once, instead of the encoder trying
    five filters on each row: half the time of Pillow's encoder for files about the same
    size on the figures' drawings, whose rows repeat the row above (blank space, axes,
    straight lines). The resolution is written in a pHYs chunk, each text in a tEXt chunk
    (an iTXt chunk, UTF-8, for text beyond Latin-1), as Pillow writes them.

    Parameters
    ----------
    pixels : numpy.ndarray
        uint8 image, shape (height, width, bands): 1 (grey), 3 (RGB) or 4 (RGBA); a view of
        some bands of a larger image is read in place.
    dpi : float
        Resolution [pixels per inch].
    texts : dict of str to str, optional
        Text chunks by keyword (Latin-1 keywords).

    Returns
    -------
    bytes
        The PNG file.

    References
    ----------
    W3C (2003). Portable Network Graphics (PNG) Specification (Second Edition), §9 (filtering)
    and §11 (chunks).

    Examples
    --------
    >>> import io
    >>> import numpy as np
    >>> from PIL import Image
    >>> rgb = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    >>> image = Image.open(io.BytesIO(png_bytes(rgb, 300, {"Title": "θ"})))
    >>> bool((np.asarray(image) == rgb).all()), image.text, round(image.info["dpi"][0])
    (True, {'Title': 'θ'}, 300)
    """
    import struct
    import zlib

    import numpy as np
    from zlib_ng import zlib_ng

    pixels = np.asarray(pixels, dtype=np.uint8)
    height, width, bands = pixels.shape
    filtered = np.empty((height, width * bands + 1), np.uint8)
    filtered[:, 0] = 2  # Up: each byte minus the byte above it (modulo 256)
    filtered[0, 0] = 0  # the first row has none above it: unfiltered
    # the filtered rows written through a (height, width, bands) view: no copy of the image
    rows = np.ndarray((height, width, bands), np.uint8, buffer=filtered, offset=1,
                      strides=(filtered.strides[0], bands, 1))
    rows[0] = pixels[0]
    np.subtract(pixels[1:], pixels[:-1], out=rows[1:])

    def chunk(kind: bytes, data: bytes) -> bytes:
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data)))

    per_metre = int(dpi / 0.0254 + 0.5)
    out = [b"\x89PNG\r\n\x1a\n",
           chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, {1: 0, 3: 2, 4: 6}[bands],
                                      0, 0, 0)),
           chunk(b"pHYs", struct.pack(">IIB", per_metre, per_metre, 1))]
    for key, text in (texts or {}).items():
        try:
            out.append(chunk(b"tEXt", key.encode("latin-1") + b"\0" + text.encode("latin-1")))
        except UnicodeEncodeError:
            out.append(chunk(b"iTXt", key.encode("latin-1") + b"\0\0\0\0\0"
                             + text.encode("utf-8")))
    out += [chunk(b"IDAT", zlib_ng.compress(filtered, PNG_COMPRESS_LEVEL)),
            chunk(b"IEND", b"")]
    return b"".join(out)


def _agg_canvas(fig):
    """Return the figure's Agg canvas, giving it one if it has another (or none).

    One canvas, so one renderer at a resolution, for the layout, the titles' places and the
    PNG: matplotlib remembers the extents of texts per renderer, and a figure without a canvas
    of its own gets a new renderer at each layout.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    return fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)


@contextmanager
def laid_out(fig):
    """Keep one layout of ``fig`` within the context.

    Its layout engine runs once (at the PNG's resolution) on entry and not again in each draw
    (the figure check, every format saved), where it is the costliest part of a small figure.
    The engine is restored on exit.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.

    Yields
    ------
    matplotlib.figure.Figure
        ``fig``, laid out.

    Examples
    --------
    >>> from flumekit.figures.style import laid_out, new_figure, save
    >>> fig, axes = new_figure()
    >>> with laid_out(fig):                        # doctest: +SKIP
    ...     save(fig, "a.png", "a.pdf")
    """
    with _layout_once(fig):
        yield fig


@contextmanager
def _layout_once(fig):
    """Run the layout engine once; see :func:`laid_out`.

    Nothing to do for a figure without a layout engine, or one whose layout is already fixed.
    """
    engine = fig.get_layout_engine()
    if engine is None or not hasattr(engine, "execute") or type(engine).__name__ == \
            "PlaceHolderLayoutEngine":
        yield
        return
    dpi = fig.get_dpi()
    fig.set_dpi(STYLE["savefig.dpi"])
    _agg_canvas(fig)
    remembered = _ticks_remembered(fig)
    try:
        with style(), _mathtext_cached():
            engine.execute(fig)
            _boxes_rounded(fig)
            placed = _titles_placed(fig)
            fixed = _ticks_fixed(fig)
    except BaseException:
        remembered()
        raise
    finally:
        fig.set_dpi(dpi)
    # no engine at all, not matplotlib's placeholder for "none": with any engine, savefig
    # draws a vector figure once without output, for the layout, before drawing it
    import matplotlib

    with matplotlib.rc_context({"figure.autolayout": False,
                                "figure.constrained_layout.use": False}):
        fig.set_layout_engine(None)
    try:
        yield
    finally:
        fig.set_layout_engine(engine)
        for ax in placed:
            ax._autotitlepos = True
        for ticker, locator, formatter in fixed:
            ticker.locator, ticker.formatter = locator, formatter
        remembered()


def _ticks_remembered(fig):
    """Let each axis of ``fig`` update its ticks once per state, until the returned call.

    matplotlib updates an axis's ticks (locator, formatter, every tick's place and label)
    whenever anything asks where they are: in a layout pass, each of the axes' four spines, its
    title, and the tick boxes of every axes its labels align with (all rows of a column of
    shared axes) ask again, some ten times per state. While the state the ticks depend on is
    the same (the view and data limits, the axes' box on the canvas, the tickers), the ticks
    are those of the last update, which is returned instead. So are the boxes of the tick
    labels, which every axis of such a column measures again for each of its siblings in each
    draw: the last boxes measured with the same renderer, state and ticks. Returns the call
    that gives the axes their own methods back.
    """
    axes = [axis for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)]

    def remembering(axis):
        cls = type(axis)
        update, measure = cls._update_ticks, cls._get_ticklabel_bboxes
        last: list = [None, []]
        boxes: list = [None, ([], [])]

        def state():
            return (tuple(axis.get_view_interval()), tuple(axis.get_data_interval()),
                    axis.axes.bbox.bounds, axis.major.locator, axis.major.formatter,
                    axis.minor.locator, axis.minor.formatter)

        def _update_ticks():
            now = state()
            if last[0] != now:  # the tickers compare by identity
                last[1] = update(axis)
                last[0] = state()  # an update may set the limits (autoscaling)
            return list(last[1])

        def _get_ticklabel_bboxes(ticks, renderer):
            # the ticks of one state have the places and labels of its update; the renderer
            # (compared by identity, held while the context lasts) gives the resolution
            now = (renderer, renderer.points_to_pixels(1.0), state(), tuple(map(id, ticks)))
            if boxes[0] != now:
                boxes[1] = measure(axis, ticks, renderer)
                boxes[0] = now
            return list(boxes[1][0]), list(boxes[1][1])

        return _update_ticks, _get_ticklabel_bboxes

    for axis in axes:
        axis._update_ticks, axis._get_ticklabel_bboxes = remembering(axis)

    def restore():
        for axis in axes:
            axis.__dict__.pop("_update_ticks", None)
            axis.__dict__.pop("_get_ticklabel_bboxes", None)

    return restore


def _ticks_fixed(fig) -> list:
    """Fix the ticks and tick labels of the laid-out ``fig`` at those matplotlib would find again.

    Every draw (the layout's two passes, the titles' places, the check, each format) asks each
    axis's locator for its ticks and its formatter for their labels (and offset text), which
    depend only on the view limits and the axes' size, both final once laid out. They are
    replaced by the ticks and labels they give there. Colour bars, and axes whose box each draw
    sets again (a fixed aspect ratio, an inset's locator), are left to compute theirs.

    Returns
    -------
    list of tuple
        (ticker, locator, formatter) replaced, to be put back.
    """
    from matplotlib import ticker as mt

    def moved(ax) -> bool:  # the box or limits are set again at each draw
        return (getattr(ax, "_colorbar", None) is not None or ax.get_aspect() != "auto"
                or ax.get_axes_locator() is not None)

    fixed = []
    # a ticker shared with axes drawn otherwise is left as it is
    seen = {id(t) for ax in fig.axes if moved(ax) for axis in (ax.xaxis, ax.yaxis)
            for t in (axis.major, axis.minor)}
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for ticker in (axis.major, axis.minor):  # shared axes share their tickers
                locator, formatter = ticker.locator, ticker.formatter
                if id(ticker) in seen or isinstance(locator, mt.NullLocator):
                    continue
                seen.add(id(ticker))
                locs = locator()
                frozen = _fixed_labels()(formatter.format_ticks(locs), formatter.get_offset())
                ticker.locator, ticker.formatter = mt.FixedLocator(locs), frozen
                ticker.locator.set_axis(axis)
                frozen.set_axis(axis)
                fixed.append((ticker, locator, formatter))
    return fixed


@functools.cache
def _fixed_labels():
    """Return the formatter class of :func:`_ticks_fixed`: the labels and offset text found.

    Made on first use, as matplotlib is imported only when a figure is drawn.
    """
    from matplotlib import ticker as mt

    class FixedLabels(mt.Formatter):
        def __init__(self, labels, offset):
            self.labels, self.offset = list(labels), offset

        def format_ticks(self, values):
            return list(self.labels)

        def __call__(self, x, pos=None):
            return self.labels[pos] if pos is not None and 0 <= pos < len(self.labels) else ""

        def get_offset(self):
            return self.offset

    return FixedLabels


#: decimals of the figure's width and height to which a laid-out axes box is rounded
LAYOUT_DECIMALS = 9


def _boxes_rounded(fig) -> None:
    """Round every axes box the layout engine placed to :data:`LAYOUT_DECIMALS` decimals.

    kiwisolver, the solver of the constrained layout, keys its variables by their address in
    memory, so the order in which it sums their terms depends on the process's history: the
    same figure laid out in two processes can differ in the last bit of a box (2e-16 of the
    figure), enough to change the coordinates a PDF writes with ten decimals. Rounded, the
    boxes are a function of the figure alone; none moves by more than 5e-10 of the figure.
    """
    import numpy as np
    from matplotlib.transforms import Bbox

    for ax in fig.get_axes():
        for original, which in ((True, "original"), (False, "active")):
            box = np.round(ax.get_position(original=original).bounds, LAYOUT_DECIMALS)
            ax._set_position(Bbox.from_bounds(*box), which=which)


def _titles_placed(fig) -> list:
    """Place the axes titles of the laid-out ``fig`` once, and keep them there.

    matplotlib places a title above its axes' top tick labels and offset text in every draw
    (the figure check, each format), updating the ticks of both axes each time; in the final
    layout the place is the same. Returns the axes whose titles were fixed (to be freed), none
    where matplotlib's private placement is not the one expected (another version).
    """
    axes = [ax for ax in fig.axes if getattr(ax, "_autotitlepos", None) is True
            and hasattr(ax, "_update_title_position")]
    if not axes:
        return []
    renderer = _agg_canvas(fig).get_renderer()
    for ax in axes:
        ax._update_title_position(renderer)
        ax._autotitlepos = False
    return axes


#: font subsets embedded in PDFs, by (font file, face, glyphs): the same labels in figure after
#: figure need the same subset, and subsetting a TrueType font (fontTools: parsing its layout
#: tables) costs more than drawing most figures
_SUBSETS: dict = {}
#: characters every subset holds: printable ASCII (the words and numbers that change from one
#: figure to the next), the no-break space of the titles, the minus of negative tick labels,
#: degree, micro, superscripts and the multiplication sign, the Greek letters of symbols
#: (η, θ, ω, Δ), ≈, ±, angle brackets (a mean ⟨P⟩), the combining dot of a time derivative
#: (θ̇) and the Latin ligatures the text layout forms (fi, fl, ffi): a figure that adds one of
#: these to its text does not need a subset of its own
_COMMON = ("".join(map(chr, range(32, 127)))
           + "\u00a0\u2212\u00b0\u00b5\u00b2\u00b3\u00d7"
           + "".join(map(chr, range(0x3b1, 0x3ca))) + "\u0393\u0394\u0398\u039b\u039e\u03a0"
           "\u03a3\u03a6\u03a8\u03a9" + "\u2248\u00b1\u27e8\u27e9\u0307"
           + "\ufb00\ufb01\ufb02\ufb03\ufb04")


@functools.cache
def _common_glyphs(path: str, face: int) -> frozenset:
    """Glyph indices of the :data:`_COMMON` characters that the font ``path`` has."""
    from fontTools.ttLib import TTFont

    with TTFont(path, fontNumber=face, lazy=True) as font:
        cmap = font.getBestCmap() or {}
        return frozenset(font.getGlyphID(cmap[ord(c)]) for c in _COMMON if ord(c) in cmap)


#: tables of a TrueType font that the font a PDF embeds (FontFile2) never reads: OpenType
#: layout (substitution, positioning, kerning, the math layout; the PDF places every glyph
#: itself, and subsetting them was two thirds of the time of a subset) and FontForge's time
#: stamp, which the subsetter cannot subset (it would say so on standard error)
_DROPPED_TABLES = ["GSUB", "GPOS", "GDEF", "kern", "MATH", "BASE", "JSTF", "FFTM"]


def _font_subset(path: str, face: int, glyphs: frozenset) -> tuple[bytes, dict]:
    """Subset the TrueType font ``path`` to ``glyphs``, without the tables a PDF never reads.

    Returns the subset font's file and the map from the font's glyph indices to the subset's.
    """
    from io import BytesIO

    from fontTools import subset

    options = subset.Options(glyph_names=True, recommended_glyphs=True, font_number=face,
                             layout_features=[])
    options.drop_tables += _DROPPED_TABLES
    with subset.load_font(path, options) as font:
        subsetter = subset.Subsetter(options=options)
        subsetter.populate(gids=set(glyphs))
        subsetter.subset(font)
        out = BytesIO()
        font.save(out)
        return out.getvalue(), dict(subsetter.glyph_index_map)


@contextmanager
def _font_subsets_cached():
    """Subset the TrueType fonts embedded in PDFs once per glyph set, within the context.

    Per font and glyph set (``pdf.fonttype`` 42), for the life of the process, without the
    layout tables (:data:`_DROPPED_TABLES`). Every subset, computed or remembered, is embedded
    from its saved bytes: the PDF has the same bytes whichever figure came first. Where
    matplotlib's private subsetting helpers are not the ones expected (another matplotlib
    version), nothing is changed.
    """
    try:
        from io import BytesIO

        from fontTools.ttLib import TTFont
        from matplotlib.backends import _backend_pdf_ps as pdf_ps

        original, as_file = pdf_ps.get_glyphs_subset, pdf_ps.font_as_file
        results = pdf_ps.SubsetResults
        results._as_cm  # noqa: B018 - the context manager this version returns
    except (ImportError, AttributeError):
        yield
        return
    saved: dict[int, tuple] = {}  # id of a subset font handed out -> (font, its file)

    def subset(fontfile, glyphs):
        face = getattr(fontfile, "face_index", 0)
        # with the glyphs of every figure's common characters, one subset serves nearly all
        # figures (numbers and titles change the exact set from one figure to the next)
        glyphs = frozenset(glyphs) | _common_glyphs(str(fontfile), face)
        key = (str(fontfile), face, glyphs)
        if key not in _SUBSETS:
            _SUBSETS[key] = _font_subset(str(fontfile), face, glyphs)
        data, index = _SUBSETS[key]
        # re-read as it was written: no new time stamp or bounds (the subsetter sets neither)
        font = TTFont(BytesIO(data), recalcBBoxes=False, recalcTimestamp=False)
        saved[id(font)] = (font, data)
        return results(font, dict(index))._as_cm()

    def font_file(font):
        # the subset's own file, not the font compiled again from its tables
        known = saved.get(id(font))
        return BytesIO(known[1]) if known is not None and known[0] is font else as_file(font)

    pdf_ps.get_glyphs_subset, pdf_ps.font_as_file = subset, font_file
    try:
        yield
    finally:
        pdf_ps.get_glyphs_subset, pdf_ps.font_as_file = original, as_file


@functools.lru_cache(maxsize=4096)
def _mathtext_parse(output_type: str, s: str, dpi: float, prop, antialiased: bool,
                    load_glyph_flags):
    """One parse of mathtext ``s``, shared by every parser of ``output_type`` in the process."""
    from matplotlib.mathtext import MathTextParser

    parser = MathTextParser("path" if output_type == "vector" else "agg")
    return _MATHTEXT_PARSE(parser, s, dpi, prop, antialiased, load_glyph_flags)


@contextmanager
def _mathtext_cached():
    """Share the mathtext parses of every renderer within the context.

    Each matplotlib renderer has its own parsers, whose parses are remembered per parser: every
    new figure, and each of its formats, parsed its labels, log-scale tick labels and units
    again (pyparsing: a few milliseconds a string). Here a parse is remembered per string, size,
    font and resolution for the life of the process; it is the parse of the string, whichever
    parser asks. Where matplotlib's private parse cache is not the one expected (another
    matplotlib version), nothing is changed.
    """
    global _MATHTEXT_PARSE
    try:
        from matplotlib.mathtext import MathTextParser

        original = MathTextParser.__dict__["_parse_cached"]
        _MATHTEXT_PARSE = original.__wrapped__
    except (ImportError, KeyError, AttributeError):
        yield
        return

    def cached(self, s, dpi, prop, antialiased, load_glyph_flags):
        return _mathtext_parse(self._output_type, s, dpi, prop, antialiased, load_glyph_flags)

    MathTextParser._parse_cached = cached
    try:
        yield
    finally:
        MathTextParser._parse_cached = original


#: matplotlib's own parse, uncached (set by :func:`_mathtext_cached`)
_MATHTEXT_PARSE = None

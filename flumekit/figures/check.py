"""The figure test: what every flumekit figure must satisfy before it is saved.

:func:`problems` lists what is wrong with a matplotlib figure at its saved size: a width that
is neither one (3.5 in) nor two (7 in) journal columns, text smaller than 8 pt or cut at the
figure's edge, an axes with nothing drawn in it or hidden (a hole in the layout), an axis
whose tick labels are shown without a label giving units in square brackets, a legend that
overlaps an axes' data area or the title, no figure title (which names the run(s) and
condition), panels lettered other than (a), (b), ... in the order of the axes.
"""

from __future__ import annotations

import re

from flumekit.figures.style import MIN_FONT_SIZE, ONE_COLUMN, TWO_COLUMNS

_UNITS = re.compile(r"\[[^\]]+\]")
_LETTER = re.compile(r"^\(([a-z])\)")
#: tallest figure that fits a page with its caption [in]
MAX_HEIGHT = 9.0


def _drawn(ax) -> bool:
    """Tell whether ``ax`` shows data.

    A line, a collection (scatter, contour, mesh), an image or a patch (bars, polygons) other
    than the axes background.
    """
    return bool(ax.lines or ax.collections or ax.images or ax.patches)


def _inside(box, page, tol: float = 1.0) -> bool:
    """Whether ``box`` lies within ``page`` up to ``tol`` pixels."""
    return (box.x0 >= page.x0 - tol and box.y0 >= page.y0 - tol and box.x1 <= page.x1 + tol
            and box.y1 <= page.y1 + tol)


def _undrawn_tick_labels(axis):
    """Labels of ticks outside the view interval: a locator places them, nothing draws them."""
    lo, hi = sorted(axis.get_view_interval())
    eps = 1e-9 * max(abs(lo), abs(hi), 1e-300)
    for tick in axis.get_major_ticks() + axis.get_minor_ticks():
        if not lo - eps <= tick.get_loc() <= hi + eps:
            yield tick.label1
            yield tick.label2


def _tick_labels_shown(axis) -> bool:
    return any(t.get_visible() and t.get_text() for t in axis.get_ticklabels())


def _labelled(ax, which: str) -> str:
    """Return the label of ``ax``'s x or y axis, or of a sibling sharing it.

    A shared grid labels its outer axes only.
    """
    own = getattr(ax, f"get_{which}label")()
    if own:
        return own
    siblings = getattr(ax, f"get_shared_{which}_axes")().get_siblings(ax)
    return next((getattr(s, f"get_{which}label")() for s in siblings
                 if getattr(s, f"get_{which}label")()), "")


def problems(fig) -> list[str]:
    """List everything that fails the figure test, as readable sentences.

    Checked at the saved resolution (on the PNG's drawing when the figure was just drawn
    by :func:`flumekit.figures.style.save`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure, at its saved size.

    Returns
    -------
    list of str
        The problems (module notes), empty when the figure passes.

    Examples
    --------
    >>> from flumekit.figures.check import problems
    >>> from flumekit.figures.style import new_figure
    >>> fig, axes = new_figure(width=5.0)
    >>> problems(fig)[0]
    'width 5.00 in is neither one column (3.5 in) nor two (7.0 in)'
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from flumekit.figures.style import STYLE

    dpi = fig.get_dpi()
    canvas = fig.canvas
    drawn = (isinstance(canvas, FigureCanvasAgg) and not fig.stale
             and dpi == STYLE["savefig.dpi"] and canvas.get_renderer().dpi == dpi)
    if drawn:  # drawn as it is saved (flumekit.figures.style.save): checked on that drawing
        return _problems(fig, canvas)
    # at the saved resolution: the layout and the text extents checked are the PNG's
    fig.set_dpi(STYLE["savefig.dpi"])
    try:
        canvas = FigureCanvasAgg(fig)  # a figure built without pyplot has no renderer of its own
        # lays the figure out and fills in the tick labels, without painting a pixel
        fig.draw_without_rendering()
        return _problems(fig, canvas)
    finally:
        fig.set_dpi(dpi)


def _problems(fig, canvas) -> list[str]:
    """:func:`problems` of a figure laid out on ``canvas``."""
    from matplotlib.text import Text

    out: list[str] = []
    width, height = fig.get_size_inches()
    if not any(abs(width - w) < 0.01 for w in (ONE_COLUMN, TWO_COLUMNS)):
        out.append(f"width {width:.2f} in is neither one column ({ONE_COLUMN} in) nor two "
                   f"({TWO_COLUMNS} in)")
    if height > MAX_HEIGHT:
        out.append(f"height {height:.2f} in exceeds a page ({MAX_HEIGHT} in)")
    small = sorted({f"'{t.get_text()[:30]}' ({t.get_fontsize():.1f} pt)"
                    for t in fig.findobj(Text)
                    if t.get_visible() and t.get_text().strip()
                    and t.get_fontsize() < MIN_FONT_SIZE - 1e-6})
    if small:
        out.append(f"text below {MIN_FONT_SIZE:g} pt: " + ", ".join(small[:5]))
    sup = fig._suptitle  # no public getter; the title is the figure's own Text
    if sup is None or not sup.get_text().strip():
        out.append("no figure title naming the run(s) and condition")
    renderer = canvas.get_renderer()
    page = fig.bbox
    hidden = {id(t) for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)
              for t in _undrawn_tick_labels(axis)}
    cut = sorted({f"'{t.get_text()[:30]}'" for t in fig.findobj(Text)
                  if t.get_visible() and t.get_text().strip() and id(t) not in hidden
                  and not _inside(t.get_window_extent(renderer), page, fig.dpi / 100)})
    if cut:
        out.append("text cut at the figure's edge: " + ", ".join(cut[:5]))
    boxes = []
    for i, ax in enumerate(fig.axes):
        name = ax.get_title(loc="left") or ax.get_title() or f"axes {i}"
        if not ax.get_visible():
            out.append(f"{name}: hidden axes (leaves a hole in the layout)")
            continue
        if not _drawn(ax):
            out.append(f"{name}: empty axes")
        for which in "xy":
            if not _tick_labels_shown(getattr(ax, f"{which}axis")):
                continue
            text = _labelled(ax, which)
            if not text:
                out.append(f"{name}: {which} axis has no label")
            elif not _UNITS.search(text):
                out.append(f"{name}: {which} label '{text}' gives no units in [brackets]")
        if not getattr(ax, "_colorbar", None):
            boxes.append((name, ax.get_window_extent(renderer)))
    # each file's panels lettered from (a) in order: a reader refers to them by these letters
    letters = [m.group(1) for ax in fig.axes if ax.get_visible()
               for m in [_LETTER.match(ax.get_title(loc="left") or ax.get_title())] if m]
    if letters and letters != [chr(ord("a") + k) for k in range(len(letters))]:
        out.append(f"panels lettered ({'), ('.join(letters)}), not from (a) in order")
    legends = list(fig.legends) + [ax.get_legend() for ax in fig.axes if ax.get_legend()]
    for leg in legends:
        box = leg.get_window_extent(renderer)
        if sup is not None and sup.get_text() and box.overlaps(sup.get_window_extent(renderer)):
            out.append("legend overlaps the figure title")
        for name, axbox in boxes:
            if box.overlaps(axbox):
                out.append(f"legend overlaps the data area of {name}")
    return out


def assert_passes(fig, what: str = "figure") -> None:
    """Raise ``ValueError`` listing every problem of ``fig`` (see :func:`problems`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure, at its saved size.
    what : str, optional
        Name of the figure in the message.

    Raises
    ------
    ValueError
        The figure fails the figure test.
    """
    found = problems(fig)
    if found:
        raise ValueError(f"{what} fails the figure test: " + "; ".join(found))

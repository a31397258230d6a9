"""One static HTML page for a processed campaign: ``flumekit report``.

The page lives in the processed folder (``processed/<pipeline>/report.html``) and links the
figures and datasets beside it by relative paths, so it opens from disk or any copy of the
folder, with no server, script or network. It shows the run conditions (one row per run), the
summary statistics of every campaign dataset, the warnings the campaign datasets carry
(``flumekit_warnings``), the counts of every quality-control flag (any
variable with CF ``flag_values`` and ``flag_meanings`` in a campaign dataset or under ``qc/``),
every figure, and a link to every dataset. Same processed folder, same bytes: nothing depends
on the clock or absolute paths.
"""

from __future__ import annotations

import html
from pathlib import Path

import numpy as np
import xarray as xr

from flumekit import __version__
from flumekit.errors import InputError
from flumekit.io.atomic import atomic_path

__all__ = ["REPORT_NAME", "write_report"]

REPORT_NAME = "report.html"
#: the per-run conditions, in the order of the table: (dataset, variable)
CONDITIONS = (("waves_summary", "wave_period"), ("waves_summary", "wave_height"),
              ("waves_summary", "measured_period"), ("waves_summary", "incident_height"),
              ("waves_summary", "reflection_coefficient"), ("flap_summary", "theta_amplitude"),
              ("flap_summary", "mean_power"), ("flap_summary", "capture_factor"))
#: the irregular runs' sea states and performance, in the order of their table
SEA_STATES = (("waves_summary", "wave_hm0"), ("waves_summary", "wave_tp"),
              ("waves_summary", "wave_te"), ("waves_summary", "hm0"), ("waves_summary", "tp"),
              ("waves_summary", "te"), ("waves_summary", "reflection_coefficient"),
              ("waves_summary", "low_frequency_energy_fraction"),
              ("flap_summary", "mean_power"), ("flap_summary", "capture_width_ratio"))
IMAGE_SUFFIXES = (".png", ".svg", ".jpg", ".jpeg")

_CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;margin:2em auto;max-width:72em;
padding:0 1em;color:#222}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}
th,td{border:1px solid #ddd;padding:.25em .6em;text-align:right}
th{background:#f3f3f3}td.l,th.l{text-align:left}
figure{display:inline-block;margin:.5em;vertical-align:top;max-width:100%}
figure img{width:100%;border:1px solid #eee}
figcaption{font-size:.85em;color:#555}
nav a{margin-right:1em}.muted{color:#777}
"""


def _esc(x) -> str:
    return html.escape(str(x), quote=True)


def _fmt(v) -> str:
    if isinstance(v, (float, np.floating)):
        return "" if not np.isfinite(v) else f"{v:.4g}"
    return _esc(v)


def _label(var: xr.DataArray) -> str:
    name = var.attrs.get("long_name", var.name)
    units = var.attrs.get("units")
    return f"{name} [{units}]" if units not in (None, "", "1") else str(name)


def _table(header: list[str], rows: list[list[str]], left: int = 1) -> str:
    th = "".join(f'<th class="l">{h}</th>' if i < left else f"<th>{h}</th>"
                 for i, h in enumerate(header))
    body = "".join("<tr>" + "".join(f'<td class="l">{c}</td>' if i < left else f"<td>{c}</td>"
                                    for i, c in enumerate(r)) + "</tr>" for r in rows)
    return f"<table><thead><tr>{th}</tr></thead><tbody>{body}</tbody></table>"


def _open(path: Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _conditions(summaries: dict[str, xr.Dataset], table=CONDITIONS, irregular=False) -> str:
    """Tabulate the conditions ``table``, one row per run.

    The regular runs (a target period), or the irregular ones (a target Hm0).
    """
    cols = [(d, v) for d, v in table if d in summaries and v in summaries[d].variables]
    if not cols:
        return ("" if irregular else
                '<p class="muted">No run summary (waves_summary.nc) in this folder.</p>')
    first = summaries[cols[0][0]]
    key = "wave_hm0" if irregular else "wave_period"
    if key in first.coords and first[key].ndim == 1:
        runs = first["run"].values[np.isfinite(first[key].values)]
    else:
        runs = np.array([]) if irregular else first["run"].values
    if runs.size == 0:
        return ""
    header = ["run"] + [_esc(_label(summaries[d][v])) for d, v in cols]
    rows = []
    for r in runs:
        row = [_esc(r)]
        for d, v in cols:
            ds = summaries[d]
            row.append(_fmt(ds[v].sel(run=r).values.item()) if r in ds["run"].values else "")
        rows.append(row)
    return _table(header, rows)


def _statistics(name: str, ds: xr.Dataset) -> str:
    rows = []
    for v, var in ds.data_vars.items():
        if var.dtype.kind not in "fiu" or "flag_values" in var.attrs or var.size == 0:
            continue
        # one row per value of a small extra dimension (e.g. comparison's "source"), not one
        # statistic pooled over experiment and models
        other = [d for d in var.dims if d != "run"]
        groups = ([(f"{other[0]} = {c}", var.sel({other[0]: c}))
                   for c in var[other[0]].values]
                  if len(other) == 1 and other[0] in var.coords and var.sizes[other[0]] <= 10
                  else [("", var)])
        for tag, sub in groups:
            x = np.asarray(sub.values, dtype=float).ravel()
            x = x[np.isfinite(x)]
            if x.size:
                rows.append([_esc(v) + (f" ({_esc(tag)})" if tag else ""), _esc(_label(var)),
                             str(x.size), _fmt(x.mean()), _fmt(x.std()), _fmt(x.min()),
                             _fmt(x.max())])
    if not rows:
        return ""
    return (f"<h3>{_esc(name)}</h3>"
            + _table(["variable", "quantity", "n", "mean", "std", "min", "max"], rows, left=2))


def _power_matrix(summaries: dict[str, xr.Dataset]) -> str:
    """Tabulate the power matrix (IEC TS 62600-100), one table per source.

    The cells' mean capture width ratio and mean power with their number of runs, Hm0 bins
    down and Te bins across.
    """
    ds = summaries.get("power_matrix")
    if ds is None or "capture_width_ratio" not in ds:
        return ""
    hm0, te = (d for d in ds["capture_width_ratio"].dims if d != "source")
    out = []
    for src in ds["source"].values:
        cell = ds.sel(source=src)
        header = ["H<sub>m0</sub> [m] \\ T<sub>e</sub> [s]"] + [
            _esc(_bin(ds, te, j)) for j in range(ds.sizes[te])]
        rows = []
        for i in range(ds.sizes[hm0]):
            row = [_esc(_bin(ds, hm0, i))]
            for j in range(ds.sizes[te]):
                c = cell.isel({hm0: i, te: j})
                n = int(c["run_count"]) if "run_count" in c else 0
                row.append("" if n == 0 else
                           f"{_fmt(float(c['capture_width_ratio']))} "
                           f"({_fmt(float(c['mean_power']))} W, n = {n})"
                           if "mean_power" in c else f"{_fmt(float(c['capture_width_ratio']))}")
            rows.append(row)
        out.append(f"<h3>{_esc(_value(src))}</h3>" + _table(header, rows))
    return ("<p>Cells: mean capture width ratio (mean absorbed power, number of runs); the "
            "standard deviations (ddof = 0) are in power_matrix.nc.</p>" + "".join(out))


def _bin(ds: xr.Dataset, dim: str, i: int) -> str:
    """Label bin ``i`` of ``dim``: 'lo-hi' from its CF bounds, else its centre."""
    bounds = ds[dim].attrs.get("bounds")
    if bounds and bounds in ds:
        lo, hi = (float(v) for v in ds[bounds].values[i])
        return f"{lo:.3g}-{hi:.3g}"
    return f"{float(ds[dim].values[i]):.3g}"


def _value(v) -> str:
    from flumekit.figures.style import value_label

    return value_label(v)


def _uncertainty(summaries: dict[str, xr.Dataset]) -> list[tuple[str, str, str]]:
    """Give the sections of the results per condition with their uncertainties and budgets.

    Those of :func:`flumekit.uncertainty.report_sections`, where the campaign has them.
    """
    if "conditions" not in summaries:
        return []
    from flumekit.uncertainty import report_sections

    return report_sections(summaries["conditions"], summaries.get("budget"))


def _notes(root: Path) -> str:
    """List the notes the per-run products carry in their attributes, with their runs.

    A fitted parameter held at its bound: the flap's pressure model of Eq. 13.
    """
    from flumekit.io.run_files import text_attributes

    where: dict[str, list[str]] = {}
    files = sorted((root / "flap").glob("*.nc"))
    for p, note in zip(files, text_attributes(files, "pressure_fit_bounded"), strict=True):
        if note:
            where.setdefault(f"flap pressure fit (I_p, K_p of Eq. 13): {note}", []).append(p.stem)
    if not where:
        return '<p class="muted">No fitted parameter at a bound.</p>'
    return _table(["note", "runs"], [[_esc(n), _esc(", ".join(r))] for n, r in where.items()])


def _qc_counts(summaries: dict[str, xr.Dataset]) -> str:
    """Tabulate the QC summary: per run and record, the samples of each QARTOD flag.

    From ``qc_summary.nc`` (its ``<record>_qc_count`` over ``flag_meaning``); empty without it.
    """
    ds = summaries.get("qc_summary")
    if ds is None or "flag_meaning" not in ds.dims:
        return ""
    names = [v for v in ds.data_vars if v.endswith("_qc_count")]
    meanings = [str(m) for m in ds["flag_meaning"].values]
    rows = []
    for r in ds["run"].values:
        for v in names:
            counts = ds[v].sel(run=r).values
            rows.append([_esc(r), _esc(v.removesuffix("_qc_count")),
                         *(str(int(c)) if np.isfinite(c) else "" for c in counts)])
    return ("<p>Samples per QARTOD flag of every run's records (qc_summary.nc); the per-sample "
            "flags are in qc/&lt;record&gt;/&lt;run&gt;.nc and drawn in figures/qc.</p>"
            + _table(["run", "record", *(_esc(m.replace("_", " ")) for m in meanings)],
                     rows, left=2))


def _flag_counts(datasets: dict[str, xr.Dataset]) -> str:
    rows = []
    for name, ds in datasets.items():
        for v, var in ds.variables.items():
            values, meanings = var.attrs.get("flag_values"), var.attrs.get("flag_meanings")
            if values is None or meanings is None:
                continue
            data = np.asarray(var.values).ravel()
            for fv, meaning in zip(np.atleast_1d(values), str(meanings).split()):
                rows.append([_esc(name), _esc(v), _esc(meaning), str(int(np.sum(data == fv)))])
    if not rows:
        return '<p class="muted">No quality-control flags in the processed datasets.</p>'
    return _table(["dataset", "variable", "flag", "count"], rows, left=3)


def _warnings(datasets: dict[str, xr.Dataset]) -> str:
    """List the warnings of the campaign datasets, once each, with the datasets carrying them.

    Their ``flumekit_warnings`` attribute: each run's warnings gathered by the summaries.
    """
    where: dict[str, list[str]] = {}
    for name, ds in datasets.items():
        for w in str(ds.attrs.get("flumekit_warnings", "")).splitlines():
            if w.strip():
                where.setdefault(w.strip(), []).append(name)
    if not where:
        return '<p class="muted">No warnings.</p>'
    return (f"<p>{len(where)} warning(s): the analysis went on, but check these.</p>"
            + _table(["warning", "datasets"],
                     [[_esc(w), _esc(", ".join(d))] for w, d in where.items()]))


def _figures(root: Path) -> str:
    images = sorted(p for p in root.rglob("*") if p.suffix.lower() in IMAGE_SUFFIXES)
    # one image per figure: the PNG where a figure is also written as SVG or PDF
    seen: dict[Path, Path] = {}
    for p in images:
        key = p.with_suffix("")
        if key not in seen or p.suffix.lower() == ".png":
            seen[key] = p
    if not seen:
        return '<p class="muted">No figures in this folder (run `flumekit make`).</p>'
    out = []
    for p in sorted(seen.values()):
        rel = p.relative_to(root).as_posix()
        others = sorted(q.relative_to(root).as_posix()
                        for q in p.parent.glob(p.stem + ".*")
                        if q != p and q.suffix.lower() in (".pdf", ".svg"))
        links = "".join(f' <a href="{_esc(o)}">{_esc(Path(o).suffix[1:].upper())}</a>'
                        for o in others)
        meta = _png_text(p) if p.suffix.lower() == ".png" else {}
        # the title as a sentence of its own, then what the figure shows
        parts = [_plain(meta[k]).strip() for k in ("Title", "Description") if meta.get(k)]
        caption = " ".join(_esc(t if t.endswith((".", ":", "?", "!")) or t is parts[-1]
                                else t + ".") for t in parts)
        width = _png_width(p) if p.suffix.lower() == ".png" else None
        size = f' style="width:{width:.2f}in"' if width else ""
        out.append(f'<figure id="{_esc(rel)}"{size}><a href="{_esc(rel)}">'
                   f'<img src="{_esc(rel)}" alt="{_esc(meta.get("Title", p.stem))}" '
                   f'loading="eager"></a><figcaption>{caption or _esc(p.stem)} '
                   f'<span class="muted">({_esc(rel)}{links})</span></figcaption></figure>')
    return "\n".join(out)


_GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "Delta": "Δ", "eta": "η",
          "theta": "θ", "lambda": "λ", "mu": "μ", "nu": "ν", "pi": "π", "rho": "ρ",
          "sigma": "σ", "tau": "τ", "phi": "φ", "omega": "ω", "approx": "≈", "times": "×",
          "langle": "⟨", "rangle": "⟩", "dot": "", "ddot": "", "mathrm": "", ",": " "}


def _plain(text: str) -> str:
    """Turn a figure title or docstring sentence into plain text.

    Matplotlib's mathtext (``$H_{m0}$``) and reStructuredText markup (``:func:`x```,
    ````x````) undone.
    """
    import re

    def math(m):
        t = re.sub(r"\\([A-Za-z]+|,)", lambda g: _GREEK.get(g.group(1), g.group(1)), m.group(1))
        return re.sub(r"[{}]", "", t.replace("_", "").replace("^", ""))

    text = re.sub(r"\$([^$]*)\$", math, text)
    text = re.sub(r":[a-z]+:`~?([^`]*)`", lambda m: m.group(1).split(".")[-1], text)
    return text.replace("``", "")


def _png_chunks(path: Path):
    """Yield (type, data) of each chunk of a PNG file, up to its image data."""
    import struct

    with open(path, "rb") as fh:
        if fh.read(8) != b"\x89PNG\r\n\x1a\n":
            return
        while True:
            head = fh.read(8)
            if len(head) < 8:
                return
            length, kind = struct.unpack(">I4s", head)
            if kind == b"IDAT":
                return
            yield kind, fh.read(length)
            fh.read(4)  # CRC


def _png_text(path: Path) -> dict[str, str]:
    """Read the text chunks of a PNG.

    The title and description :func:`flumekit.figures.style.save` writes.
    """
    out = {}
    for kind, data in _png_chunks(path):
        if kind == b"tEXt" and b"\0" in data:
            key, _, value = data.partition(b"\0")
            out[key.decode("latin-1")] = value.decode("latin-1")
        elif kind == b"iTXt" and b"\0" in data:
            key, _, rest = data.partition(b"\0")
            # compression flag and method, language tag, translated keyword, then the text
            parts = rest[2:].split(b"\0", 2)
            if len(parts) == 3 and rest[0] == 0:
                out[key.decode("latin-1")] = parts[2].decode("utf-8")
    return out


def _png_width(path: Path) -> float | None:
    """Give the printed width of a PNG [in]: its pixels over its resolution (pHYs).

    A column figure then shows at a column's width and a page-width one at a page's.
    """
    import struct

    size = dpm = None
    for kind, data in _png_chunks(path):
        if kind == b"IHDR":
            size = struct.unpack(">I", data[:4])[0]
        elif kind == b"pHYs" and data[8] == 1:  # pixels per metre
            dpm = struct.unpack(">I", data[:4])[0]
    return size / dpm / 0.0254 if size and dpm else None


def _datasets(root: Path) -> str:
    rows = []
    for p in sorted(root.glob("*.nc")):
        rows.append([f'<a href="{_esc(p.name)}">{_esc(p.name)}</a>', "1"])
    for d in sorted(q for q in root.iterdir() if q.is_dir()):
        files = sorted(d.rglob("*.nc"))
        if files:
            links = ", ".join(f'<a href="{_esc(f.relative_to(root).as_posix())}">'
                              f"{_esc(f.stem)}</a>" for f in files)
            rows.append([f"{_esc(d.name)}/: {links}", str(len(files))])
    return _table(["datasets", "files"], rows) if rows else ""


def write_report(processed: str | Path, out: str | Path | None = None,
                 title: str | None = None) -> Path:
    """Write the static HTML report of a processed campaign.

    Parameters
    ----------
    processed : str or pathlib.Path
        The processed campaign folder (``processed/<pipeline>``).
    out : str or pathlib.Path, optional
        Where to write the page; default ``report.html`` in ``processed``. Figures and datasets
        are linked relative to the page, so it must lie in ``processed`` itself.
    title : str, optional
        Page title; default "flumekit report: <folder name>".

    Returns
    -------
    pathlib.Path
        The page written.

    Raises
    ------
    flumekit.errors.InputError
        When ``processed`` holds no processed dataset, or ``out`` lies outside it.
    """
    root = Path(processed)
    if not root.is_dir() or not any(root.rglob("*.nc")):
        raise InputError(root, "no processed dataset here: run `flumekit make` first, or give "
                               "the processed folder of the campaign")
    out = root / REPORT_NAME if out is None else Path(out)
    if out.resolve().parent != root.resolve():
        raise InputError(out, f"the report must be written into {root} itself (it links the "
                              "figures and datasets there by relative paths)")
    title = title or f"flumekit report: {root.resolve().name}"
    summaries = {p.stem: _open(p) for p in sorted(root.glob("*.nc"))}
    stats = "".join(_statistics(n, ds) for n, ds in summaries.items() if "run" in ds.dims)
    qc = {f"qc/{p.stem}": _open(p) for p in sorted((root / "qc").glob("*.nc"))}
    sea = _conditions(summaries, SEA_STATES, irregular=True)
    matrix = _power_matrix(summaries)
    sections = [
        ("conditions", "Run conditions", _conditions(summaries)),
        *([("sea-states", "Irregular runs: sea states and capture", sea)] if sea else []),
        *([("power-matrix", "Power matrix", matrix)] if matrix else []),
        *_uncertainty(summaries),
        ("statistics", "Range over all runs (every condition pooled)", stats or
         '<p class="muted">No campaign summary datasets.</p>'),
        ("notes", "Notes on fitted parameters", _notes(root)),
        ("warnings", "Warnings", _warnings({**summaries, **qc})),
        ("qc", "Quality control", _qc_counts(summaries) or _flag_counts({**summaries, **qc})),
        ("figures", "Figures", _figures(root)),
        ("datasets", "Datasets", _datasets(root)),
    ]
    nav = "".join(f'<a href="#{a}">{_esc(h)}</a>' for a, h, _ in sections)
    body = "\n".join(f'<h2 id="{a}">{_esc(h)}</h2>\n{s}' for a, h, s in sections)
    page = (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{_esc(title)}</title><style>{_CSS}</style></head><body>"
            f"<h1>{_esc(title)}</h1>"
            f'<p class="muted">{len(summaries)} campaign datasets, written by flumekit '
            f"{_esc(__version__)}</p><nav>{nav}</nav>\n{body}\n</body></html>\n")
    with atomic_path(out) as tmp:
        tmp.write_text(page, encoding="utf-8")
    return out

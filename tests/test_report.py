"""``flumekit report``: the static campaign page, its content and its rendering in Chromium.

The rendering test needs Debian's ``chromium`` (``apt-get install chromium``); it is skipped
where the browser is absent (CI installs only the pip dependencies).
"""

import json
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr

from flumekit.errors import InputError
from flumekit.report import write_report

RUNS = ["T2.00_H0.150_r0", "T3.50_H0.250_r0", "T4.00_H0.200_r0"]
KR = np.array([0.19, 0.21, 0.23])
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture
def processed(tmp_path):
    """A small processed campaign: summaries, a QC flag, per-run files and figures."""
    root = tmp_path / "processed" / "demo"
    (root / "waves").mkdir(parents=True)
    (root / "figures").mkdir()
    coords = {"run": RUNS, "wave_period": ("run", [2.0, 3.5, 4.0]),
              "wave_height": ("run", [0.15, 0.25, 0.2])}
    xr.Dataset({"reflection_coefficient": ("run", KR, {"units": "1",
                                                       "long_name": "reflection coefficient Kr"}),
                "incident_height": ("run", [0.149, 0.249, 0.199], {"units": "m"})},
               coords=coords).to_netcdf(root / "waves_summary.nc")
    xr.Dataset({"theta_amplitude": (("run", "source"), np.arange(6.0).reshape(3, 2),
                                    {"units": "rad"})},
               coords={**coords, "source": ["experiment", "model"]}
               ).to_netcdf(root / "comparison_summary.nc")
    xr.Dataset({"probe_flag": (("run", "probe"), [[1, 1], [1, 4], [3, 1]],
                               {"flag_values": np.array([1, 3, 4], np.int8),
                                "flag_meanings": "pass suspect fail"})},
               coords={"run": RUNS, "probe": ["WP1", "WP2"]}).to_netcdf(root / "qc_summary.nc")
    for r in RUNS:
        xr.Dataset({"eta": ("time", np.zeros(4))}).to_netcdf(root / "waves" / f"{r}.nc")
    (root / "qc").mkdir()
    xr.Dataset({"record_flag": ("time", np.array([1, 9, 9], np.int8),
                                {"flag_values": np.array([1, 9], np.int8),
                                 "flag_meanings": "good missing"})}
               ).to_netcdf(root / "qc" / f"{RUNS[0]}.nc")
    for name in ("fig05a", "fig08"):
        fig, ax = plt.subplots(figsize=(2, 1.5))
        ax.plot([0, 1], [0, 1])
        fig.savefig(root / "figures" / f"{name}.png", dpi=50)
        fig.savefig(root / "figures" / f"{name}.pdf")
        plt.close(fig)
    return root


def test_report_content(processed):
    out = write_report(processed)
    assert out == processed / "report.html"
    page = out.read_text(encoding="utf-8")
    # conditions: every run with its Kr
    for r, kr in zip(RUNS, KR):
        assert r in page and f"<td>{kr:.4g}</td>" in page
    # statistics: mean and max of Kr over the runs, and one row per comparison source
    assert f"<td>{KR.mean():.4g}</td>" in page and f"<td>{KR.max():.4g}</td>" in page
    assert "theta_amplitude (source = experiment)" in page
    assert "theta_amplitude (source = model)" in page
    # QC counts from flag_values / flag_meanings: pass 4, suspect 1, fail 1
    for meaning, n in (("pass", 4), ("suspect", 1), ("fail", 1), ("missing", 2)):
        assert f'<td class="l">{meaning}</td><td>{n}</td>' in page
    # every figure shown once (PNG) with a link to its vector twin; every dataset linked
    assert page.count("<img ") == 2
    assert 'src="figures/fig05a.png"' in page and 'href="figures/fig05a.pdf"' in page
    for r in RUNS:
        assert f'href="waves/{r}.nc"' in page
    assert 'href="waves_summary.nc"' in page
    # nothing fetched from anywhere but the folder: no scheme, no absolute path
    assert "http" not in page and str(processed) not in page
    # same folder, same bytes
    first = out.read_bytes()
    write_report(processed)
    assert out.read_bytes() == first


def test_report_refuses_an_empty_folder_and_an_outside_page(tmp_path, processed):
    with pytest.raises(InputError, match="no processed dataset"):
        write_report(tmp_path / "nothing")
    with pytest.raises(InputError, match="into"):
        write_report(processed, out=tmp_path / "elsewhere.html")
    assert not (tmp_path / "elsewhere.html").exists()


def test_report_command(processed, tmp_path):
    pipe = tmp_path / "p.toml"
    pipe.write_text('[pipeline]\nname = "demo"\nraw = "raw/demo"\nprocessed = "processed/demo"\n')
    res = subprocess.run([sys.executable, "-m", "flumekit.cli", "report", "--pipeline", str(pipe)],
                         capture_output=True, text=True, cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert (processed / "report.html").exists()
    (tmp_path / "empty").mkdir()
    pipe.write_text('[pipeline]\nname = "x"\nraw = "raw/x"\nprocessed = "empty"\n')
    res = subprocess.run([sys.executable, "-m", "flumekit.cli", "report", "--pipeline", str(pipe)],
                         capture_output=True, text=True, cwd=tmp_path)
    assert res.returncode == 1 and "flumekit make" in res.stderr and "Traceback" not in res.stderr


# --- rendering in headless Chromium ---------------------------------------------------------

#: injected at the top of <head> of a copy of the page: records every load error (capturing
#: phase, so failed <img> loads are seen) and, on load, every image that did not decode
PROBE = """<script>window.__errors=[];
window.addEventListener('error',function(e){
  window.__errors.push(String((e.target&&(e.target.src||e.target.href))||e.message))},true);
window.addEventListener('load',function(){
  var im=[].slice.call(document.images);
  var bad=im.filter(function(i){return !(i.complete&&i.naturalWidth>0)}).map(function(i){
    return i.getAttribute('src')});
  var d=document.createElement('pre');d.id='__check';
  d.textContent=JSON.stringify({images:im.length,broken:bad,errors:window.__errors});
  document.body.appendChild(d);});</script>"""


def render(page):
    """Load ``page`` in headless Chromium; the probe's verdict and the console log lines."""
    probe = page.with_name(".render_check.html")
    probe.write_text(page.read_text(encoding="utf-8").replace("<head>", "<head>" + PROBE, 1),
                     encoding="utf-8")
    try:
        res = subprocess.run(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--virtual-time-budget=10000", "--enable-logging=stderr", "--v=0", "--dump-dom",
             probe.resolve().as_uri()], capture_output=True, text=True, timeout=120)
    finally:
        probe.unlink()
    dom = res.stdout
    start = dom.index('<pre id="__check">') + len('<pre id="__check">')
    verdict = json.loads(dom[start:dom.index("</pre>", start)].replace("&quot;", '"'))
    console = [ln for ln in res.stderr.splitlines() if "CONSOLE" in ln]
    return verdict, console


@pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (apt-get install chromium)")
def test_report_renders_in_headless_chromium_with_every_image(processed):
    verdict, console = render(write_report(processed))
    assert verdict == {"images": 2, "broken": [], "errors": []}
    assert console == []
    # the check can fail: an image that does not decode is reported
    (processed / "figures" / "fig05a.png").write_bytes(b"not a png")
    verdict, _ = render(write_report(processed))
    assert verdict["broken"] == ["figures/fig05a.png"] and verdict["errors"]


def test_captions_from_the_figures_and_their_printed_width(tmp_path):
    """A figure saved by flumekit carries its title and what it shows; the report captions it
    with them (mathtext and reST markup undone) and shows it at its printed width."""
    from flumekit.figures.style import ONE_COLUMN, TWO_COLUMNS, new_figure, save, title

    root = tmp_path / "p"
    (root / "figures").mkdir(parents=True)
    xr.Dataset({"a": ("run", [1.0])}, coords={"run": ["r"]}).to_netcdf(root / "s.nc")
    for name, width in (("narrow", ONE_COLUMN), ("wide", TWO_COLUMNS)):
        fig, axes = new_figure(width=width)
        axes[0, 0].plot([0, 1], [0, 1])
        title(fig, f"Spectra of run r: $H_{{m0}}$ = 0.1 m, {name}")
        save(fig, root / "figures" / f"{name}.png",
             description="What it shows, from :func:`flumekit.waves.separate` and ``x``.")
    page = write_report(root, title="Lab campaign 2026").read_text(encoding="utf-8")
    assert "<h1>Lab campaign 2026</h1>" in page
    assert "Spectra of run r: Hm0 = 0.1 m, narrow. What it shows, from separate and x." in page
    assert 'style="width:3.50in"' in page and 'style="width:7.00in"' in page


def test_irregular_runs_and_power_matrix_tables(tmp_path):
    """A campaign with irregular runs: their sea-state table (regular runs left out of it,
    and irregular ones out of the regular table) and the power matrix per source."""
    from flumekit.performance import power_matrix

    root = tmp_path / "p"
    root.mkdir()
    runs = ["T2.00_H0.150_r0", "JS_a", "JS_b"]
    coords = {"run": runs, "wave_period": ("run", [2.0, np.nan, np.nan]),
              "wave_hm0": ("run", [np.nan, 0.1, 0.12])}
    xr.Dataset({"hm0": ("run", [np.nan, 0.101, 0.119], {"units": "m", "long_name": "Hm0"}),
                "incident_height": ("run", [0.149, np.nan, np.nan], {"units": "m"})},
               coords=coords).to_netcdf(root / "waves_summary.nc")
    m = power_matrix(np.array([0.101, 0.119]), np.array([1.8, 1.9]),
                     {"capture_width_ratio": np.array([[0.2], [0.3]]),
                      "mean_power": np.array([[2.0], [3.0]])},
                     hm0_edges=[0.09, 0.11, 0.13], te_edges=[1.5, 2.5],
                     sources=["experiment"])
    m.to_netcdf(root / "power_matrix.nc")
    page = write_report(root).read_text(encoding="utf-8")
    sea = page.split('id="sea-states"')[1].split("<h2")[0]
    regular = page.split('id="conditions"')[1].split("<h2")[0]
    assert "JS_a" in sea and "JS_b" in sea and "T2.00_H0.150_r0" not in sea
    assert "T2.00_H0.150_r0" in regular and "JS_a" not in regular
    matrix = page.split('id="power-matrix"')[1].split("<h2")[0]
    assert "0.09-0.11" in matrix and "1.5-2.5" in matrix
    assert "0.2 (2 W, n = 1)" in matrix and "0.3 (3 W, n = 1)" in matrix


def test_qc_counts_from_the_qc_summary(tmp_path):
    """The counts per flag of every run's records, as qc_summary.nc holds them (the per-run
    QC products lie in qc/<record>/, where no flag_values variable is at the top level)."""
    root = tmp_path / "p"
    root.mkdir()
    meanings = ["pass", "not_evaluated", "suspect", "fail", "missing_data"]
    xr.Dataset({"probe_voltage_qc_count": (("run", "flag_meaning"),
                                           [[21790, 0, 7, 3, 0], [36400, 0, 0, 0, 0]])},
               coords={"run": ["r1", "r2"], "flag_meaning": meanings}
               ).to_netcdf(root / "qc_summary.nc")
    page = write_report(root).read_text(encoding="utf-8")
    qc = page.split('id="qc"')[1].split("<h2")[0]
    assert "No quality-control flags" not in qc
    assert ('<td class="l">r1</td><td class="l">probe_voltage</td><td>21790</td><td>0</td>'
            "<td>7</td><td>3</td><td>0</td>") in qc

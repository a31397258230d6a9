"""The second bad-input corpus through the pipeline: a small virtual campaign (two runs of the
default template, 2.0 s and 3.5 s) copied with one fault each, built with ``flumekit make``.
Each case is a clear error naming the run's file and the problem, or the right result; the
raw files are hashed before and after."""

import hashlib
import re
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent / "io"))
from virtual_run import RUN  # noqa: E402

from flumekit.cli import main  # noqa: E402

OTHER = "T3.50_H0.150_r0"


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """The raw campaign: the run of tests/io/virtual_run.py and a 3.5 s run."""
    from flumekit.campaign import load_campaign
    from flumekit.synth.campaign import Truth, _probe_gains, _write_run
    from virtual_run import write_one_run

    root = tmp_path_factory.mktemp("corpus") / "original"
    write_one_run(root)
    c = load_campaign(root)
    a, b = _probe_gains(c.probes.names, np.random.default_rng(5))
    _write_run(root, c, OTHER, "waves", 3.5, 0.15, 0, None, a, b, Truth(),
               np.random.default_rng(2), 20)
    return root


def _hashes(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def copy(campaign: Path, tmp_path: Path) -> Path:
    root = tmp_path / "raw"
    shutil.copytree(campaign, root)
    (tmp_path / "pipeline.toml").write_text(
        '[pipeline]\nname = "corpus"\nraw = "raw"\nprocessed = "processed"\n')
    return root


def make(tmp_path: Path, *targets: str, capsys=None) -> tuple[int, str]:
    code = main(["make", "--pipeline", str(tmp_path / "pipeline.toml"), *targets])
    if capsys is None:
        return code, ""
    out = capsys.readouterr()
    return code, out.out + out.err


def test_a_flap_record_of_another_run_is_refused(campaign, tmp_path, capsys):
    root = copy(campaign, tmp_path)
    before = _hashes(root)
    shutil.copy(root / "runs" / OTHER / "flap.csv", root / "runs" / RUN / "flap.csv")
    before = _hashes(root)
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1
    # the 3.5 s record's period, to the spectral resolution of its 218 s
    assert re.search(rf"runs/{RUN}/flap.csv: dominant period 3\.(49|50)\d s \(encoder counts\)",
                     err)
    assert "declares period 2 s" in err
    assert "Traceback" not in err
    assert _hashes(root) == before
    # the run's own flap record passes
    shutil.copy(campaign / "runs" / RUN / "flap.csv", root / "runs" / RUN / "flap.csv")
    assert make(tmp_path, f"qc/flap/{RUN}")[0] == 0


def test_a_files_entry_outside_the_run_folder(campaign, tmp_path, capsys):
    root = copy(campaign, tmp_path)
    toml = root / "runs" / RUN / "run.toml"
    text = toml.read_text()
    toml.write_text(text + f'\n[files]\nflap = "../{OTHER}/flap.csv"\n')
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1
    assert "field 'files.flap'" in err and "lies outside the run folder" in err
    assert 'shared = ["flap"]' in err
    # declared shared on purpose, the flap's own period still tells the records apart
    toml.write_text(text + f'\n[files]\nflap = "../{OTHER}/flap.csv"\nshared = ["flap"]\n')
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1 and re.search(rf"runs/{OTHER}/flap.csv: dominant period 3\.(49|50)", err)
    toml.write_text(text + '\n[files]\nshared = ["flapp"]\n')
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1 and "unknown instrument 'flapp'" in err and "did you mean" in err


def test_warnings_reach_the_make_summary_the_summaries_and_the_report(campaign, tmp_path,
                                                                      capsys):
    """A declared height 12 % off the measured one (a warning beyond 10 %, an error beyond
    25 %): before, only in each dataset's attribute; now printed, gathered, reported."""
    import xarray as xr

    root = copy(campaign, tmp_path)
    toml = root / "runs" / RUN / "run.toml"
    toml.write_text(toml.read_text().replace("height = 0.15", "height = 0.168"))
    code, err = make(tmp_path, "waves_summary", "flap_summary", capsys=capsys)
    assert code == 0
    lines = err.splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("warnings: "))
    assert "flumekit report" in lines[k]
    shown = lines[k + 1:k + 6]
    height = [w for w in shown if "run.height" in w]
    assert len(height) == 1 and f"runs/{RUN}/run.toml" in height[0] and RUN in height[0]
    assert "declared height 0.168 m" in height[0]
    processed = tmp_path / "processed"
    with xr.open_dataset(processed / "waves_summary.nc") as s:
        warned = s.attrs["flumekit_warnings"].splitlines()
    assert any("declared height 0.168 m" in w and RUN in w for w in warned)
    assert not any(OTHER in w and "run.height" in w for w in warned)
    assert main(["report", "--pipeline", str(tmp_path / "pipeline.toml")]) == 0
    page = (processed / "report.html").read_text()
    assert 'id="warnings"' in page and "declared height 0.168 m" in page

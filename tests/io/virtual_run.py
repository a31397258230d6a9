"""One run of the virtual flume (default campaign template) written as a raw campaign: the
shared starting point of the tests that export it to other file formats."""

from importlib import resources
from pathlib import Path

import numpy as np

RUN = "T2.00_H0.150_r0"


def write_one_run(root: Path) -> str:
    """``root``/campaign.toml, the probe calibration and the run :data:`RUN`; returns the
    campaign template's text."""
    from flumekit.campaign import load_campaign
    from flumekit.synth.campaign import Truth, _probe_gains, _write_calibration, _write_run

    (root / "calibration").mkdir(parents=True)
    (root / "truth").mkdir()
    template = resources.files("flumekit.data").joinpath("default_campaign.toml").read_text()
    (root / "campaign.toml").write_text(template)
    c = load_campaign(root)
    rng = np.random.default_rng(5)
    a, b = _probe_gains(c.probes.names, rng)
    _write_calibration(root, c.probes.names, a, b, c.probes.sampling_rate, Truth(), rng)
    _write_run(root, c, RUN, "waves", 2.0, 0.15, 0, None, a, b, Truth(),
               np.random.default_rng(1), 55)
    return template

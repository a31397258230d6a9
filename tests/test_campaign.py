"""Campaign metadata: the default template reads, and bad fields are named."""

from importlib import resources

import pytest

from flumekit.campaign import load_campaign
from flumekit.errors import InputError


@pytest.fixture
def root(tmp_path):
    src = resources.files("flumekit.data").joinpath("default_campaign.toml")
    (tmp_path / "campaign.toml").write_text(src.read_text())
    run = tmp_path / "runs" / "r1"
    run.mkdir(parents=True)
    (run / "run.toml").write_text("[run]\nperiod = 3.5\nheight = 0.25\nrepeat = 0\n"
                                  "[probes]\nWP1 = -4\nWP2 = -3\nWP3 = -2\nWP4 = -0.6\n")
    return tmp_path


def test_default_template_reads(root):
    c = load_campaign(root)
    assert c.flume.water_depth == 0.825
    assert c.probes.separation == ("WP1", "WP2", "WP3")
    assert c.runs[0].period == 3.5 and c.runs[0].probe_x["WP4"] == -0.6
    assert c.pto.friction.static_force > c.pto.friction.coulomb_force


def edit(path, old, new):
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))


@pytest.mark.parametrize("file, old, new, message", [
    ("runs/r1/run.toml", "period = 3.5\n", "", r"run\.toml.*'run\.period'.*missing"),
    ("runs/r1/run.toml", "period = 3.5", 'period = "long"', r"'run\.period'.*finite number"),
    ("runs/r1/run.toml", "period = 3.5", "period = -1", r"'run\.period'.*> 0"),
    ("runs/r1/run.toml", "WP4 = -0.6", "WP4 = -0.6\nWP9 = 1", r"unknown probe.*WP9"),
    ("runs/r1/run.toml", "WP4 = -0.6", "", r"'probes\.WP4'.*missing"),
    ("campaign.toml", "water_depth = 0.825", "water_depth = 0.0", r"flume\.water_depth.*> 0"),
    ("campaign.toml", "width = 1.31", "width = 2.0", r"flap width 2\.0 m exceeds"),
    ("campaign.toml", "L5 = 1.53", "L5 = -1.53", r"encoder\.L5.*> 0"),
    ("campaign.toml", "[flume]", "[flume", r"campaign\.toml.*not valid TOML"),
    ("campaign.toml", "static_force = 70.0", "static_force = 10.0", r"static friction"),
])
def test_bad_fields_are_named(root, file, old, new, message):
    edit(root / file, old, new)
    with pytest.raises(InputError, match=message):
        load_campaign(root)


def test_missing_campaign_file(tmp_path):
    with pytest.raises(InputError, match="campaign.toml: file not found"):
        load_campaign(tmp_path)


def test_five_typos_reported_at_once_with_suggestions(root):
    edit(root / "campaign.toml", "water_depth = 0.825", "water_dept = 0.825")
    edit(root / "campaign.toml", "sampling_rate = 25.0", "sampling_rat = 25.0")
    edit(root / "campaign.toml", "thickness = 0.17", "thicknes = 0.17")
    edit(root / "campaign.toml", "counts_per_metre = 6000.0", "counts_per_meter = 6000.0")
    edit(root / "campaign.toml", "[uvp.UP2]", "[uvp.UP02]")
    with pytest.raises(InputError) as e:
        load_campaign(root)
    text = str(e.value)
    assert "5 problems" in text
    for typo, right in [("flume.water_dept", "water_depth"), ("probes.sampling_rat",
                        "sampling_rate"), ("flap.thicknes", "thickness"),
                        ("encoder.counts_per_meter", "counts_per_metre"), ("uvp.UP02", "UP2")]:
        line = next(x for x in text.splitlines() if f"'{typo}'" in x)
        assert str(root / "campaign.toml") in line and f"did you mean '{right}'" in line
    # the keys the typos left missing are not reported again: the typo is the one problem
    assert "missing" not in text


def test_run_file_problems_reported_at_once(root):
    edit(root / "runs/r1/run.toml", "period = 3.5", "periode = 3.5")
    edit(root / "runs/r1/run.toml", "WP4 = -0.6", "WP5 = -0.6")
    with pytest.raises(InputError) as e:
        load_campaign(root)
    text = str(e.value)
    assert "did you mean 'period'" in text and "'probes.WP4'" in text and "WP5" in text


def test_waves_only_campaign(tmp_path):
    (tmp_path / "campaign.toml").write_text(
        '[campaign]\nname = "w"\n[flume]\nwater_depth = 0.5\n'
        '[probes]\nnames = ["A", "B", "C"]\nsampling_rate = 50.0\nunits = "cm"\n')
    run = tmp_path / "runs" / "r1"
    run.mkdir(parents=True)
    (run / "run.toml").write_text("[run]\nperiod = 1.5\n[probes]\nA = 0\nB = 0.3\nC = 0.8\n"
                                  "[clock]\nprobes = 0.25\n")
    c = load_campaign(tmp_path)
    assert c.instruments == ("probes",) and c.flap is None and c.probes.calibrated
    assert c.runs[0].height is None and c.runs[0].clock["probes"] == 0.25
    (run / "run.toml").write_text("[run]\nperiod = 1.5\n[probes]\nA = 0\nB = 0.3\nC = 0.8\n"
                                  "[clock]\nflap = 0.25\n")
    with pytest.raises(InputError, match="clock.flap.*no flap instrument"):
        load_campaign(tmp_path)


def test_flap_instruments_go_together(root):
    text = (root / "campaign.toml").read_text()
    start = text.index("[encoder]")
    (root / "campaign.toml").write_text(text[:start] + text[text.index("[probes]"):])
    with pytest.raises(InputError, match=r"'encoder'.*together"):
        load_campaign(root)


def test_descriptive_fields_are_optional(root):
    """Fields no computation reads (flume length, flap height, mass, centre of mass) may be
    left out; given, they are still checked."""
    for line in ("length = 60.0", "height = 0.84", "mass = 72.3", "cog_height = 0.33"):
        edit(root / "campaign.toml", line, "")
    c = load_campaign(root)
    assert c.flume.length is None and c.flap.mass is None and c.flap.height is None
    assert c.flap.cog_height is None and c.flap.inertia == 14.74
    edit(root / "campaign.toml", "[flap]", "[flap]\nmass = -1.0")
    with pytest.raises(InputError, match=r"flap\.mass.*> 0"):
        load_campaign(root)

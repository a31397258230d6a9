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
    ("runs/r1/run.toml", "height = 0.25\n", "", r"run\.toml.*'run\.height'.*missing"),
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

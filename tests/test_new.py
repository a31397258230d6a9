"""`flumekit new DIR`: a commented skeleton that reads as a campaign, never over existing files."""

from flumekit.campaign import CAMPAIGN, DIALECT, load_campaign
from flumekit.cli import main


def test_skeleton_reads_and_mentions_every_key(tmp_path, capsys):
    d = tmp_path / "lab"
    assert main(["new", str(d)]) == 0
    c = load_campaign(d)
    assert c.name == "lab" and c.instruments == ("probes",) and c.probes.calibrated
    assert c.runs[0].id == "run01" and c.runs[0].probe_x == {"WP1": 0.0, "WP2": 0.3, "WP3": 0.8}
    text = (d / "campaign.toml").read_text()
    keys = {k for t in CAMPAIGN.values() if t.table for k in t.table} | set(DIALECT)
    assert not [k for k in keys if k not in text]  # every key is shown, most commented out
    assert 'raw = "."' in (d / "pipeline.toml").read_text()


def test_new_refuses_a_folder_with_files(tmp_path, capsys):
    (tmp_path / "data.csv").write_text("1,2\n")
    assert main(["new", str(tmp_path)]) == 1
    assert "not an empty folder" in capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == ["data.csv"]

"""Stage parameters: one generated reference, every parameter documented, typos named."""

from pathlib import Path

import pytest

from flumekit.errors import InputError
from flumekit.stages import check_stage_params, parameters, parameters_markdown


def test_parameter_reference_is_generated_and_complete():
    """docs/parameters.md is `flumekit params --markdown`, and every parameter has a meaning."""
    root = Path(__file__).resolve().parents[2]
    assert (root / "docs" / "parameters.md").read_text() == parameters_markdown() + "\n"
    for stage, params in parameters().items():
        for name, (_, doc) in params.items():
            assert doc, f"[stages.{stage}] {name} is not documented"


def test_unknown_stages_and_parameters_reported_at_once(tmp_path):
    p = tmp_path / "p.toml"
    with pytest.raises(InputError) as e:
        check_stage_params({"wave": {"x_ref": 0}, "waves": {"tolerence": 0.1}}, p)
    text = str(e.value)
    assert "2 problems" in text and str(p) in text
    assert "did you mean 'waves'" in text and "did you mean 'tolerance'" in text

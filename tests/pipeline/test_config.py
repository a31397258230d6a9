"""Pipeline files are validated: every problem of a file at once, unknown keys with a hint."""

import pytest

from flumekit.errors import InputError
from flumekit.pipeline.config import load_pipeline


def test_pipeline_file_problems_reported_at_once(tmp_path):
    p = tmp_path / "p.toml"
    p.write_text('[pipeline]\nname = "x"\nraw = "r"\nprocesed = "p"\nextends = "d.toml"\n'
                 '[synth]\nsize = "huge"\n')
    with pytest.raises(InputError) as e:
        load_pipeline(p)
    text = str(e.value)
    assert "3 problems" in text
    assert "'pipeline.procesed'" in text and "did you mean 'processed'" in text
    assert "'pipeline.extends'" in text and "'synth.size'" in text


def test_a_problem_in_an_extended_file_names_that_file(tmp_path):
    (tmp_path / "base.toml").write_text('[pipeline]\nname = "b"\nraw = "r"\nprocessed = "p"\n'
                                        "[synth]\nseed = 1.5\n")
    (tmp_path / "child.toml").write_text('extends = "base.toml"\n[pipeline]\nname = "c"\n')
    with pytest.raises(InputError, match=r"base\.toml.*'synth\.seed'.*integer"):
        load_pipeline(tmp_path / "child.toml")

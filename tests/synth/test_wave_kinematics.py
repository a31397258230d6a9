"""The UVP's wave kinematics: a record at fixed points equals the same points one by one.

flumekit.synth.uvp.wave_kinematics sums the field with one compiled kernel in two ways: every
time with every position (a record at fixed points, as the UVP's beams and the true field are
sampled) and point by point (any other broadcast). Both must give the same bits, so that a
beam's record does not depend on which other points it was computed with.
"""

import numpy as np
import pytest

from flumekit.synth.uvp import wave_kinematics
from flumekit.synth.waves import Beach

WAVE = dict(period=3.5, height=0.25, depth=0.825, reflection=0.14, reflection_phase=0.6)


@pytest.mark.parametrize("kw", [dict(beach=Beach(transmission=0.9)),
                                dict(ramp_waves=None, theory="stokes2")])
def test_record_at_fixed_points_equals_point_by_point(kw):
    rng = np.random.default_rng(3)
    x, z = rng.uniform(-0.4, -0.1, 7), rng.uniform(0.0, 0.6, 7)
    # times across the ramp's arrival at the points and after it
    t = np.concatenate([rng.uniform(0.0, 150.0, 9), [0.0]])
    grid = wave_kinematics(x[None, :], z[None, :], t[:, None], **WAVE, **kw)
    tt, xx, zz = (a.ravel() for a in np.broadcast_arrays(t[:, None], x[None, :], z[None, :]))
    points = wave_kinematics(xx, zz, tt, **WAVE, **kw)
    for g, p in zip(grid, points):
        assert g.shape == (t.size, x.size)
        np.testing.assert_array_equal(g.ravel(), p)
    # together or apart: each beam's points give the same bits with or without the others
    alone = wave_kinematics(x[None, :3], z[None, :3], t[:, None], **WAVE, **kw)
    for g, a in zip(grid, alone):
        np.testing.assert_array_equal(g[:, :3], a)
    assert np.ptp(grid[2]) > 0.1  # a wave, not zeros

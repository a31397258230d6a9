"""
Incident and reflected waves of a real flume record
====================================================

Three capacitance gauges at x = 0, 0.6 and 0.9 m recorded regular waves (T ≈ 1.33 s) in
0.25 m of water at 100 Hz for 200 s (WaveLabX, ``wavedata.csv``, MIT licence, © 2025
sandslamsal). The record is read with pandas as it is, DC offsets and all, and separated
with :func:`flumekit.waves.separate` and drawn with :func:`flumekit.plot.separation`;
the six lines below are all a notebook needs.

``separate`` sees that the record is regular (nearly all of its variance sits at 0.75 Hz and
the harmonics of it) and therefore fits the harmonics as bound waves and reports the
first-harmonic reflection coefficient, without an option. Fitted bin by bin as free waves
(``regular=False``), the bound second harmonic would be counted as reflection.
"""

path = "../wavelabx/wavedata.csv"  # vendored beside the gallery, in examples/wavelabx

# %%
# Separate, with public names only:
import pandas as pd

import flumekit

eta = pd.read_csv(path)  # one column per gauge, one row per sample
result = flumekit.waves.separate(eta, depth=0.25, x=[0.0, 0.6, 0.9], sampling_rate=100.0)
print(f"Kr = {result.reflection_coefficient.item():.3f}")
flumekit.plot.separation(result)

# %%
# What the detection found, and the free-wave fit for comparison:
print(result.attrs["regular_detection"])
free = flumekit.waves.separate(eta, depth=0.25, x=[0.0, 0.6, 0.9], sampling_rate=100.0,
                               regular=False)
print(f"bin-wise free-wave fit: Kr = {free.reflection_coefficient.item():.3f}")

"""
Opening a UVP profile file
==========================

A real Met-Flow UVP Monitor recording (``data_sample.mfprof`` from the PyUDV project, GPL-3.0;
one transducer, 4 MHz, 654 channels, 50 ms between profiles) read with
:func:`flumekit.read_mfprof`. The result is an :class:`xarray.Dataset` over (time, channel)
with the along-beam velocity in m/s and the distance of each channel from the transducer.
"""

from pathlib import Path

import matplotlib.pyplot as plt

import flumekit

# the recording is GPL-3.0 and not vendored: it lies in shared/data beside the project folder
path = Path("../../../shared/data/metflow/data_sample.mfprof")
uvp = flumekit.read_mfprof(path)
print(uvp.sizes, f"velocity resolution {uvp.attrs['velocity_resolution'] * 1000:.2f} mm/s")

# %%
# Velocity along the beam against time and distance:
fig, ax = plt.subplots(figsize=(7, 3), layout="constrained")
uvp["beam_velocity"].plot(ax=ax, x="time", y="distance", cmap="RdBu_r", robust=True)
ax.set_title("Along-beam velocity (sign convention as stored, see the reader)")

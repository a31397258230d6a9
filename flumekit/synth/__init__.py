"""The virtual flume: synthetic campaigns with a known truth.

Regular and irregular waves, the flap's response and UVP profiles, written in the raw format
of raw/README.md, with the truth beside them (Brito et al. 2020's flume and flap).
"""

from flumekit.lazy import lazy_names

#: marker of a campaign folder the virtual flume wrote: its size, seed, planned runs and (when
#: written run by run) the runs written so far. Only a folder holding it is ever completed run
#: by run, and only with runs never written (:mod:`flumekit.pipeline.raw`)
MARKER = ".flumekit-virtual.json"
#: default seed of the virtual flume: the one the shipped pipeline files set (``[synth] seed =
#: 2020`` in ``pipelines/default.toml``, the year of the flume paper), so that a pipeline
#: without a seed, ``flumekit synth`` and :func:`flumekit.synth.campaign.write_campaign` write
#: the same campaign
DEFAULT_SEED = 2020


#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "write_campaign": "campaign",
    "virtual_campaign": "campaign",
    "regular_wave_field": "waves",
    "irregular_wave_field": "waves",
    "jonswap": "waves",
    "flap_record": "flap",
    "true_field": "uvp",
    "irregular_sea": "irregular",
}

__all__ = sorted([*_LAZY, "DEFAULT_SEED", "MARKER"])


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())

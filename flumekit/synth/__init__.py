"""synth"""

#: marker of a campaign folder the virtual flume wrote: its size, seed, planned runs and (when
#: written run by run) the runs written so far. Only a folder holding it is ever completed run
#: by run, and only with runs never written (:mod:`flumekit.pipeline.raw`)
MARKER = ".flumekit-virtual.json"
#: default seed of the virtual flume: the one the shipped pipeline files set (``[synth] seed =
#: 2020`` in ``pipelines/default.toml``, the year of the flume paper), so that a pipeline
#: without a seed, ``flumekit synth`` and :func:`flumekit.synth.campaign.write_campaign` write
#: the same campaign
DEFAULT_SEED = 2020

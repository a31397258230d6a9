"""The graph of a pipeline: every stage's rules for its campaign, and the virtual flume's.

Where the virtual flume is to write the campaign (:func:`flumekit.pipeline.raw.synthesis_plan`),
the stages are planned from its design and the synthesis rules of :mod:`flumekit.stages.virtual`
write only the raw files a requested target reads. Planning writes nothing but the graph's
cache (:func:`flumekit.pipeline.cache.cached_graph`).
"""

from __future__ import annotations

from flumekit.docstrings import filler
from flumekit.pipeline.cache import cached_graph, pipeline_key

#: docstring text that several functions of this module share
_doc = filler(
    pipe=("pipe : Pipeline\n"
          "    The parsed pipeline file."))


@_doc
def pipeline_rules(pipe, lazy) -> list:
    """Return the rules of a pipeline (:class:`flumekit.pipeline.config.Pipeline`).

    Parameters
    ----------
    %(pipe)s
    lazy : Synthesis or None
        What the virtual flume is to synthesise (None: the campaign is there).

    Returns
    -------
    list of Rule
        Every stage's rules, and the virtual flume's synthesis rules when ``lazy`` is given.
    """
    from flumekit.campaign import load_campaign
    from flumekit.stages import build_rules, check_stage_params, virtual
    from flumekit.stages.context import Context

    check_stage_params(pipe.stages, pipe.path)
    if lazy is None:
        return build_rules(Context(campaign=load_campaign(pipe.raw), processed=pipe.processed,
                                   params=pipe.stages, scenes=pipe.scenes))
    from flumekit.synth.campaign import virtual_campaign

    campaign = virtual_campaign(pipe.raw, lazy.size, lazy.seed)
    rules = build_rules(Context(campaign=campaign, processed=pipe.processed, params=pipe.stages,
                                scenes=pipe.scenes))
    return rules + virtual.rules(rules, pipe.raw, lazy.size, lazy.seed,
                                 [r.id for r in campaign.runs])


@_doc
def pipeline_graph(pipe, key_lazy: tuple | None = None):
    """Return the graph of a pipeline, from its cache while nothing it is made of changed.

    Parameters
    ----------
    %(pipe)s
    key_lazy : tuple, optional
        Its :func:`flumekit.pipeline.cache.pipeline_key`, if already computed.

    Returns
    -------
    flumekit.pipeline.engine.Graph
        The graph of :func:`pipeline_rules`.
    """
    key, lazy = key_lazy or pipeline_key(pipe)
    return cached_graph(pipe.processed / ".flumekit-graph.pickle", key,
                        lambda: pipeline_rules(pipe, lazy))

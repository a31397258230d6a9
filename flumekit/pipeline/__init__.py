"""The make-style pipeline of flumekit.

A pipeline file (:func:`load_pipeline`), rules (:class:`Rule`), the graph they form, what is
out of date (:func:`plan`, :func:`why`) and running it (:func:`make`, with an executor from
:func:`executor_for`).
"""


from flumekit.lazy import lazy_names

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "Pipeline": "config",
    "load_pipeline": "config",
    "make": "engine",
    "plan": "engine",
    "why": "engine",
    "Rule": "rules",
    "executor_for": "executors",
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())

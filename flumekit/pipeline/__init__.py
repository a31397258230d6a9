"""The make-style pipeline: a pipeline file (:func:`load_pipeline`), rules (:class:`Rule`),
the graph they form, what is out of date (:func:`plan`, :func:`why`) and running it
(:func:`make`, with an executor from :func:`executor_for`)."""


import importlib

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


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))

"""The make-style pipeline of flumekit.

A pipeline file (:func:`load_pipeline`), rules (:class:`Rule`), the graph they form, what is
out of date (:func:`plan`, :func:`why`) and running it (:func:`make`, with an executor from
:func:`executor_for`).
"""


from flumekit.lazy import attach

# public names by the module that defines them, each imported on first use so that
# importing the package stays cheap
__getattr__, __dir__, __all__ = attach(
    __name__, globals(),
    config=["Pipeline", "load_pipeline"],
    engine=["make", "plan", "why"],
    rules=["Rule"],
    executors=["executor_for"],
)

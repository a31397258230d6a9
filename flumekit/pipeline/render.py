"""The dependency graph of targets as text: Graphviz DOT or Mermaid.

Target names are quoted (a run's name may hold any character a campaign allows); nodes are
numbered so that the edges need no quoting.
"""

from __future__ import annotations

FORMATS = ("dot", "mermaid")


def _label(target: str, fmt: str) -> str:
    """Return a target name escaped for the double quotes of a DOT or Mermaid label."""
    if fmt == "dot":
        return target.replace("\\", "\\\\").replace('"', '\\"')
    return target.replace('"', "#quot;")


def render(graph, nodes: list[str], fmt: str = "dot") -> str:
    """Return the subgraph of ``nodes`` (with every edge between them) as DOT or Mermaid.

    Parameters
    ----------
    graph : Graph
        The pipeline's graph (:class:`flumekit.pipeline.engine.Graph`).
    nodes : list of str
        Targets to draw, in order (e.g. the closure of what a make would build).
    fmt : {"dot", "mermaid"}
        Output language.

    Returns
    -------
    str
        The graph, one statement a line.

    Raises
    ------
    ValueError
        For a format other than those of :data:`FORMATS`.

    Examples
    --------
    >>> from flumekit.pipeline.engine import Graph
    >>> from flumekit.pipeline.rules import Rule
    >>> g = Graph([Rule("a", "m:f", {}, {"o": "a.txt"}), Rule("b", "m:f", {"i": "a.txt"},
    ...                                                     {"o": "b.txt"})])
    >>> print(render(g, ["a", "b"], "mermaid"))
    flowchart LR
      n0["a"]
      n1["b"]
      n0 --> n1
    """
    if fmt not in FORMATS:
        raise ValueError(f"format must be one of {FORMATS}, got {fmt!r}")
    ids = {t: f"n{i}" for i, t in enumerate(nodes)}
    edges = [(ids[d], ids[t]) for t in nodes for d in graph.deps(t) if d in ids]
    if fmt == "dot":
        lines = ["digraph flumekit {", "  rankdir=LR;", "  node [shape=box];"]
        lines += [f'  {ids[t]} [label="{_label(t, fmt)}"];' for t in nodes]
        lines += [f"  {a} -> {b};" for a, b in edges]
        lines.append("}")
    else:
        lines = ["flowchart LR"]
        lines += [f'  {ids[t]}["{_label(t, fmt)}"]' for t in nodes]
        lines += [f"  {a} --> {b}" for a, b in edges]
    return "\n".join(lines)


__all__ = ["FORMATS", "render"]

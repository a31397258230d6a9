"""``.. stage-parameters::``: the parameters of every pipeline stage with their defaults.

Read from the ``DEFAULTS`` of each module in :data:`flumekit.stages.STAGES`, so the reference
cannot drift from the code. A pipeline file overrides them under ``[stages.<stage>]``.
"""

from __future__ import annotations

import importlib

from docutils import nodes
from docutils.parsers.rst import Directive


def _literal(value) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value).replace("'", '"')


class StageParameters(Directive):
    has_content = False

    def run(self):
        from flumekit.stages import STAGES

        out = []
        for stage in STAGES:
            defaults = getattr(importlib.import_module(f"flumekit.stages.{stage}"),
                               "DEFAULTS", None)
            section = nodes.section(ids=[f"stage-{stage}"])
            section += nodes.title(text=f"[stages.{stage}]")
            if not defaults:
                section += nodes.paragraph(text="No parameters.")
                out.append(section)
                continue
            table = nodes.table()
            group = nodes.tgroup(cols=2)
            table += group
            group += nodes.colspec(colwidth=1)
            group += nodes.colspec(colwidth=2)
            head = nodes.thead()
            row = nodes.row()
            for text in ("parameter", "default"):
                row += nodes.entry("", nodes.paragraph(text=text))
            head += row
            group += head
            body = nodes.tbody()
            for key, value in defaults.items():
                row = nodes.row()
                row += nodes.entry("", nodes.paragraph("", "", nodes.literal(text=key)))
                row += nodes.entry("", nodes.paragraph("", "",
                                                       nodes.literal(text=_literal(value))))
                body += row
            group += body
            section += table
            out.append(section)
        return out


def setup(app):
    app.add_directive("stage-parameters", StageParameters)
    return {"parallel_read_safe": True, "parallel_write_safe": True}

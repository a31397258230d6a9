"""Uncertainty of the results of a campaign (GUM, JCGM 101, ITTC 7.5-02-01-01).

``condition_statistics``: repeat statistics and Type A uncertainties per test condition;
``components``: the declared Type B components resolved for a run; ``propagation``: Monte
Carlo (JCGM 101) and linear (GUM) propagation through the waves and flap analyses;
``combine``: Type A with Type B, effective degrees of freedom (Welch-Satterthwaite) and the
coverage factor; ``report_section``: the HTML section of the report.
"""

from flumekit.uncertainty.html import report_sections
from flumekit.uncertainty.propagation import Input, RunModel, propagate, resolve_inputs
from flumekit.uncertainty.repeats import CONDITION_COORDS, QUANTITIES, condition_statistics

__all__ = ["CONDITION_COORDS", "QUANTITIES", "condition_statistics", "report_sections",
           "Input", "RunModel", "propagate", "resolve_inputs"]

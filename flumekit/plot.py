"""Figures for notebooks: each function returns a :class:`matplotlib.figure.Figure`.

These are the figures of the pipeline (:mod:`flumekit.figures`) under the names an analyst
looks for; they take the datasets the analysis functions return or ``flumekit make`` wrote.
"""

from flumekit.figures.flap import figure_5b as flap_angle
from flumekit.figures.uvp import fig11 as velocity_field
from flumekit.figures.waves import figure_5a as probe_elevation
from flumekit.figures.waves import separation

__all__ = ["flap_angle", "probe_elevation", "separation", "velocity_field"]

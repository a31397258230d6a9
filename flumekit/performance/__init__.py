"""Device-agnostic performance of a wave energy converter in irregular seas.

Capture width and capture width ratio (:mod:`.capture`), statistics of a motion or load record
(:mod:`.statistics`), and the power matrix over the incident Hm0 and Te (:mod:`.matrix`), for a
pitching flap and a heaving buoy alike (IEC TS 62600-100, IEC TS 62600-103).
"""

from flumekit.performance.capture import capture_width, capture_width_ratio
from flumekit.performance.matrix import edges_around, power_matrix, target_te
from flumekit.performance.statistics import motion_statistics

__all__ = ["capture_width", "capture_width_ratio", "edges_around", "motion_statistics",
           "power_matrix", "target_te"]

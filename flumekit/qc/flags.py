"""QARTOD quality flags and their CF description.

One flag per sample, the U.S. IOOS QARTOD scheme (IOOS 2020, *Manual for the Use of Real-Time
Oceanographic Data Quality Control Flags*, v1.2, Table 2): 1 pass, 2 not evaluated, 3 suspect,
4 fail, 9 missing. The aggregate of several tests is the worst flag, with 9 (missing) above 4.
Datasets carry the flags as ``<variable>_qc`` with CF ``flag_values``/``flag_meanings``
(CF conventions §3.5) and ``ancillary_variables`` on the data variable.
"""

from __future__ import annotations

import numpy as np

GOOD = 1
NOT_EVALUATED = 2
SUSPECT = 3
FAIL = 4
MISSING = 9

#: signed bytes: CF 1.8 knows no unsigned types, and flags born int8 are written as they are
FLAG_VALUES = np.array([GOOD, NOT_EVALUATED, SUSPECT, FAIL, MISSING], dtype=np.int8)
FLAG_MEANINGS = "pass not_evaluated suspect fail missing_data"

#: order of severity used to aggregate flags (missing counts as worst) and its inverse
_RANK = np.zeros(256, dtype=np.uint8)
_RANK[[GOOD, NOT_EVALUATED, SUSPECT, FAIL, MISSING]] = [1, 0, 2, 3, 4]
_FLAG_OF_RANK = np.array([NOT_EVALUATED, GOOD, SUSPECT, FAIL, MISSING], dtype=np.int8)


def flag_attrs(variable: str, long_name: str | None = None) -> dict:
    """CF attributes of the flag variable of ``variable`` (QARTOD values and meanings)."""
    return {"units": "1", "long_name": long_name or f"QARTOD quality flag of {variable}",
            "standard_name": "quality_flag", "flag_values": FLAG_VALUES,
            "flag_meanings": FLAG_MEANINGS,
            "references": "U.S. IOOS QARTOD flag scheme (1 pass, 2 not evaluated, 3 suspect, "
                          "4 fail, 9 missing)"}


def aggregate(*flags: np.ndarray) -> np.ndarray:
    """Worst flag per sample over several tests' flags of the same shape.

    ``NOT_EVALUATED`` (2) ranks below ``GOOD`` so that a sample any test passed reads 1.
    """
    # np.take, not fancy indexing: the same lookup at half the cost on a UVP beam's block
    worst = np.take(_RANK, np.asarray(flags[0], dtype=np.uint8))
    for f in flags[1:]:
        np.maximum(worst, np.take(_RANK, np.asarray(f, dtype=np.uint8)), out=worst)
    return np.take(_FLAG_OF_RANK, worst)

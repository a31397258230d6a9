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

#: ratio of the standard deviation to the median absolute deviation of a normal distribution
#: (1/Φ⁻¹(3/4)): the robust scale against which the tests set their flags, here where both the
#: numpy tests (:mod:`flumekit.qc.qartod`) and their compiled kernels (:mod:`flumekit.qc.kernels`)
#: read it
MAD_TO_STD = 1.4826


def flag_attrs(variable: str, long_name: str | None = None) -> dict:
    """Return the CF attributes of the flag variable of ``variable`` (QARTOD values and meanings).

    Parameters
    ----------
    variable : str
        Name of the flagged variable.
    long_name : str, optional
        The flag variable's ``long_name``; default "QARTOD quality flag of <variable>".

    Returns
    -------
    dict
        ``units``, ``long_name``, ``standard_name`` (quality_flag), ``flag_values``,
        ``flag_meanings`` and ``references``.

    References
    ----------
    U.S. IOOS (2020). Manual for the use of real-time oceanographic data quality control flags,
    v1.2, Table 2.

    CF conventions, §3.5 Flags.

    Examples
    --------
    >>> from flumekit.qc.flags import flag_attrs
    >>> flag_attrs("eta")["flag_meanings"]
    'pass not_evaluated suspect fail missing_data'
    """
    return {"units": "1", "long_name": long_name or f"QARTOD quality flag of {variable}",
            "standard_name": "quality_flag", "flag_values": FLAG_VALUES,
            "flag_meanings": FLAG_MEANINGS,
            "references": "U.S. IOOS QARTOD flag scheme (1 pass, 2 not evaluated, 3 suspect, "
                          "4 fail, 9 missing)"}


def aggregate(*flags: np.ndarray) -> np.ndarray:
    """Return the worst flag per sample over several tests' flags of the same shape.

    ``NOT_EVALUATED`` (2) ranks below ``GOOD`` so that a sample any test passed reads 1;
    ``MISSING`` (9) ranks above ``FAIL`` (4).

    Parameters
    ----------
    *flags : numpy.ndarray
        QARTOD flags of each test (int8 or uint8), all of one shape.

    Returns
    -------
    numpy.ndarray
        Aggregate flags (int8), of that shape.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.flags import aggregate
    >>> aggregate(np.array([1, 2, 2, 3], np.int8), np.array([2, 1, 2, 4], np.int8)).tolist()
    [1, 1, 2, 4]
    """
    # the flag values are their order of severity but for NOT_EVALUATED, which is taken as 0
    # for the maximum and restored after: byte arithmetic, cheaper than a table lookup
    # (np.take) per test on a UVP beam
    worst = None
    for f in flags:
        f = np.asarray(f)
        f = f.view(np.uint8) if f.dtype == np.int8 else f.astype(np.uint8)
        key = f - choose(f == NOT_EVALUATED, NOT_EVALUATED, 0)
        worst = key if worst is None else np.maximum(worst, key, out=worst)
    worst += choose(worst == 0, NOT_EVALUATED, 0)
    return worst.view(np.int8)


def choose(condition: np.ndarray, yes: int, no: int) -> np.ndarray:
    """Return flag ``yes`` where ``condition``, else ``no``, as bytes (uint8).

    Byte arithmetic on the condition (``no + condition * (yes - no)``, modulo 256), which costs
    much less than numpy's ``where`` with two scalars or a masked assignment on an irregular
    condition.

    Parameters
    ----------
    condition : array_like
        Boolean condition.
    yes : int
        Flag where ``condition``.
    no : int
        Flag elsewhere.

    Returns
    -------
    numpy.ndarray
        Flags (uint8) of the shape of ``condition``.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.flags import choose
    >>> choose(np.array([True, False]), 4, 1).tolist()
    [4, 1]
    """
    f = np.asarray(condition, dtype=bool).view(np.uint8) * np.uint8((yes - no) % 256)
    f += np.uint8(no)
    return f

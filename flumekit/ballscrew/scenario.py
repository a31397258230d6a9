"""The reference scenario of Senatore & De Simone (2022) and the results the paper states.

The paper gives no table of numbers for its scenario, only statements (§3.1-3.2 and §4): the
indirect efficiency ranges "from 73 % to 97 %"; the ball screw "operates largely under
mixed-mode lubrication"; "electrical losses four times higher than frictional losses"; the nut
shows "a uniform temperature increase just above 40 °C"; the EMRG is "the most thermally
stressed component" (Figs. 17-18 show its field); "simulation times equal to 100 min allow the
temperature to reach the steady-state value in each component" (lumped model, Fig. 16).
:func:`stated_results` turns each statement into a number of flumekit's scenario and the
interval that the paper's wording allows (its precision: integers of per cent for η, one
significant figure for "four times", "just above 40" read as 40-42 K). The unstated parameters
chosen to meet them are documented where they are defined (:class:`~flumekit.ballscrew.screw.
BallScrew`, :class:`~flumekit.ballscrew.screw.Lubricant`,
:class:`~flumekit.ballscrew.thermal.lumped.LumpedThermal`,
:class:`~flumekit.ballscrew.thermal.fem.PTOGeometry`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from flumekit.ballscrew import buoy, ehl, screw
from flumekit.ballscrew.thermal import fem, lumped
from flumekit.docstrings import doc

#: The regions of the FEM section that belong to the EMRG (electro-mechanical reciprocating
#: generator): its stator, the air gap and its rotor on the screw shaft.
GENERATOR_REGIONS = ("stator", "air_gap", "rotor", "rotor_hub")


@dataclass(frozen=True)
class StatedResult:
    """One statement of the paper, its admissible interval and flumekit's value.

    Parameters
    ----------
    quantity : str
        What is compared.
    paper : str
        The paper's wording.
    low : float
        Lower end of the interval the wording allows [``unit``].
    high : float
        Upper end [``unit``].
    value : float
        flumekit's value [``unit``].
    unit : str
        Unit of the interval and the value.

    Examples
    --------
    >>> from flumekit.ballscrew.scenario import StatedResult
    >>> StatedResult("lowest indirect efficiency", "73 %", 72.5, 73.5, 73.1, "%").holds
    True
    """

    quantity: str
    paper: str
    low: float
    high: float
    value: float
    unit: str

    @property
    def holds(self) -> bool:
        """Return whether the value lies in the interval.

        Returns
        -------
        bool
            low ≤ value ≤ high.
        """
        return bool(self.low <= self.value <= self.high)


@doc
def reference_scenario(amplitude: float = 1.0, period: float = 3.8,
                       samples_per_period: int = 380) -> tuple[xr.Dataset, xr.Dataset,
                                                               xr.Dataset]:
    """Compute the efficiency, lumped and FEM thermal datasets of the paper's scenario (§3.1-3.2).

    The buoy's kinematics (:func:`flumekit.ballscrew.buoy.kinematics`), the ball screw's
    efficiency (:func:`flumekit.ballscrew.screw.efficiency`), then the lumped
    (:func:`flumekit.ballscrew.thermal.lumped.thermal_lumped`) and FEM
    (:func:`flumekit.ballscrew.thermal.fem.thermal_fem`) thermal models.

    Parameters
    ----------
    amplitude : float
        Amplitude of the buoy's vertical motion [m] (1 m in the paper).
    period : float
        Wave period [s] (3.8 s in the paper).
    samples_per_period : int
        Samples of the kinematic input per period [-].

    Returns
    -------
    efficiency : xarray.Dataset
        The efficiency dataset.
    lumped : xarray.Dataset
        The lumped thermal dataset.
    fem : xarray.Dataset
        The FEM thermal dataset.

    %(references_senatore2022)s, §3.1-3.2.

    Examples
    --------
    One period of the paper's motion (A = 1 m, T = 3.8 s) in 380 samples turns the 20 mm lead
    screw at ω = 2π v / lead, up to about 1170 rpm, and drives the thermal models for the
    paper's 100 min:

    >>> import numpy as np
    >>> from flumekit.ballscrew.scenario import reference_scenario
    >>> eff, th, fem = reference_scenario()
    >>> eff.sizes["time"], round(float(eff.time[1]), 6)  # T / 380
    (380, 0.01)
    >>> bool(np.allclose(eff.screw_speed, 2 * np.pi * eff.nut_velocity / 0.02))
    True
    >>> round(float(abs(eff.screw_speed).max()) * 60 / (2 * np.pi), -1)  # [rpm]
    1170.0
    >>> float(th.time[-1]) / 60.0, th.component.values.tolist()
    (100.0, ['generator', 'screw', 'nut'])
    """
    kin = buoy.kinematics(buoy.reference_motion(amplitude, period,
                                                samples_per_period=samples_per_period))
    eff = screw.efficiency(kin)
    th = lumped.thermal_lumped(eff)
    return eff, th, fem.thermal_fem(th)


@doc
def steady_fraction_lumped(th: xr.Dataset) -> np.ndarray:
    """Return each lump's temperature rise over the last cycle as a fraction of its steady rise.

    The steady (cycle-mean) rise solves K ΔT = s̄ with s̄ the mean heat sources of Eqs. (8)-(10);
    the rise reached is the mean over the last cycle of the run.

    Parameters
    ----------
    th : xarray.Dataset
        Output of :func:`flumekit.ballscrew.thermal.lumped.thermal_lumped`.

    Returns
    -------
    numpy.ndarray
        Fraction per lump (component) [-].

    %(references_senatore2022)s, Eqs. (8)-(10) and Fig. 16.
    """
    params = lumped.LumpedThermal(**{k: th.attrs[k] for k in
                                     lumped.LumpedThermal.__dataclass_fields__})
    _, k, _ = lumped.system_matrices(params)
    cycle = float(th.attrs["cycle_duration"])
    t = th["time"].values
    last = t >= t[-1] - cycle
    src = th["heat_source"].values[last].mean(axis=0)
    rise = th["temperature"].values[last].mean(axis=0) - params.initial_temperature
    return rise / np.linalg.solve(k, src)


def hottest_region(fem_ds: xr.Dataset) -> str:
    """Return the name of the FEM region holding the hottest node at the last stored time.

    Parameters
    ----------
    fem_ds : xarray.Dataset
        Output of :func:`flumekit.ballscrew.thermal.fem.thermal_fem`: ``temperature_field``
        [K] over (snapshot_time, node), ``cell_nodes``, ``cell_region`` and ``region``.

    Returns
    -------
    str
        The region's name; in the paper's scenario the EMRG (Figs. 17-18).
    """
    field = fem_ds["temperature_field"].values[-1]
    cells = fem_ds["cell_nodes"].values
    region = fem_ds["cell_region"].values
    hottest_cell = int(np.argmax(field[cells].max(axis=1)))
    return str(fem_ds["region"].values[region[hottest_cell]])


@doc
def stated_results(eff: xr.Dataset, th: xr.Dataset, fem_ds: xr.Dataset) -> list[StatedResult]:
    """Compare each statement of the paper about its scenario with flumekit's value.

    See the module's description for the statements and the intervals their wording allows.

    Parameters
    ----------
    eff : xarray.Dataset
        The efficiency dataset of :func:`reference_scenario`.
    th : xarray.Dataset
        The lumped thermal dataset.
    fem_ds : xarray.Dataset
        The FEM thermal dataset.

    Returns
    -------
    list of StatedResult
        One per statement.

    %(references_senatore2022)s, §3.1-3.2 and §4.

    Examples
    --------
    Every statement holds for the reference scenario; the first is the lowest indirect
    efficiency, "73 %":

    >>> from flumekit.ballscrew.scenario import reference_scenario, stated_results
    >>> results = stated_results(*reference_scenario())
    >>> len(results), all(r.holds for r in results)
    (9, True)
    >>> results[0].quantity, round(results[0].value, 1), results[0].unit
    ('lowest indirect efficiency', 73.1, '%')
    """
    indirect = eff["power_flow_direction"].values > 0
    eta = 100 * eff["ballscrew_efficiency"].values[indirect]
    mixed = 100 * np.mean(eff["lubrication_regime_screw"].values == 1)
    mixed_nut = 100 * np.mean(eff["lubrication_regime_nut"].values == 1)
    ratio = float(th["electrical_power_loss"].mean() / th["mechanical_power_loss"].mean())
    comp = list(th["component"].values)
    rise = th["temperature"].values[-1] - float(th.attrs["initial_temperature"])
    steady = 100 * steady_fraction_lumped(th)
    in_generator = hottest_region(fem_ds) in GENERATOR_REGIONS
    lo, hi = ehl.REGIME_LIMITS
    return [
        StatedResult("lowest indirect efficiency", "73 %", 72.5, 73.5, float(eta.min()), "%"),
        StatedResult("highest indirect efficiency", "97 %", 96.5, 97.5, float(eta.max()), "%"),
        StatedResult(f"time with the screw contact mixed ({lo:g} <= lambda < {hi:g})",
                     "largely mixed", 50.0, 100.0, float(mixed), "%"),
        StatedResult("time with the nut contact mixed", "largely mixed", 50.0, 100.0,
                     float(mixed_nut), "%"),
        StatedResult("electrical / frictional losses", "four times", 3.5, 4.5, ratio, "1"),
        StatedResult("nut temperature rise at 100 min (lumped)", "just above 40 °C", 40.0, 42.0,
                     float(rise[comp.index("nut")]), "K"),
        StatedResult("generator rise minus nut rise (lumped)", "EMRG warmer than the nut", 0.0,
                     np.inf, float(rise[comp.index("generator")] - rise[comp.index("nut")]), "K"),
        StatedResult("hottest FEM region is in the EMRG at 100 min", "EMRG most stressed", 1.0,
                     1.0, float(in_generator), "1"),
        StatedResult("slowest lump's share of its steady rise at 100 min (lumped)",
                     "steady state", 98.0, 100.5, float(steady.min()), "%"),
    ]


def table(results: list[StatedResult]) -> str:
    """Return the stated results as a plain-text table.

    Parameters
    ----------
    results : list of StatedResult
        The results (:func:`stated_results`).

    Returns
    -------
    str
        One header line and one line per result.

    Examples
    --------
    >>> from flumekit.ballscrew.scenario import StatedResult, table
    >>> print(table([StatedResult("ratio", "four times", 3.5, 4.5, 4.0, "1")]).split()[-1])
    yes
    """
    rows = [f"{'quantity':<62} {'paper':<26} {'flumekit':>9} {'interval':>15}  ok"]
    for r in results:
        rows.append(f"{r.quantity:<62} {r.paper:<26} {r.value:>9.2f} "
                    f"{f'[{r.low:g}, {r.high:g}]':>15}  {'yes' if r.holds else 'NO'}")
    return "\n".join(rows)

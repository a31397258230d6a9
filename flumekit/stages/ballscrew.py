"""Stage: the ball-screw WEC of Senatore & De Simone (2022), step by step.

kinematics -> efficiency -> thermal_lumped -> thermal_fem, each its own rule, so that a scene
asking only for the efficiency never runs the thermal finite-element model.

The study needs no instrument and no run, so it is part of a pipeline only when the pipeline
asks for it (:func:`wanted`): a ``[stages.ballscrew]`` table, or a scene naming its targets
(an entry beginning ``ballscrew/`` or ``figure/bs_fig``). A wave-flume campaign's pipeline
that asks for neither lists no ``ballscrew/*`` or ``figure/bs_fig*`` target.

Each step's action follows the protocol of :mod:`flumekit.stages`, reads the previous step's
dataset (``previous``; none for the kinematics) and writes ``ballscrew/<step>.nc``.

References
----------
Senatore, A. and De Simone, A. (2022). Modeling and simulation of a wave energy converter:
multibody system coupled to fluid-film lubrication model and thermal analysis. Energies 15,
9358.
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule

# the parameters (DEFAULTS, DOCS) and the models' knobs, in their own module
from flumekit.stages.ballscrew_params import DEFAULTS, DOCS, MODEL_KNOBS  # noqa: F401
from flumekit.stages.context import Context

VERSION = "2"

STEPS = ("kinematics", "efficiency", "thermal_lumped", "thermal_fem")
#: which step's dataset each figure of the paper is drawn from
FIGURE_SOURCES = {9: "thermal_lumped", 10: "thermal_fem", 11: "efficiency", 12: "efficiency",
                  13: "efficiency", 14: "efficiency", 15: "efficiency", 16: "thermal_lumped",
                  17: "thermal_fem", 18: "thermal_fem"}


#: how a scene entry names the study's targets: ballscrew/<step> and figure/bs_fig<n>
PREFIXES = ("ballscrew/", "figure/bs_fig")


def wanted(ctx: Context) -> bool:
    """Return whether the pipeline asks for the ball-screw study.

    It does with a ``[stages.ballscrew]`` table in ``ctx.params``, or a scene entry beginning
    with one of :data:`PREFIXES`.
    """
    return "ballscrew" in ctx.params or any(
        t.startswith(PREFIXES) for targets in ctx.scenes.values() for t in targets)


def rules(ctx: Context, p: dict) -> list[Rule]:
    """Return one rule per step of :data:`STEPS`; none unless the pipeline asks (:func:`wanted`).

    Protocol: :mod:`flumekit.stages`; each step's rule carries only the parameters it uses.
    """
    if not wanted(ctx):
        return []
    keys = {"kinematics": ("amplitude", "period", "samples_per_period", "lead"),
            "efficiency": (),
            "thermal_lumped": ("cycle_duration", "total_duration", "lumped_time_step"),
            "thermal_fem": ("fem_time_step", "radial_cell_size", "axial_cell_size", "fem_order")}
    for step, parts in MODEL_KNOBS.items():  # only the knobs a pipeline sets enter the rule
        keys[step] += tuple(f"{part}_{name}" for part, names in parts.items() for name in names
                            if p[f"{part}_{name}"] is not None)
    out, previous = [], None
    for step in STEPS:
        inputs = {} if previous is None else {"previous": ctx.out("ballscrew", f"{previous}.nc")}
        out.append(Rule(f"ballscrew/{step}", f"flumekit.stages.ballscrew:{step}", inputs=inputs,
                        outputs={"dataset": ctx.out("ballscrew", f"{step}.nc")},
                        params={k: p[k] for k in keys[step]}, version=VERSION))
        previous = step
    return out


def _write(ds, outputs, title, params) -> Written:
    from flumekit.io.netcdf import write_product

    return write_product(ds, outputs["dataset"], title,
                         "flumekit ballscrew stage (Senatore & De Simone 2022 models)", params)


def _previous(inputs):
    from flumekit.io.netcdf import read_dataset

    return read_dataset(inputs["previous"])


def kinematics(inputs, outputs, params) -> Written:
    """Compute the buoy's reference motion and the linkage kinematics (the first step)."""
    from flumekit.ballscrew import buoy

    motion = buoy.reference_motion(params["amplitude"], params["period"],
                                   samples_per_period=params["samples_per_period"])
    return _write(buoy.kinematics(motion, lead=params["lead"]), outputs,
                  "Ball-screw WEC: buoy motion and linkage kinematics", params)


def _knobs(params, part: str) -> dict:
    """Return the ``<part>_<field>`` parameters a pipeline set, as the model's keywords."""
    return {k[len(part) + 1:]: v for k, v in params.items() if k.startswith(part + "_")}


def efficiency(inputs, outputs, params) -> Written:
    """Compute the PTO force, lubrication regime and efficiency of the ball screw.

    From the kinematics, with the ``screw_*``, ``lubricant_*`` and ``pto_*`` knobs a pipeline set
    (:data:`MODEL_KNOBS`; unset: the model's default).
    """
    from flumekit.ballscrew import screw as ballscrew

    kin = _previous(inputs)
    eff = ballscrew.efficiency(
        kin, screw=ballscrew.BallScrew(lead=float(kin.attrs["lead"]), **_knobs(params, "screw")),
        lubricant=ballscrew.Lubricant(**_knobs(params, "lubricant")),
        pto=ballscrew.PTOCoefficients(**_knobs(params, "pto")))
    return _write(eff, outputs, "Ball-screw WEC: PTO force, lubrication and efficiency", params)


def thermal_lumped(inputs, outputs, params) -> Written:
    """Run the lumped thermal model of the ball-screw PTO on the efficiency's losses.

    With the ``thermal_*`` knobs a pipeline set (:data:`MODEL_KNOBS`).
    """
    from flumekit.ballscrew.thermal.lumped import LumpedThermal
    from flumekit.ballscrew.thermal.lumped import thermal_lumped as run

    ds = run(_previous(inputs), LumpedThermal(**_knobs(params, "thermal")),
             cycle_duration=params["cycle_duration"], total_duration=params["total_duration"],
             time_step=params["lumped_time_step"])
    return _write(ds, outputs, "Ball-screw WEC: lumped thermal model", params)


def thermal_fem(inputs, outputs, params) -> Written:
    """Run the axisymmetric finite-element thermal model of the ball screw (the last step)."""
    from flumekit.ballscrew.thermal.fem import thermal_fem as run

    return _write(run(_previous(inputs), time_step=params["fem_time_step"],
                      radial_cell_size=params["radial_cell_size"],
                      axial_cell_size=params["axial_cell_size"], order=params["fem_order"]),
                  outputs, "Ball-screw WEC: axisymmetric finite-element thermal model", params)

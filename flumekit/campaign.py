"""Typed campaign and run metadata, read from the TOML files of a raw campaign (raw/README.md).

Each file is validated against its schema (:data:`CAMPAIGN`, :data:`RUN`) before anything is
built from it: every problem of a file is reported at once, naming the file, the key and what
was expected; an unknown key is an error with the closest known name.
"""

from __future__ import annotations

import difflib
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from flumekit.docstrings import doc
from flumekit.schema import Key, Problem, raise_problems, read_toml, suggest, validate

# --------------------------------------------------------------------------------------------
# Schemas: what each file may hold (flumekit.schema validates them, every problem at once)
# --------------------------------------------------------------------------------------------

def _num(doc: str, unit: str = "", **kw) -> Key:
    return Key("number", doc, unit, **kw)


def _still_water_check(v: Any) -> str | None:
    if isinstance(v, str):
        return None if v in STILL_WATER_RULES else (
            f"expected one of {list(STILL_WATER_RULES)}, a level [m], [start, end] [s] or a "
            f"table probe = level [m], got {v!r}")
    if isinstance(v, list):
        if len(v) != 2 or not v[0] < v[1]:
            return f"a still segment is [start, end] in seconds with start < end, got {v!r}"
    if isinstance(v, dict):
        bad = [k for k, x in v.items() if not isinstance(x, (int, float)) or isinstance(x, bool)]
        if bad:
            return f"levels must be numbers [m], not for {bad}"
    return None


#: still-water rules by name (a number, a segment or a table per probe are the other forms)
STILL_WATER_RULES = {
    "mean": "the record mean of each probe",
    "none": "nothing removed (calibrated voltages already refer to the still-water level)",
}
STILL_WATER = Key(
    "text", "still-water level removed from each probe's elevation: 'mean' (record mean), "
    "'none', a level [m] for every probe, [start, end] [s] (mean of a still segment before the "
    "waves arrive) or a table probe = level [m]", required=False,
    kinds=("number", "numbers", "table"), check=_still_water_check)


def _columns_check(v: Any) -> str | None:
    vals = v.values() if isinstance(v, dict) else v
    if not all((isinstance(c, str) or (isinstance(c, int) and not isinstance(c, bool) and c >= 1))
               for c in vals):
        return "columns are header names (strings) or 1-based column numbers"
    return None


def _units_check(v: Any) -> str | None:
    from flumekit.units import UNITS

    vals = list(v.values()) if isinstance(v, dict) else [v]
    bad = [u for u in vals if not isinstance(u, str) or u not in UNITS]
    return f"unknown unit(s) {bad}; known: {' '.join(UNITS)}" if bad else None


def _delimiter_check(v: str) -> str | None:
    return None if len(v) == 1 or v == "whitespace" else \
        f"a delimiter is one character (',', ';', '\\t') or 'whitespace', got {v!r}"


def _encoding_check(v: str) -> str | None:
    import codecs

    try:
        codecs.lookup(v)
    except LookupError:
        return f"unknown encoding {v!r}; e.g. 'utf-8', 'cp1252', 'latin-1'"
    return None


def _timezone_check(v: str) -> str | None:
    import zoneinfo

    if not v:
        return None
    try:
        zoneinfo.ZoneInfo(v)
    except (zoneinfo.ZoneInfoNotFoundError, ValueError):
        return f"unknown time zone {v!r}; an IANA name such as 'Europe/Lisbon'"
    return None


#: how an instrument's file is written (io.dialects reads it): one schema for every instrument
DIALECT: dict[str, Key] = {
    "file": Key("text", "file name in each run folder (calibration: relative to the campaign "
                "folder); a run's [files] table may override it", required=False),
    "format": Key("text", "file format", required=False, default="csv",
                  choices=("csv", "tdms", "hdf5", "netcdf")),
    "delimiter": Key("text", "csv: column delimiter (',', ';', '\\t' or 'whitespace')",
                     required=False, default=",", check=_delimiter_check),
    "decimal": Key("text", "csv: decimal mark", required=False, default=".",
                   choices=(".", ",")),
    "comment": Key("text", "csv: lines starting with this text are skipped", required=False,
                   default=""),
    "skip_lines": Key("integer", "csv: preamble lines before the header (or the data)",
                      required=False, default=0, nonnegative=True),
    "header": Key("bool", "csv: the first (non-preamble) line names the columns",
                  required=False, default=True),
    "columns": Key("table", "channel -> column: a header name or a 1-based column number "
                   "(csv), 'group/channel' or a channel name (tdms), a variable path (hdf5, "
                   "netcdf); a list gives them in channel order; default: the channel names",
                   required=False, kinds=("any",), items=Key("any"), check=_columns_check),
    "units": Key("text", "one unit for every channel, or a table channel = unit (also 'time'); "
                 "default: the unit in the header cell 'name [unit]' or the file's unit "
                 "attribute", required=False, kinds=("table",), items=Key("text"),
                 check=_units_check),
    "time": Key("text", "the time column (numbers, or datetimes taken relative to the first "
                "sample), or 'rate' for time from the sampling rate", required=False,
                default="time", kinds=("integer",)),
    "group": Key("text", "tdms, hdf5, netcdf: the group holding the channels", required=False,
                 default=""),
    "encoding": Key("text", "csv: text encoding ('utf-8', with or without byte-order mark; "
                    "'cp1252', 'latin-1', ...)", required=False, default="utf-8",
                    check=_encoding_check),
    "timezone": Key("text", "csv: IANA time zone of date-time stamps written without a UTC "
                    "offset (local time, e.g. 'Europe/Lisbon'): they are put on UTC, across a "
                    "daylight-saving change", required=False, default="",
                    check=_timezone_check),
}

FRICTION = {k: _num(d, u, nonnegative=True) for k, d, u in (
    ("sigma0", "bristle stiffness", "N m-1"), ("sigma1", "bristle micro-damping", "N s m-1"),
    ("sigma2", "viscous friction coefficient", "N s m-1"), ("coulomb_force", "F_c", "N"),
    ("static_force", "F_s", "N"), ("stribeck_velocity", "x_s", "m s-1"),
    ("stribeck_exponent", "n", "1"), ("minimum_friction_velocity", "x_b", "m s-1"),
    ("tau_hp", "film time constant, acceleration", "s"),
    ("tau_hm", "film time constant, deceleration", "s"),
    ("tau_h0", "film time constant, dwell", "s"))}

BEAM = {"x": _num("x of the transducer face", "m"),
        "dz": _num("face elevation relative to the run's UVP elevation", "m"),
        "angle_deg": _num("beam angle above the horizontal, towards +x", "degree")}

#: campaign.toml; [flap], [pto] and [encoder] together declare the flap instruments, [uvp] the
#: velocity profiler; a campaign with [probes] only is a waves study
CAMPAIGN: dict[str, Key] = {
    "campaign": Key("table", "name and title", table={
        "name": Key("text", "short name of the campaign"),
        "title": Key("text", "title written into every dataset", required=False)}),
    "flume": Key("table", "the flume", table={
        "water_depth": _num("still water depth h", "m", positive=True),
        "width": _num("flume width", "m", positive=True, required=False),
        "length": _num("flume length", "m", positive=True, required=False),
        "density": _num("water density rho (the energy flux of irregular seas)", "kg m-3",
                        positive=True, required=False, default=1000.0)}),
    "flap": Key("table", "bottom-hinged flap (with [pto] and [encoder])", required=False,
                table={
        "height": _num("flap height (descriptive)", "m", positive=True, required=False),
        "width": _num("flap width", "m", positive=True),
        "thickness": _num("flap thickness", "m", positive=True),
        "mass": _num("flap mass (descriptive)", "kg", positive=True, required=False),
        "inertia": _num("moment of inertia about the hinge", "kg m2", positive=True),
        "hinge_height": _num("hinge above the bed", "m", nonnegative=True),
        "cog_height": _num("centre of mass above the hinge (descriptive)", "m",
                           required=False),
        "buoyancy_stiffness": _num("linearised net buoyancy torque per radian C",
                                   "N m rad-1")}),
    "pto": Key("table", "hydraulic cylinder power take-off", required=False, table={
        "bed_anchor": Key("point", "bed anchor (x, z)", "m"),
        "flap_anchor": Key("point", "flap anchor (x, z) at theta = 0", "m"),
        "bore_diameter": _num("cylinder bore", "m", positive=True),
        "atmospheric_pressure": _num("atmospheric pressure", "Pa", positive=True,
                                     required=False, default=101325.0),
        "vapour_pressure": _num("vapour pressure (absolute)", "Pa", positive=True,
                                required=False, default=2339.0),
        "friction": Key("table", "modified LuGre friction (Appendix B)", required=False,
                        table=FRICTION)}),
    "encoder": Key("table", "wire encoder of Eq. (1) (also the pressure sensor's rate)",
                   required=False, table={
        "L5": _num("hinge to wire anchor", "m", positive=True),
        "L7": _num("wire length at theta = 0", "m", positive=True),
        "counts_per_metre": _num("encoder counts per metre of wire", "m-1", positive=True),
        "sampling_rate": _num("sampling rate of encoder and pressure", "Hz", positive=True)}),
    "probes": Key("table", "wave probes", table={
        "names": Key("names", "probe names"),
        "separation": Key("names", "probes used for the incident/reflected separation "
                          "(default: all)", required=False),
        "sampling_rate": _num("sampling rate", "Hz", positive=True),
        "units": Key("text", "unit of the recorded probe channels: a voltage unit (V, mV) "
                     "needs the static calibration; a length unit (m, cm, mm) is already "
                     "calibrated", required=False, default="V", check=_units_check),
        "still_water": STILL_WATER}),
    "uvp": Key("table", "ultrasonic velocity profiler; one [uvp.<beam>] table per beam",
               required=False, table={
        "frequency": _num("emitting frequency", "Hz", positive=True),
        "sampling_rate": _num("profile rate per beam", "Hz", positive=True),
        "n_channels": Key("integer", "channels per profile", positive=True),
        "start_channel": _num("distance of channel 0", "m", nonnegative=True),
        "channel_distance": _num("channel spacing", "m", positive=True),
        "channel_width": _num("channel width", "m", positive=True),
        "sound_speed": _num("speed of sound", "m s-1", positive=True),
        "beams": Key("names", "beam (transducer) names")},
        items=Key("table", "one beam", table=BEAM)),
    "files": Key("table", "how each instrument's files are written (default: the flumekit CSV)",
                 required=False, table={
        "probes": Key("table", "wave probe records", required=False, table=DIALECT),
        "flap": Key("table", "encoder and pressure records", required=False, table=DIALECT),
        "calibration": Key("table", "static probe calibration", required=False,
                           table=DIALECT)}),
    "scale": Key("table", "Froude scale of the model (flumekit.scale: prototype values)",
                 required=False, table={
        "factor": _num("geometric scale lambda = L_prototype / L_model", "1", positive=True),
        "model_density": _num("water density of the model test", "kg m-3", positive=True,
                              required=False, default=1000.0),
        "prototype_density": _num("sea water density at full scale", "kg m-3", positive=True,
                                  required=False, default=1025.0)}),
}

#: deepest still water a campaign may declare [m]: the deepest wave basins hold tens of metres
MAX_WATER_DEPTH = 1000.0

#: the Type B components of [uncertainty]: name -> (unit, meaning, default distribution, default
#: value or None when derived from the campaign's own data, where the default comes from).
#: ``value`` is the standard uncertainty of a normal distribution or the half-width of a
#: rectangular one (GUM 4.3.7: u = a / sqrt(3)).
UNCERTAINTY_COMPONENTS: dict[str, tuple[str, str, str, float | None, str]] = {
    "probe_noise": ("m", "wave probe noise, per sample", "normal", None,
                    "the RMS residual of the static calibration (calibration.nc)"),
    "probe_resolution": ("m", "wave probe digitisation step, per sample (half-width: half "
                         "the step)", "rectangular", 0.5e-4,
                         "not in the paper: 0.1 mm steps (16-bit over +-10 V at ~10 V m-1)"),
    "calibration": ("1", "relative uncertainty of each probe's calibration gain",
                    "normal", None, "the standard error of the fitted gain (calibration.nc "
                    "residuals over the spread of the static levels)"),
    "probe_position": ("m", "position x of each probe", "normal", 1.0e-3,
                       "not in the paper: 1 mm (tape measure along the flume)"),
    "water_depth": ("m", "still water depth", "normal", 1.0e-3,
                    "not in the paper: 1 mm (point gauge)"),
    "encoder_resolution": ("m", "wire encoder step (half-width: half a count)", "rectangular",
                           None, "half of 1 / counts_per_metre of [encoder]"),
    "pressure_accuracy": ("1", "pressure sensor accuracy as a fraction of its rated output, "
                          "per sample", "normal", 0.002,
                          "Brito et al. (2020), §2.3: 0.2 % of the rated output"),
    "flap_inertia": ("1", "relative uncertainty of the flap's moment of inertia", "normal",
                     0.02, "not in the paper: 2 % (pendulum test)"),
    "clock_offset": ("s", "time offset between the probes' and the flap's clocks", "normal",
                     0.01, "not in the paper: one encoder sample (100 Hz)"),
    "uvp_velocity_resolution": ("m s-1", "UVP velocity resolution (half-width)", "rectangular",
                                0.7e-3, "not in the paper: Met-Flow UVP-DUO at 2 MHz, ~0.7 "
                                "mm s-1"),
}


def _component_key(name: str) -> Key:
    unit, doc, dist, value, source = UNCERTAINTY_COMPONENTS[name]
    return Key("table", f"{doc} [{unit}]; default {value if value is not None else source} "
               f"({dist})", required=False, table={
                   "value": _num(f"standard uncertainty (normal) or half-width (rectangular); "
                                 f"default: {source}", unit, nonnegative=True, required=False),
                   "distribution": Key("text", "normal or rectangular", required=False,
                                       default=dist, choices=("normal", "rectangular")),
                   **({"rated_output": _num("rated output of the pressure sensor", "Pa",
                                            positive=True, required=False, default=1.0e6)}
                      if name == "pressure_accuracy" else {})})


CAMPAIGN["uncertainty"] = Key(
    "table", "Type B uncertainty components of the instruments and set-up, each a table "
    "{value, distribution}; an absent component takes its documented default",
    required=False, table={k: _component_key(k) for k in UNCERTAINTY_COMPONENTS})

INSTRUMENT_FILES = {"probes": "probes.csv", "flap": "flap.csv",
                    "calibration": "calibration/probes.csv"}

#: run kinds: regular waves (with or without UVP) and irregular sea states
RUN_KINDS = ("waves", "uvp", "irregular")
#: the keys of a run.toml's [run] that only a regular, or only an irregular run has
REGULAR_KEYS = ("period", "height")
SEA_STATE_KEYS = ("hm0", "tp", "te", "gamma", "seed", "duration", "transient")

RUN: dict[str, Key] = {
    "run": Key("table", "the wave condition", table={
        "kind": Key("text", "waves (regular), uvp (regular, the run also has .mfprof files) or "
                    "irregular (a sea state: hm0 with tp or te, no period)", required=False,
                    default="waves", choices=RUN_KINDS),
        "period": _num("regular runs: target wave period", "s", positive=True, required=False),
        "height": _num("regular runs: target wave height", "m", positive=True, required=False),
        "hm0": _num("irregular runs: target significant wave height Hm0 = 4 sqrt(m0)", "m",
                    positive=True, required=False),
        "tp": _num("irregular runs: target peak period (or te)", "s", positive=True,
                   required=False),
        "te": _num("irregular runs: target energy period Tm-1,0 (or tp)", "s", positive=True,
                   required=False),
        "gamma": _num("irregular runs: JONSWAP peak enhancement factor of the target spectrum",
                      positive=True, required=False),
        "seed": Key("integer", "irregular runs: seed of the wavemaker's random phases",
                    required=False),
        "duration": _num("irregular runs: nominal duration of the wavemaker signal", "s",
                         positive=True, required=False),
        "transient": _num("irregular runs: start of the analysed span, once the sea state is "
                          "stationary at the probes (the wavemaker's ramp and the first "
                          "reflections, from the device and the beach, arrived); default "
                          "detected from the records (the ramp and the device's reflection "
                          "only)", "s", nonnegative=True, required=False),
        "repeat": Key("integer", "repeat number of the condition", required=False, default=0),
        "uvp_elevation": _num("UVP runs: elevation of the horizontal transducer", "m",
                              required=False),
        "start": Key("datetime", "when the records started, where their files do not say "
                     "(a file that gives its start must agree within 1 s)", required=False)}),
    "probes": Key("table", "x of every probe named in campaign.toml", "m", table={},
                  items=_num("probe position", "m")),
    "still_water": Key("table", "this run's still-water rule, overriding [probes] still_water "
                       "of campaign.toml: rule = ...", required=False,
                       table={"rule": STILL_WATER}),
    "clock": Key("table", "time offset added to each instrument's time stamps to put them on "
                 "the probes' clock [s] (`flumekit clock` estimates one)", required=False,
                 table={k: _num(f"{k} time offset", "s", required=False, default=0.0)
                        for k in ("probes", "flap", "uvp")}),
    "files": Key("table", "this run's instrument files, relative to the run folder, when not "
                 "named as in [files] of campaign.toml", required=False,
                 table={**{k: Key("text", f"{k} record: its file name, or a table of the "
                                  f"keys of [files.{k}] in campaign.toml for this run's own "
                                  "file (another format, delimiter, columns...)",
                                  required=False, kinds=("table",), table=DIALECT)
                           for k in ("probes", "flap")},
                        "shared": Key("names", "instruments whose file lies outside the run "
                                      "folder on purpose (one record several runs share); any "
                                      "other file outside its run folder is an error",
                                      required=False)}),
}


# --------------------------------------------------------------------------------------------
# Typed metadata
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Flume:
    """The wave flume of a campaign (``[flume]`` of campaign.toml).

    Attributes
    ----------
    water_depth : float
        Still-water depth [m].
    width : float or None
        Channel width [m]; required with the flap (the channel of its models).
    length : float or None
        Flume length [m], descriptive: no computation reads it.
    density : float
        Water density [kg m-3], fresh water unless declared.
    """

    water_depth: float  # [m]
    width: float | None = None  # [m], required with the flap (the channel of its models)
    length: float | None = None  # [m], descriptive: no computation reads it
    density: float = 1000.0  # [kg m-3], fresh water unless declared


@dataclass(frozen=True)
class SeaState:
    """The target sea state of an irregular run (a JONSWAP spectrum)."""

    hm0: float  # significant wave height [m]
    tp: float | None = None  # peak period [s] (one of tp and te is declared)
    te: float | None = None  # energy period Tm-1,0 [s]
    gamma: float | None = None  # peak enhancement [-], None when not declared
    seed: int | None = None
    duration: float | None = None  # [s]
    transient: float | None = None  # start of the analysed span [s], None: detected


@dataclass(frozen=True)
class Flap:
    """Bottom-hinged flap (Brito et al. 2020, §2.2). Heights are above the hinge unless named.

    ``height``, ``mass`` and ``cog_height`` describe the flap but no computation reads them
    (the dynamics use ``inertia`` and ``buoyancy_stiffness``): they are optional.
    """

    width: float  # [m]
    thickness: float  # [m]
    inertia: float  # moment of inertia about the hinge [kg m2]
    hinge_height: float  # hinge above the bed [m]
    buoyancy_stiffness: float  # linearised net buoyancy torque per radian C [N m rad-1]
    height: float | None = None  # [m]
    mass: float | None = None  # [kg]
    cog_height: float | None = None  # centre of mass above the hinge [m]


@dataclass(frozen=True)
class Friction:
    """Parameters of the modified LuGre friction model (Brito et al. 2020, Appendix B)."""

    sigma0: float  # bristle stiffness [N m-1]
    sigma1: float  # bristle micro-damping [N s m-1]
    sigma2: float  # viscous friction coefficient [N s m-1]
    coulomb_force: float  # F_c [N]
    static_force: float  # F_s [N]
    stribeck_velocity: float  # x_s [m s-1]
    stribeck_exponent: float  # n [-]
    minimum_friction_velocity: float  # x_b [m s-1]
    tau_hp: float  # film time constant, acceleration [s]
    tau_hm: float  # film time constant, deceleration [s]
    tau_h0: float  # film time constant, dwell [s]


@dataclass(frozen=True)
class PTO:
    """Single-acting hydraulic cylinder between a bed anchor and a flap anchor (§2.2)."""

    bed_anchor: tuple[float, float]  # (x, z) [m], fixed
    flap_anchor: tuple[float, float]  # (x, z) [m] at theta = 0, moves with the flap
    bore_diameter: float  # [m]
    atmospheric_pressure: float  # [Pa]
    vapour_pressure: float  # [Pa], absolute
    friction: Friction | None = None

    @property
    def bore_area(self) -> float:
        """Bore area of the cylinder [m2]."""
        return math.pi * self.bore_diameter**2 / 4


@dataclass(frozen=True)
class Encoder:
    """Wire encoder of Eq. (1): L5 hinge-to-wire-anchor, L7 wire length at theta = 0."""

    L5: float  # [m]
    L7: float  # [m]
    counts_per_metre: float  # encoder counts per metre of wire shortening [m-1]
    sampling_rate: float  # [Hz]


@doc
@dataclass(frozen=True)
class Probes:
    """The wave probes of a campaign (``[probes]`` of campaign.toml).

    Attributes
    ----------
    names : tuple of str
        Probe names, in channel order.
    %(sampling_rate)s
    separation : tuple of str
        Probes used for the incident/reflected separation.
    units : str
        Unit of the recorded channels (:data:`flumekit.units.UNITS`): a voltage is
        calibrated, a length is not.
    still_water : str, list, dict or None
        The still-water rule; None: ``"none"`` for voltages, ``"mean"`` for lengths.
    """

    names: tuple[str, ...]
    sampling_rate: float  # [Hz]
    separation: tuple[str, ...]  # probes used for incident/reflected separation
    units: str = "V"  # unit of the recorded channels (voltage: calibrate; length: calibrated)
    # still-water rule (None: 'none' for voltages, 'mean' for lengths); a list or table is
    # unhashable, and a campaign is hashed (cached hydrodynamics): left out of the hash
    still_water: Any = field(default=None, hash=False)

    @property
    def calibrated(self) -> bool:
        """True when the channels are recorded in length units (no calibration needed)."""
        from flumekit.units import UNITS

        return UNITS[self.units][0] == "length"


@dataclass(frozen=True)
class Beam:
    """One UVP transducer: face position and beam direction (angle above horizontal)."""

    name: str
    x: float  # transducer face x [m]
    dz: float  # transducer face elevation relative to the run's UVP elevation [m]
    angle: float  # beam angle above the horizontal, towards +x [rad]


@dataclass(frozen=True)
class UVP:
    """The ultrasonic velocity profiler of a campaign (``[uvp]`` of campaign.toml).

    Attributes
    ----------
    frequency : float
        Emitting frequency [Hz].
    sampling_rate : float
        Profile rate per beam [Hz].
    n_channels : int
        Channels along each beam.
    start_channel : float
        Distance of channel 0 from the transducer [m].
    channel_distance, channel_width : float
        Spacing and width of the channels [m].
    sound_speed : float
        Speed of sound in the water [m s-1].
    beams : tuple of Beam
        The transducers.
    """

    frequency: float  # emitting frequency [Hz]
    sampling_rate: float  # profile rate per beam [Hz]
    n_channels: int
    start_channel: float  # distance of channel 0 [m]
    channel_distance: float  # [m]
    channel_width: float  # [m]
    sound_speed: float  # [m s-1]
    beams: tuple[Beam, ...]


@dataclass(frozen=True)
class Scale:
    """Froude scale of the model: lambda = L_prototype / L_model and the two densities."""

    factor: float  # [-]
    model_density: float = 1000.0  # [kg m-3]
    prototype_density: float = 1025.0  # [kg m-3]


@dataclass(frozen=True)
class Component:
    """One declared Type B uncertainty component of ``[uncertainty]``.

    Attributes
    ----------
    name : str
        A key of :data:`UNCERTAINTY_COMPONENTS`.
    value : float or None
        The standard uncertainty (normal) or the half-width (rectangular), in the unit of
        :data:`UNCERTAINTY_COMPONENTS`; None when it is derived from the campaign's data
        (calibration residuals, encoder counts).
    distribution : {"normal", "rectangular"}
        Its distribution.
    declared : bool
        False: the documented default.
    rated_output : float or None
        Rated output of the pressure sensor [Pa], ``pressure_accuracy`` only.

    References
    ----------
    JCGM 100:2008, Evaluation of measurement data - Guide to the expression of uncertainty in
    measurement (GUM), §4.3 (Type B evaluation).
    """

    name: str
    value: float | None
    distribution: str  # "normal" or "rectangular"
    declared: bool  # False: the documented default
    rated_output: float | None = None  # [Pa], pressure_accuracy only

    @property
    def standard_uncertainty(self) -> float | None:
        """Standard uncertainty u in the component's unit: the value, or value / √3 if rectangular.

        A rectangular distribution of half-width a has u = a / √3 (JCGM 100:2008, §4.3.7).
        """
        if self.value is None:
            return None
        return self.value / math.sqrt(3.0) if self.distribution == "rectangular" else self.value


def uncertainty_components(table: dict | None) -> tuple[Component, ...]:
    """Return every component of :data:`UNCERTAINTY_COMPONENTS`, declared or at its default.

    Parameters
    ----------
    table : dict or None
        The ``[uncertainty]`` table of campaign.toml (None: every default).

    Returns
    -------
    tuple of Component
        One per component, in the order of :data:`UNCERTAINTY_COMPONENTS`.

    Examples
    --------
    >>> all(not c.declared for c in uncertainty_components(None))
    True
    """
    table = table or {}
    out = []
    for name, (_, _, dist, value, _) in UNCERTAINTY_COMPONENTS.items():
        given = table.get(name, {})
        v = given.get("value", value)
        out.append(Component(name, None if v is None else float(v),
                             given.get("distribution", dist), "value" in given,
                             float(given.get("rated_output", 1.0e6))
                             if name == "pressure_accuracy" else None))
    return tuple(out)


@dataclass(frozen=True)
class Run:
    """One run of a campaign, read from its ``runs/<run>/run.toml``.

    Attributes
    ----------
    id : str
        The run's name (its folder).
    path : pathlib.Path
        Its folder.
    kind : {"waves", "uvp", "irregular"}
        What the run records.
    period : float or None
        Target wave period [s]; None for an irregular run.
    height : float or None
        Target wave height [m]; None when not declared (and for an irregular run).
    repeat : int
        Repetition index of the wave condition.
    probe_x : dict of str to float
        Probe name -> position x [m].
    uvp_elevation : float or None
        Elevation of the UVP beams [m] (UVP runs).
    files : dict of str to pathlib.Path
        Instrument -> raw file.
    clock : dict of str to float
        Instrument -> clock offset [s].
    still_water : object
        The run's still-water rule (None: the campaign's).
    start : str or None
        Declared start of the records, ISO 8601 (``Z``: UTC).
    sea_state : SeaState or None
        The target sea state of an irregular run.
    dialects : dict
        Instrument -> the run's own ``[files.<instrument>]`` keys.
    """

    id: str
    path: Path
    kind: str  # "waves", "uvp" or "irregular"
    period: float | None  # [s], None for an irregular run
    height: float | None  # [m], None when not declared (and for an irregular run)
    repeat: int
    probe_x: dict[str, float]  # probe name -> x [m]
    uvp_elevation: float | None  # [m]
    files: dict[str, Path] = field(default_factory=dict)  # instrument -> file
    clock: dict[str, float] = field(default_factory=dict)  # instrument -> time offset [s]
    still_water: Any = None  # the run's still-water rule (None: the campaign's)
    start: str | None = None  # declared start of the records, ISO 8601 (Z: UTC), see _iso
    sea_state: SeaState | None = None  # the target sea state of an irregular run
    # instrument -> this run's own [files.<instrument>] dialect keys (Campaign.dialect)
    dialects: dict[str, dict] = field(default_factory=dict, hash=False)

    @property
    def irregular(self) -> bool:
        """Whether the run is an irregular sea state (no period, a target spectrum)."""
        return self.kind == "irregular"

    def file(self, instrument: str) -> Path:
        """Return the raw file of an instrument (``"probes"``, ``"flap"``) of this run."""
        return self.files[instrument]


@dataclass(frozen=True)
class Campaign:
    """A raw campaign: its flume, instruments and runs (:func:`load_campaign`).

    Attributes
    ----------
    name, title : str
        The campaign's name and title.
    root : pathlib.Path
        The campaign folder.
    flume : Flume
        The flume.
    flap, pto, encoder : Flap, PTO, Encoder or None
        The flap instruments, declared together or not at all.
    probes : Probes
        The wave probes.
    uvp : UVP or None
        The velocity profiler.
    runs : tuple of Run
        The runs, sorted by folder name.
    files : dict
        Instrument -> its file dialect (``[files.<instrument>]``).
    scale : Scale or None
        Froude scale of the model, when declared.
    uncertainty : tuple of Component
        Every Type B uncertainty component, declared or at its default.
    """

    name: str
    title: str
    root: Path
    flume: Flume
    flap: Flap | None
    pto: PTO | None
    encoder: Encoder | None
    probes: Probes
    uvp: UVP | None
    runs: tuple[Run, ...] = field(default_factory=tuple)
    # instrument -> dialect (io.dialects); not hashed (a dict), see Probes.still_water
    files: dict[str, dict] = field(default_factory=dict, hash=False)
    scale: Scale | None = None  # [scale]: Froude scale of the model, when declared
    # [uncertainty]: every Type B component, declared or at its default
    uncertainty: tuple[Component, ...] = field(default_factory=lambda: uncertainty_components(
        None))

    @property
    def calibration_file(self) -> Path:
        """Path of the probe calibration file."""
        return self.root / self.files.get("calibration", {}).get(
            "file", INSTRUMENT_FILES["calibration"])

    @property
    def instruments(self) -> tuple[str, ...]:
        """The instruments declared: 'probes', then 'flap' (flap, PTO, encoder, pressure), 'uvp'."""
        return ("probes",) + (("flap",) if self.flap else ()) + (("uvp",) if self.uvp else ())

    def dialect(self, instrument: str, run: Run | None = None) -> dict:
        """Return how an instrument's files are written (a dict for ``io.dialects.Dialect``).

        The campaign's ``[files.<instrument>]``, with a run's own keys over it; a run declaring
        another ``format`` than the campaign's has its own dialect alone (a delimiter means
        nothing to an HDF5 file).

        Parameters
        ----------
        instrument : str
            ``"probes"``, ``"flap"``, ``"calibration"`` or ``"uvp"``.
        run : Run, optional
            The run whose own keys apply.

        Returns
        -------
        dict
            The dialect's keys.
        """
        base = dict(self.files.get(instrument, {}))
        own = {} if run is None else dict(run.dialects.get(instrument, {}))
        if "format" in own and own["format"] != base.get("format", "csv"):
            return own
        return {**base, **own}

    def run(self, run_id: str) -> Run:
        """Return the run named ``run_id``; a KeyError naming the campaign if there is none."""
        for r in self.runs:
            if r.id == run_id:
                return r
        raise KeyError(f"campaign '{self.name}' has no run '{run_id}'")


def _table(data: dict, key: str) -> dict:
    v = data.get(key)
    return v if isinstance(v, dict) else {}


def _read_run(path: Path, campaign: Campaign, problems: list[Problem]) -> Run | None:
    data = read_toml(path)
    found = validate(data, RUN, path)
    names = campaign.probes.names
    px = _table(data, "probes")
    for name in names:
        if name not in px:
            found.append(Problem(path, f"probes.{name}", "missing key: x of the probe [m]"))
    for name in px:
        if name not in names:
            found.append(Problem(path, f"probes.{name}", f"unknown probe '{name}'; the campaign "
                                 f"declares {list(names)}" + suggest(name, list(names))))
    r = _table(data, "run")
    kind = r.get("kind", "waves")
    if kind == "uvp" and "uvp_elevation" not in r:
        found.append(Problem(path, "run.uvp_elevation", "missing key: UVP runs need the "
                             "elevation of the horizontal transducer [m]"))
    if kind == "uvp" and campaign.uvp is None:
        found.append(Problem(path, "run.kind", "a 'uvp' run needs [uvp] in campaign.toml"))
    if kind == "irregular":
        found += [Problem(path, f"run.{k}", "an irregular run has no regular-wave " + k
                          + ": declare its sea state (hm0 with tp or te)")
                  for k in REGULAR_KEYS if k in r]
        if "hm0" not in r:
            found.append(Problem(path, "run.hm0", "missing key: the target significant wave "
                                 "height of the irregular run [m]"))
        if ("tp" in r) == ("te" in r):
            found.append(Problem(path, "run.tp", "declare exactly one of tp (peak period) and "
                                 "te (energy period) [s]"))
    else:
        found += [Problem(path, f"run.{k}", f"a regular run ('{kind}') has no sea state: for "
                          "an irregular run declare kind = \"irregular\"")
                  for k in SEA_STATE_KEYS if k in r]
        if "period" not in r:
            found.append(Problem(path, "run.period", "missing key: the target wave period [s] "
                                 "(for an irregular sea state declare kind = \"irregular\" "
                                 "with hm0 and tp or te)"))
    clock = _table(data, "clock")
    for k in clock:
        if k in ("flap", "uvp") and k not in campaign.instruments:
            found.append(Problem(path, f"clock.{k}", f"the campaign declares no {k} instrument"))
    files = {}
    shared = _table(data, "files").get("shared")
    shared = shared if isinstance(shared, list) else []
    for k in shared:
        if k not in ("probes", "flap"):
            found.append(Problem(path, "files.shared", f"unknown instrument {k!r}; the run's "
                                 "files are 'probes' and 'flap'" + suggest(str(k),
                                                                         ["probes", "flap"])))
    dialects = {}
    for inst in ("probes", "flap"):
        given = _table(data, "files").get(inst)
        default = campaign.files.get(inst, {}).get("file", INSTRUMENT_FILES[inst])
        if isinstance(given, dict):  # this run's own dialect
            dialects[inst] = dict(given)
            _check_channels(path, {inst: given}, {"probes": list(names),
                                                  "flap": ["encoder", "pressure"]}, found)
            given = given.get("file", default)
        # normalised, not resolved: "../../record.csv" reads as the file it names
        files[inst] = Path(os.path.normpath(path.parent / (given if isinstance(given, str)
                                                           else default)))
        if inst in campaign.instruments and inst not in shared and not files[inst].is_relative_to(
                Path(os.path.normpath(path.parent))):
            # another run's record read as this run's gives a confident wrong result
            where = (f"files.{inst}", "") if isinstance(given, str) else (
                f"files.{inst}", f" ([files.{inst}] file of campaign.toml)")
            found.append(Problem(path, where[0], f"{files[inst]} lies outside the run folder "
                                 f"{path.parent}{where[1]}: another run's record? If several "
                                 f"runs share it on purpose, declare [files] shared = "
                                 f'["{inst}"] in run.toml'))
    if found:
        problems += found
        return None
    sw = _table(data, "still_water").get("rule")
    sea = None
    if kind == "irregular":
        sea = SeaState(float(r["hm0"]), *(float(r[k]) if k in r else None
                                          for k in ("tp", "te", "gamma")),
                       int(r["seed"]) if "seed" in r else None,
                       *(float(r[k]) if k in r else None for k in ("duration", "transient")))
    return Run(id=path.parent.name, path=path.parent, kind=kind,
               period=float(r["period"]) if "period" in r else None,
               height=float(r["height"]) if "height" in r else None, sea_state=sea,
               repeat=int(r.get("repeat", 0)), probe_x={n: float(px[n]) for n in names},
               uvp_elevation=float(r["uvp_elevation"]) if kind == "uvp" else None,
               files=files, dialects=dialects,
               clock={k: float(clock.get(k, 0.0)) for k in ("probes", "flap", "uvp")},
               still_water=sw, start=_iso(r["start"]) if "start" in r else None)


def _iso(t) -> str:
    """Return the ISO 8601 form of a TOML date-time.

    In UTC with ``Z`` when it has an offset, else as written (the laboratory's clock); the
    fraction of a second without trailing zeros.
    """
    import datetime

    if t.tzinfo is not None:
        t = t.astimezone(datetime.timezone.utc).replace(tzinfo=None)
        zone = "Z"
    else:
        zone = ""
    frac = f".{t.microsecond:06d}".rstrip("0") if t.microsecond else ""
    return t.strftime("%Y-%m-%dT%H:%M:%S") + frac + zone


def _check_channels(path: Path, files: dict, channels: dict[str, list[str]],
                    problems: list[Problem]) -> None:
    """Columns and units of each [files.<instrument>] must name that instrument's channels."""
    for inst, d in files.items():
        known = channels[inst]
        for key in ("columns", "units"):
            v = d.get(key)
            if isinstance(v, dict):
                extra = [k for k in v if k not in known and not (key == "units" and k == "time")]
                for k in extra:
                    problems.append(Problem(path, f"files.{inst}.{key}.{k}", f"unknown channel; "
                                            f"{inst} has {known}" + suggest(k, known)))
            if key == "columns" and isinstance(v, list) and len(v) != len(known):
                problems.append(Problem(path, f"files.{inst}.columns", f"a list of {len(known)} "
                                        f"columns in channel order {known}, got {len(v)}"))


def load_campaign(root: str | Path, runs: bool = True) -> Campaign:
    r"""Read ``root/campaign.toml`` and every ``root/runs/*/run.toml``.

    Every problem of a file is reported at once (one :class:`~flumekit.errors.InputError`
    listing them); the run files are read only when the campaign file is sound. The format of
    the files is described in ``raw/README.md``.

    Parameters
    ----------
    root : str or path-like
        The raw campaign folder.
    runs : bool, default True
        Read the runs too; without them (``campaign.toml`` alone, ``runs`` empty) for what
        needs the set-up only, as a stage's action of one run.

    Returns
    -------
    Campaign
        The campaign with its runs, sorted by folder name.

    Raises
    ------
    flumekit.errors.InputError
        Naming the file and key of every problem: a missing or unknown key (with the closest
        known name), a wrong type, a value out of range, or metadata that contradict each
        other (e.g. a flap wider than the flume).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> tmp = tempfile.TemporaryDirectory()
    >>> root = pathlib.Path(tmp.name)
    >>> _ = (root / "campaign.toml").write_text(
    ...     '[campaign]\nname = "demo"\n[flume]\nwater_depth = 0.5\n'
    ...     '[probes]\nnames = ["WP1", "WP2"]\nsampling_rate = 100.0\n')
    >>> c = load_campaign(root)
    >>> c.flume.water_depth, c.probes.names, c.instruments, c.runs
    (0.5, ('WP1', 'WP2'), ('probes',), ())
    >>> tmp.cleanup()
    """
    root = Path(root)
    path = root / "campaign.toml"
    data = read_toml(path)
    problems = validate(data, CAMPAIGN, path)
    flap_parts = [k for k in ("flap", "pto", "encoder") if k in data]
    if flap_parts and len(flap_parts) < 3:
        missing = sorted({"flap", "pto", "encoder"} - set(flap_parts))
        problems.append(Problem(path, missing[0], f"[flap], [pto] and [encoder] declare the "
                                f"flap instruments together; missing: {missing}"))
    if "uvp" in data and not flap_parts:
        problems.append(Problem(path, "uvp", "the UVP analysis is phased on the flap: declare "
                                "[flap], [pto] and [encoder] too"))
    pr = _table(data, "probes")
    names = pr.get("names") if isinstance(pr.get("names"), list) else []
    sep = pr.get("separation")
    if isinstance(sep, list) and set(sep) - set(names):
        problems.append(Problem(path, "probes.separation",
                                f"names unknown probes {sorted(set(sep) - set(names))}"))
    u = _table(data, "uvp")
    beams = u.get("beams") if isinstance(u.get("beams"), list) else []
    strays = [k for k, v in u.items() if isinstance(v, dict) and k not in beams]
    typos = {c for k in strays for c in difflib.get_close_matches(k, [str(b) for b in beams], 1)}
    for b in beams:
        if b not in u and b not in typos:
            problems.append(Problem(path, f"uvp.{b}", "missing table: x, dz, angle_deg of the "
                                    "beam"))
    for k, v in u.items():
        if isinstance(v, dict) and k not in beams:
            problems.append(Problem(path, f"uvp.{k}", f"a beam not listed in uvp.beams {beams}"
                                    + suggest(k, [str(b) for b in beams])))
    files = {k: v for k, v in _table(data, "files").items() if isinstance(v, dict)}
    _check_channels(path, files, {"probes": list(names), "flap": ["encoder", "pressure"],
                                  "calibration": ["level", *names]}, problems)
    fl, f, p = _table(data, "flume"), _table(data, "flap"), _table(data, "pto")
    if not problems and fl["water_depth"] > MAX_WATER_DEPTH:
        # the wave models overflow (cosh k h) long before; no flume or basin is this deep
        problems.append(Problem(path, "flume.water_depth", f"{fl['water_depth']:g} m is no "
                                f"flume's depth (at most {MAX_WATER_DEPTH:g} m): the depth is in "
                                "metres"))
    if not problems and f:
        if "width" not in fl:
            problems.append(Problem(path, "flume.width", "missing key [m]: the flap's models "
                                    "need the channel width"))
        elif f["width"] > fl["width"]:
            problems.append(Problem(path, "flap.width", f"flap width {f['width']} m exceeds the "
                                    f"flume width {fl['width']} m"))
        if f["hinge_height"] >= fl["water_depth"]:
            problems.append(Problem(path, "flap.hinge_height", "hinge above the still water "
                                    "level"))
        fr = p.get("friction", {})
        if fr and fr["static_force"] < fr["coulomb_force"]:
            problems.append(Problem(path, "pto.friction.static_force",
                                    "static friction force below the Coulomb force"))
        if math.dist(p["bed_anchor"], p["flap_anchor"]) <= 0:
            problems.append(Problem(path, "pto", "PTO anchors coincide"))
    raise_problems(path, problems)

    c = data["campaign"]
    flume = Flume(float(fl["water_depth"]), fl.get("width"), fl.get("length"),
                  float(fl.get("density", 1000.0)))
    flap = pto = enc = None
    if f:
        flap = Flap(**{k: float(f[k]) for k in Flap.__dataclass_fields__ if k in f})
        fr = p.get("friction")
        pto = PTO(tuple(map(float, p["bed_anchor"])), tuple(map(float, p["flap_anchor"])),
                  float(p["bore_diameter"]), float(p.get("atmospheric_pressure", 101325.0)),
                  float(p.get("vapour_pressure", 2339.0)),
                  Friction(**{k: float(fr[k]) for k in FRICTION}) if fr else None)
        e = data["encoder"]
        enc = Encoder(*(float(e[k]) for k in ("L5", "L7", "counts_per_metre", "sampling_rate")))
    probes = Probes(tuple(names), float(pr["sampling_rate"]), tuple(sep or names),
                    pr.get("units", "V"), pr.get("still_water"))
    uvp = None
    if u:
        uvp = UVP(float(u["frequency"]), float(u["sampling_rate"]), int(u["n_channels"]),
                  float(u["start_channel"]), float(u["channel_distance"]),
                  float(u["channel_width"]), float(u["sound_speed"]),
                  tuple(Beam(b, float(u[b]["x"]), float(u[b]["dz"]),
                             math.radians(u[b]["angle_deg"])) for b in beams))
    sc = _table(data, "scale")
    campaign = Campaign(name=c["name"], title=c.get("title", c["name"]), root=root,
                        flume=flume, flap=flap, pto=pto, encoder=enc, probes=probes, uvp=uvp,
                        files=files,
                        scale=Scale(float(sc["factor"]), float(sc.get("model_density", 1000.0)),
                                    float(sc.get("prototype_density", 1025.0))) if sc else None,
                        uncertainty=uncertainty_components(_table(data, "uncertainty")))
    runs_dir = root / "runs"
    if not runs:
        return campaign
    run_files = sorted(runs_dir.glob("*/run.toml")) if runs_dir.is_dir() else []
    run_problems: list[Problem] = []
    read = [_read_run(rp, campaign, run_problems) for rp in run_files]
    if run_problems:
        raise_problems(run_problems[0].path if len({q.path for q in run_problems}) == 1
                       else runs_dir, run_problems)
    return Campaign(**{**campaign.__dict__, "runs": tuple(read)})

"""Typed campaign and run metadata, read from the TOML files of a raw campaign (raw/README.md).

Every field is checked when read; a bad or missing field is an :class:`InputError` naming the
file and the field.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from flumekit.errors import InputError


def read_toml(path: Path) -> dict[str, Any]:
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        raise InputError(path, "file not found") from None
    except tomllib.TOMLDecodeError as e:
        raise InputError(path, f"not valid TOML ({e})") from None


class Table:
    """A TOML table that knows its file and section, so that errors can name both."""

    def __init__(self, data: dict, path: Path, section: str = ""):
        self.data, self.path, self.section = data, path, section

    def _name(self, key: str) -> str:
        return f"{self.section}.{key}" if self.section else key

    def sub(self, key: str) -> Table:
        value = self.data.get(key)
        if not isinstance(value, dict):
            raise InputError(self.path, "missing section" if value is None else "not a section",
                             field=self._name(key))
        return Table(value, self.path, self._name(key))

    def has(self, key: str) -> bool:
        return key in self.data

    def number(self, key: str, *, positive: bool = False, nonnegative: bool = False,
               default: float | None = None) -> float:
        if key not in self.data:
            if default is not None:
                return float(default)
            raise InputError(self.path, "missing field", field=self._name(key))
        v = self.data[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InputError(self.path, f"expected a finite number, got {v!r}",
                             field=self._name(key))
        if positive and v <= 0:
            raise InputError(self.path, f"must be > 0, got {v}", field=self._name(key))
        if nonnegative and v < 0:
            raise InputError(self.path, f"must be >= 0, got {v}", field=self._name(key))
        return float(v)

    def integer(self, key: str, default: int | None = None) -> int:
        v = self.data.get(key, default)
        if v is None:
            raise InputError(self.path, "missing field", field=self._name(key))
        if isinstance(v, bool) or not isinstance(v, int):
            raise InputError(self.path, f"expected an integer, got {v!r}", field=self._name(key))
        return v

    def text(self, key: str, default: str | None = None) -> str:
        v = self.data.get(key, default)
        if v is None:
            raise InputError(self.path, "missing field", field=self._name(key))
        if not isinstance(v, str):
            raise InputError(self.path, f"expected a string, got {v!r}", field=self._name(key))
        return v

    def point(self, key: str) -> tuple[float, float]:
        v = self.data.get(key)
        if (not isinstance(v, list) or len(v) != 2
                or not all(isinstance(a, (int, float)) and math.isfinite(a) for a in v)):
            raise InputError(self.path, f"expected [x, z] in metres, got {v!r}",
                             field=self._name(key))
        return float(v[0]), float(v[1])

    def names(self, key: str) -> tuple[str, ...]:
        v = self.data.get(key)
        if not isinstance(v, list) or not v or not all(isinstance(a, str) for a in v):
            raise InputError(self.path, f"expected a non-empty list of names, got {v!r}",
                             field=self._name(key))
        if len(set(v)) != len(v):
            raise InputError(self.path, "names are not unique", field=self._name(key))
        return tuple(v)


@dataclass(frozen=True)
class Flume:
    water_depth: float  # [m]
    width: float  # [m]
    length: float | None = None  # [m], descriptive: no computation reads it


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
        return math.pi * self.bore_diameter**2 / 4


@dataclass(frozen=True)
class Encoder:
    """Wire encoder of Eq. (1): L5 hinge-to-wire-anchor, L7 wire length at theta = 0."""

    L5: float  # [m]
    L7: float  # [m]
    counts_per_metre: float  # encoder counts per metre of wire shortening [m-1]
    sampling_rate: float  # [Hz]


@dataclass(frozen=True)
class Probes:
    names: tuple[str, ...]
    sampling_rate: float  # [Hz]
    separation: tuple[str, ...]  # probes used for incident/reflected separation


@dataclass(frozen=True)
class Beam:
    """One UVP transducer: face position and beam direction (angle above horizontal)."""

    name: str
    x: float  # transducer face x [m]
    dz: float  # transducer face elevation relative to the run's UVP elevation [m]
    angle: float  # beam angle above the horizontal, towards +x [rad]


@dataclass(frozen=True)
class UVP:
    frequency: float  # emitting frequency [Hz]
    sampling_rate: float  # profile rate per beam [Hz]
    n_channels: int
    start_channel: float  # distance of channel 0 [m]
    channel_distance: float  # [m]
    channel_width: float  # [m]
    sound_speed: float  # [m s-1]
    beams: tuple[Beam, ...]


@dataclass(frozen=True)
class Run:
    id: str
    path: Path
    kind: str  # "waves" or "uvp"
    period: float  # [s]
    height: float  # [m]
    repeat: int
    probe_x: dict[str, float]  # probe name -> x [m]
    uvp_elevation: float | None  # [m]


@dataclass(frozen=True)
class Campaign:
    name: str
    title: str
    root: Path
    flume: Flume
    flap: Flap
    pto: PTO
    encoder: Encoder
    probes: Probes
    uvp: UVP | None
    runs: tuple[Run, ...] = field(default_factory=tuple)

    @property
    def calibration_file(self) -> Path:
        return self.root / "calibration" / "probes.csv"

    def run(self, run_id: str) -> Run:
        for r in self.runs:
            if r.id == run_id:
                return r
        raise KeyError(f"campaign '{self.name}' has no run '{run_id}'")


def _read_run(path: Path, probes: Probes) -> Run:
    t = Table(read_toml(path), path)
    r = t.sub("run")
    kind = r.text("kind", "waves")
    if kind not in ("waves", "uvp"):
        raise InputError(path, f"kind must be 'waves' or 'uvp', got {kind!r}", field="run.kind")
    px = t.sub("probes")
    probe_x = {}
    for name in probes.names:
        probe_x[name] = px.number(name)
    unknown = set(px.data) - set(probes.names)
    if unknown:
        raise InputError(path, f"unknown probe(s) {sorted(unknown)}; the campaign declares "
                         f"{list(probes.names)}", field="probes")
    uvp_z = r.number("uvp_elevation") if kind == "uvp" else None
    return Run(id=path.parent.name, path=path.parent, kind=kind,
               period=r.number("period", positive=True), height=r.number("height", positive=True),
               repeat=r.integer("repeat", 0), probe_x=probe_x, uvp_elevation=uvp_z)


def load_campaign(root: str | Path) -> Campaign:
    """Read ``root/campaign.toml`` and every ``root/runs/*/run.toml``."""
    root = Path(root)
    path = root / "campaign.toml"
    t = Table(read_toml(path), path)
    c = t.sub("campaign")
    fl = t.sub("flume")
    flume = Flume(fl.number("water_depth", positive=True), fl.number("width", positive=True),
                  fl.number("length", positive=True) if fl.has("length") else None)
    f = t.sub("flap")
    flap = Flap(f.number("width", positive=True), f.number("thickness", positive=True),
                f.number("inertia", positive=True), f.number("hinge_height", nonnegative=True),
                f.number("buoyancy_stiffness"),
                height=f.number("height", positive=True) if f.has("height") else None,
                mass=f.number("mass", positive=True) if f.has("mass") else None,
                cog_height=f.number("cog_height") if f.has("cog_height") else None)
    if flap.width > flume.width:
        raise InputError(path, f"flap width {flap.width} m exceeds the flume width {flume.width} m",
                         field="flap.width")
    if flap.hinge_height >= flume.water_depth:
        raise InputError(path, "hinge above the still water level", field="flap.hinge_height")
    p = t.sub("pto")
    pto = PTO(p.point("bed_anchor"), p.point("flap_anchor"),
              p.number("bore_diameter", positive=True),
              p.number("atmospheric_pressure", positive=True, default=101325.0),
              p.number("vapour_pressure", positive=True, default=2339.0))
    if p.has("friction"):
        fr = p.sub("friction")
        fields = Friction.__dataclass_fields__
        pto = PTO(**{**pto.__dict__, "friction": Friction(
            **{k: fr.number(k, nonnegative=True) for k in fields})})
        if pto.friction.static_force < pto.friction.coulomb_force:
            raise InputError(path, "static friction force below the Coulomb force",
                             field="pto.friction.static_force")
    if math.dist(pto.bed_anchor, pto.flap_anchor) <= 0:
        raise InputError(path, "PTO anchors coincide", field="pto")
    e = t.sub("encoder")
    enc = Encoder(e.number("L5", positive=True), e.number("L7", positive=True),
                  e.number("counts_per_metre", positive=True),
                  e.number("sampling_rate", positive=True))
    pr = t.sub("probes")
    names = pr.names("names")
    sep = pr.names("separation") if pr.has("separation") else names
    if set(sep) - set(names):
        raise InputError(path, f"separation names unknown probes {sorted(set(sep) - set(names))}",
                         field="probes.separation")
    probes = Probes(names, pr.number("sampling_rate", positive=True), sep)
    uvp = None
    if t.has("uvp"):
        u = t.sub("uvp")
        beams = []
        for name in u.names("beams"):
            b = u.sub(name)
            beams.append(Beam(name, b.number("x"), b.number("dz"),
                              math.radians(b.number("angle_deg"))))
        uvp = UVP(u.number("frequency", positive=True), u.number("sampling_rate", positive=True),
                  u.integer("n_channels"), u.number("start_channel", nonnegative=True),
                  u.number("channel_distance", positive=True),
                  u.number("channel_width", positive=True),
                  u.number("sound_speed", positive=True), tuple(beams))
    runs_dir = root / "runs"
    run_files = sorted(runs_dir.glob("*/run.toml")) if runs_dir.is_dir() else []
    runs = tuple(_read_run(rp, probes) for rp in run_files)
    return Campaign(name=c.text("name"), title=c.text("title", c.text("name")), root=root,
                    flume=flume, flap=flap, pto=pto, encoder=enc, probes=probes, uvp=uvp, runs=runs)

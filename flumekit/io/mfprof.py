"""Met-Flow "UVP Monitor" profile files (``.mfprof``): reader, writer and xarray backend.

The layout follows ``shared/data/metflow/FORMAT.md`` (section numbers below refer to it):
a 104-byte little-endian header (§2), ``n_profiles`` fixed-size records (§3) read as one numpy
structured array, and an INI-style parameter block (§4). Velocities are the raw Doppler counts
times ΔV = V_range / RawDataRange with V_range = c² / (4 f0 d_max) (§5.1); channel distances
are (StartChannel + k ChannelDistance) mm (§6). Only records with ``status == 0`` are kept (§3.4).

Sign convention (§5.4): the file stores a signed Doppler shift whose physical direction is not
established. The reader does not change the numbers; it labels ``beam_velocity`` with an explicit
``positive`` attribute (default ``"away_from_transducer"``, the convention of Eqs. (4)-(6) in
Brito et al. 2020) and marks it unverified. :mod:`flumekit.uvp` honours that attribute.

Every check that fails raises :class:`flumekit.errors.InputError` naming the file and the check.
"""

from __future__ import annotations

import datetime as _dt
import os
import re
import warnings
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import xarray as xr
from xarray.backends import BackendEntrypoint

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.errors import InputError
from flumekit.io.atomic import atomic_path
from flumekit.io.dialects import iso_instant

HEADER_SIZE = 104
RECORD_HEADER_SIZE = 16
SIGNATURE = b"Met-Flow UVP Monitor"
ATTR_PREFIX = "mfprof_"
FILETIME_UNIX_EPOCH = 116_444_736_000_000_000  # 100-ns ticks from 1601-01-01 to 1970-01-01
POSITIVE_CHOICES = ("away_from_transducer", "towards_transducer")
SIGN_NOTE = ("assumed, not verified: the .mfprof format does not establish whether positive "
             "Doppler means motion towards or away from the transducer (FORMAT.md §5.4)")

_HEADER = np.dtype([("signature", "S64"), ("param_offset", "<i8"), ("n_profiles", "<u4"),
                    ("reserved1", "<u4"), ("flags", "<u4"), ("record_size", "<u4"),
                    ("n_channels", "<u4"), ("reserved2", "<u4"), ("start_time", "<i8")])
assert _HEADER.itemsize == HEADER_SIZE

_MUX_KEYS = ("NumberOfCycles", "CycleDelay", "Version", "Table")
_MULTILINE_KEYS = ("Comment", "MeasurementProtocol", "Table")

#: Parameter template in the order the UVP Monitor writes it (§4.2, §4.3); the writer fills
#: every key that the caller does not give from here. Geometry and acoustics have no default.
_UVP_TEMPLATE: dict[str, object] = {
    "Frequency": None, "StartChannel": None, "ChannelDistance": None, "ChannelWidth": None,
    "MaximumDepth": None, "SoundSpeed": None, "Angle": 90, "GainStart": 3, "GainEnd": 3,
    "Voltage": 150, "Iterations": 32, "NoiseLevel": 4, "CyclesPerPulse": 2, "TriggerMode": 0,
    "TriggerModeName": "None", "ProfileLength": None, "ProfilesPerBlock": None, "Blocks": 1,
    "AmplitudeStored": None, "DoNotStoreDoppler": 0, "RawDataMin": -128, "RawDataMax": 127,
    "RawDataRange": 256, "AmplDataMin": -8192, "AmplDataMax": 8191,
    "VelocityInterpretingMode": 0, "UserSampleTime": 1, "SampleTime": None,
    "UseMultiplexer": 0, "FlowMapping": 0, "FirstValidChannel": 0, "LastValidChannel": None,
    "FlowRateType": 0, "PeriodEnhOffset": 0, "PeriodEnhPeriod": 10,
    "PeriodEnhNCycles": 4294967295, "Comment": "", "MeasurementProtocol": "",
}
_MUX_TEMPLATE: dict[str, object] = {"NumberOfCycles": 1, "CycleDelay": 0, "Version": 2,
                                    "Table": "0"}


# --------------------------------------------------------------------------------------------
# parameter block (§4)
# --------------------------------------------------------------------------------------------

_INT_RE = re.compile(r"^[+-]?\d+$")
_FLOAT_RE = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


def _typed(text: str) -> int | float | str:
    """Integer (unbounded) or float when the text is a number, else the text itself."""
    s = text.strip()
    if _INT_RE.match(s):
        return int(s)
    if _FLOAT_RE.match(s):
        return float(s)
    return text


def parse_parameters(block: bytes, encoding: str = "cp1252") -> dict[str, dict[str, object]]:
    r"""Parse the INI-style parameter block into ``{section: {key: value}}`` (§4.1).

    A value ending with a backslash continues on the next line; the backslash stands for a line
    break inside the value. Numbers become ``int`` (unbounded) or ``float``; the free-text keys
    (``Comment``, ``MeasurementProtocol``) and the multiplexer ``Table`` stay text. Values are
    decoded one by one with ``encoding`` and ``errors="replace"``.

    Parameters
    ----------
    block : bytes
        The parameter block of a ``.mfprof`` file (from the header's ``param_offset`` on).
    encoding : str, optional
        Code page of the free-text values.

    Returns
    -------
    dict
        Section name -> {key -> int, float or str}; keys before any section under ``""``.

    Raises
    ------
    ValueError
        For a line that is neither a section, a ``key=value`` pair nor blank.

    References
    ----------
    .. [1] Met-Flow UVP Monitor file format, ``shared/data/metflow/FORMAT.md``, §4.1.

    Examples
    --------
    >>> parse_parameters(b"[UVP_PARAMETER]\nFrequency=4000000\nComment=two\\\nlines\n")
    {'UVP_PARAMETER': {'Frequency': 4000000, 'Comment': 'two\nlines'}}
    """
    sections: dict[str, dict[str, object]] = {}
    current: dict[str, object] = sections.setdefault("", {})
    lines = block.split(b"\n")
    if lines and lines[-1] == b"":
        lines = lines[:-1]
    i = 0
    while i < len(lines):  # a few dozen lines: a loop over parameters, not over data
        line = lines[i].rstrip(b"\r")
        i += 1
        if not line.strip():
            continue
        if line.startswith(b"[") and line.rstrip().endswith(b"]"):
            current = sections.setdefault(line.strip()[1:-1].decode("ascii", "replace"), {})
            continue
        if b"=" not in line:
            raise ValueError(f"parameter line {line[:60]!r} has no '='")
        key, value = line.split(b"=", 1)
        parts = [value]
        while parts[-1].endswith(b"\\") and i <= len(lines):
            parts[-1] = parts[-1][:-1]
            parts.append(lines[i].rstrip(b"\r") if i < len(lines) else b"")
            i += 1
        name = key.strip().decode("ascii", "replace")
        text = "\n".join(p.decode(encoding, "replace") for p in parts)
        if name == "Table":
            # the row count, then that many rows of 9 integers; accept rows that were written
            # without continuation backslashes too
            head = text.split("\n", 1)
            n_rows = int(head[0]) if _INT_RE.match(head[0].strip()) else 0
            rows = [r for r in (head[1].split("\n") if len(head) > 1 else []) if r.strip()]
            while len(rows) < n_rows and i < len(lines) and re.match(
                    rb"^\s*-?\d+(\s+-?\d+){8}\s*$", lines[i]):
                rows.append(lines[i].decode("ascii", "replace"))
                i += 1
            text = "\n".join([head[0].strip(), *rows]) if rows else head[0].strip()
        # free text stays text even when it looks like a number (a Comment "0" is not int 0)
        current[name] = text if name in _MULTILINE_KEYS else _typed(text)
    if not sections[""]:
        del sections[""]
    return sections


def _format_value(value: object) -> str:
    if isinstance(value, (bool, np.bool_)):
        return str(int(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if not np.isfinite(v):
            raise ValueError(f"parameter value {v} is not finite")
        return str(int(v)) if v.is_integer() and abs(v) < 2**53 else repr(v)
    return str(value)


def format_parameters(uvp: Mapping[str, object], mux: Mapping[str, object],
                      encoding: str = "cp1252") -> bytes:
    r"""Format the parameter block: ``[UVP_PARAMETER]`` then ``[MUX_PARAMETER]`` (§4.1).

    The inverse of :func:`parse_parameters`: a line break inside a value is written as a
    trailing backslash; integral floats are written as integers.

    Parameters
    ----------
    uvp : mapping
        The ``UVP_PARAMETER`` keys and values, in the order to write.
    mux : mapping
        The ``MUX_PARAMETER`` keys and values.
    encoding : str, optional
        Code page of the block (unencodable characters replaced).

    Returns
    -------
    bytes
        The block, ending with a line break.

    Raises
    ------
    ValueError
        For a value that is not finite.

    Examples
    --------
    >>> format_parameters({"Frequency": 4e6}, {"NumberOfCycles": 1})
    b'[UVP_PARAMETER]\nFrequency=4000000\n[MUX_PARAMETER]\nNumberOfCycles=1\n'
    """
    out = []
    for section, values in (("UVP_PARAMETER", uvp), ("MUX_PARAMETER", mux)):
        out.append(f"[{section}]")
        for key, value in values.items():
            out.append(f"{key}=" + "\\\n".join(_format_value(value).split("\n")))
    return ("\n".join(out) + "\n").encode(encoding, "replace")


# --------------------------------------------------------------------------------------------
# scale and geometry (§5, §6)
# --------------------------------------------------------------------------------------------

def velocity_range(sound_speed: float, frequency: float, maximum_depth: float) -> float:
    """Compute the full velocity range V_range = c² / (4 f0 d_max) of a pulsed Doppler profiler.

    Parameters
    ----------
    sound_speed : float
        Speed of sound c [m s-1].
    frequency : float
        Emitting frequency f0 [Hz].
    maximum_depth : float
        Maximum measurable depth d_max = c / (2 PRF) [m].

    Returns
    -------
    float
        V_range [m s-1]: the raw Doppler range maps onto it.

    References
    ----------
    .. [1] Met-Flow UVP Monitor file format, ``shared/data/metflow/FORMAT.md``, §5.1.

    Examples
    --------
    >>> velocity_range(1480.0, 4e6, 0.5)
    0.2738
    """
    return sound_speed**2 / (4.0 * frequency * maximum_depth)


def velocity_resolution(params: Mapping[str, object]) -> float:
    """Compute the velocity of one raw Doppler count, ΔV = V_range / RawDataRange.

    Parameters
    ----------
    params : mapping
        File parameters by their key names: ``SoundSpeed`` [m s-1], ``Frequency`` [Hz],
        ``MaximumDepth`` [mm] and ``RawDataRange`` [counts] (default: the writer's template
        value, 256).

    Returns
    -------
    float
        ΔV [m s-1 per count].

    References
    ----------
    .. [1] Met-Flow UVP Monitor file format, ``shared/data/metflow/FORMAT.md``, §5.1.

    Examples
    --------
    >>> velocity_resolution({"SoundSpeed": 1480.0, "Frequency": 4e6, "MaximumDepth": 500})
    0.00106953125
    """
    return velocity_range(float(params["SoundSpeed"]), float(params["Frequency"]),
                          float(params["MaximumDepth"]) * 1e-3) / float(
        params.get("RawDataRange", _UVP_TEMPLATE["RawDataRange"]))


def channel_distance(params: Mapping[str, object], n_channels: int) -> np.ndarray:
    """Compute each channel's distance from the transducer face.

    Parameters
    ----------
    params : mapping
        File parameters: ``StartChannel`` and ``ChannelDistance`` [mm].
    n_channels : int
        Number of channels.

    Returns
    -------
    numpy.ndarray
        (StartChannel + k ChannelDistance) for k = 0 .. n_channels - 1, in [m].

    References
    ----------
    .. [1] Met-Flow UVP Monitor file format, ``shared/data/metflow/FORMAT.md``, §6.

    Examples
    --------
    >>> channel_distance({"StartChannel": 10.0, "ChannelDistance": 0.74}, 3)
    array([0.01   , 0.01074, 0.01148])
    """
    k = np.arange(n_channels)
    return (float(params["StartChannel"]) + k * float(params["ChannelDistance"])) * 1e-3


def _record_dtype(n_channels: int, doppler: bool, amplitude: bool) -> np.dtype:
    fields = [("status", "<u4"), ("source", "<u4"), ("time", "<i8")]
    if doppler:
        fields.append(("doppler", "<i2", (n_channels,)))
    if amplitude:
        fields.append(("amplitude", "<i2", (n_channels,)))
    return np.dtype(fields)


def _filetime_to_datetime64(ticks: int) -> np.datetime64:
    return np.datetime64((ticks - FILETIME_UNIX_EPOCH) * 100, "ns")


def _filetime_to_iso(ticks: int) -> str:
    unix = ticks - FILETIME_UNIX_EPOCH
    seconds, rest = divmod(unix, 10_000_000)
    stamp = _dt.datetime(1970, 1, 1) + _dt.timedelta(seconds=seconds)
    return stamp.strftime("%Y-%m-%dT%H:%M:%S") + f".{rest:07d}"


# --------------------------------------------------------------------------------------------
# reader
# --------------------------------------------------------------------------------------------

def _mux_assignment(path: Path, mux: Mapping[str, object], n_profiles: int) -> np.ndarray:
    """Transducer number of every record by the MUX-table rule of FORMAT.md §7 (vectorised)."""
    table = str(mux.get("Table", "0")).split("\n")
    try:
        n_rows = int(table[0])
        rows = np.array([[int(v) for v in r.split()] for r in table[1:]], dtype=np.int64)
    except ValueError:
        raise InputError(path, "multiplexer table is not integer rows", field="Table") from None
    if n_rows == 0 or rows.shape != (n_rows, 9):
        raise InputError(path, f"multiplexer table: expected {n_rows} rows of 9 integers, got "
                         f"shape {rows.shape}", field="Table")
    active = rows[rows[:, 0] == 1]
    if active.size == 0 or np.any(active[:, 2] < 1):
        raise InputError(path, "multiplexer table has no active row with profiles",
                         field="Table")
    per_cycle = np.repeat(active[:, 1], active[:, 2])
    cycles = int(mux.get("NumberOfCycles", 1))
    if cycles * per_cycle.size != n_profiles:
        raise InputError(path, f"multiplexer table gives {cycles} cycles x {per_cycle.size} "
                         f"profiles = {cycles * per_cycle.size}, but the file holds "
                         f"{n_profiles} records", field="Table")
    return np.tile(per_cycle, cycles)


@doc
def read_mfprof(path: str | Path, *, positive: str = "away_from_transducer",
                transducer: int | None = None, angle_correction: bool = False,
                encoding: str = "cp1252") -> xr.Dataset:
    """Read a Met-Flow UVP Monitor ``.mfprof`` file.

    Parameters
    ----------
    path : str or pathlib.Path
        File to read.
    positive : {"away_from_transducer", "towards_transducer"}, optional
        Meaning of a positive along-beam velocity; the default is the convention of
        Eqs. (4)-(6) in Brito et al. (2020). It only labels the data (FORMAT.md §5.4: the
        file does not say); numbers are not changed.
    transducer : int, optional
        For multiplexed files (``UseMultiplexer=1``, FORMAT.md §7), the transducer (socket)
        number whose records to return. Required for such files; ignored otherwise.
    angle_correction : bool, optional
        Divide by sin(``Angle``) as other readers do (§5.3). Off by default:
        ``beam_velocity`` is the velocity along the beam.
    encoding : str, optional
        Code page of free-text parameters (``Comment``, ``MeasurementProtocol``).

    Returns
    -------
    xarray.Dataset
        Dims ``(time, channel)``: ``beam_velocity`` [m s-1], ``amplitude`` [counts] when
        stored; coordinates ``time`` [s] since the file's start time (only ``status == 0``
        records), ``channel``, ``distance`` [m] from the transducer face and ``record``
        (index of the record in the file). Every file parameter is an attribute
        ``mfprof_<Key>``; derived attributes: ``velocity_resolution`` [m s-1],
        ``velocity_range`` [m s-1], ``pulse_repetition_frequency`` [Hz], ``start_time`` (ISO,
        time zone unknown).

    Raises
    ------
    flumekit.errors.InputError
        Naming the file and the failed check (signature, header consistency, size,
        parameters, record contents, multiplexer table).
    ValueError
        For an unknown ``positive``.

    References
    ----------
    .. [1] Met-Flow UVP Monitor file format, ``shared/data/metflow/FORMAT.md``.
    .. [2] %(brito2020)s, Eqs. (4)-(6).

    Examples
    --------
    >>> import tempfile
    >>> params = dict(Frequency=4e6, SoundSpeed=1480.0, StartChannel=10.0,
    ...               ChannelDistance=0.74, ChannelWidth=0.74)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     f = write_mfprof(Path(folder) / "a.mfprof", {"time": np.arange(3) * 0.05,
    ...                      "beam_velocity": np.zeros((3, 4))}, params)
    ...     ds = read_mfprof(f)
    >>> ds["beam_velocity"].dims, ds["time"].values, ds["distance"].values
    (('time', 'channel'), array([0.  , 0.05, 0.1 ]), array([0.01   , 0.01074, 0.01148, 0.01222]))
    """
    path = Path(path)
    if positive not in POSITIVE_CHOICES:
        raise ValueError(f"positive must be one of {POSITIVE_CHOICES}, got {positive!r}")
    try:
        size = path.stat().st_size
    except FileNotFoundError:
        raise InputError(path, "file not found") from None
    if size < HEADER_SIZE:
        raise InputError(path, f"file of {size} bytes is shorter than the {HEADER_SIZE}-byte "
                         "header (truncated or not a .mfprof file)")
    with open(path, "rb") as f:
        head = _read_header(f, path, size)
        f.seek(int(head["param_offset"]))
        uvp, mux = _read_parameters(f.read(), path, encoding)
        n_profiles, n_channels = int(head["n_profiles"]), int(head["n_channels"])
        amp_stored = _check_layout(path, head, uvp)
        f.seek(HEADER_SIZE)
        rec = np.fromfile(f, dtype=_record_dtype(n_channels, True, amp_stored),
                          count=n_profiles)  # one structured-array read
    if rec.size != n_profiles:
        raise InputError(path, f"only {rec.size} of {n_profiles} records could be read")

    index = _valid_records(path, rec, uvp, mux, transducer)
    rec = rec[index]
    velocity = _velocity(path, rec["doppler"], uvp, angle_correction)

    attrs = _attributes(path, head, uvp, mux)
    if int(uvp.get("UseMultiplexer", 0)):
        attrs["transducer"] = int(transducer)
    bv_attrs = {"positive": positive, "sign_convention": SIGN_NOTE,
                "angle_correction": int(angle_correction)}
    data_vars = {"beam_velocity": (("time", "channel"), velocity, bv_attrs)}
    if amp_stored:
        data_vars["amplitude"] = (("time", "channel"), rec["amplitude"])
    ds = xr.Dataset(
        data_vars,
        coords={"time": ("time", rec["time"] / 1e7,
                         # the header's start, on the UVP Monitor PC's clock (zone unknown)
                         {conventions.RECORD_START: iso_instant(_filetime_to_datetime64(
                             int(head["start_time"])), utc=False)}),
                "channel": ("channel", np.arange(n_channels)),
                "distance": ("channel", channel_distance(uvp, n_channels)),
                "record": ("time", index)},
        attrs=attrs)
    return conventions.annotate(ds)


def _read_header(f, path: Path, size: int) -> np.void:
    """Read the 104-byte header (§2), checked for signature and consistency with the file size."""
    head = np.frombuffer(f.read(HEADER_SIZE), dtype=_HEADER)[0]
    sig = bytes(head["signature"])
    if not sig.startswith(SIGNATURE):
        raise InputError(path, "signature is not 'Met-Flow UVP Monitor' (not a .mfprof file)")
    version = sig[len(SIGNATURE):].strip(b"\n\x00").split(b"\n")[0]
    if version != b"4":
        warnings.warn(f"{path}: format version line {version!r}, only '4' is known",
                      stacklevel=3)
    param_offset = int(head["param_offset"])
    n_profiles, record_size = int(head["n_profiles"]), int(head["record_size"])
    if int(head["reserved1"]) or int(head["reserved2"]):
        warnings.warn(f"{path}: reserved header fields are not zero", stacklevel=3)
    if param_offset != HEADER_SIZE + n_profiles * record_size:
        raise InputError(path, f"header param_offset {param_offset} != 104 + n_profiles "
                         f"({n_profiles}) x record_size ({record_size}) = "
                         f"{HEADER_SIZE + n_profiles * record_size}", field="param_offset")
    if param_offset > size:
        raise InputError(path, f"file of {size} bytes is truncated: the records end at byte "
                         f"{param_offset}", field="param_offset")
    return head


def _read_parameters(block: bytes, path: Path, encoding: str
                     ) -> tuple[dict[str, object], dict[str, object]]:
    """Read the ``[UVP_PARAMETER]`` and ``[MUX_PARAMETER]`` sections of the parameter block (§4).

    The acoustic and channel parameters are checked positive.
    """
    if not block.strip():
        raise InputError(path, "parameter block is missing (file truncated after the records)")
    try:
        sections = parse_parameters(block, encoding)
    except ValueError as e:
        raise InputError(path, f"parameter block: {e}") from None
    uvp = sections.get("UVP_PARAMETER")
    if uvp is None:
        raise InputError(path, "parameter block has no [UVP_PARAMETER] section")
    for key in ("Frequency", "SoundSpeed", "MaximumDepth", "StartChannel",
                "ChannelDistance", "RawDataRange", "ProfileLength"):
        if not isinstance(uvp.get(key), (int, float)) or not uvp[key] > 0:
            raise InputError(path, f"parameter missing or not a positive number: "
                             f"{uvp.get(key)!r}", field=key)
    return uvp, sections.get("MUX_PARAMETER", {})


def _check_layout(path: Path, head: np.void, uvp: Mapping[str, object]) -> bool:
    """Check the header's record layout against the parameters (§3).

    Returns whether the records hold an amplitude block.
    """
    flags, record_size, n_channels = (int(head["flags"]), int(head["record_size"]),
                                      int(head["n_channels"]))
    if int(uvp["ProfileLength"]) != n_channels:
        raise InputError(path, f"ProfileLength {uvp['ProfileLength']} != header n_channels "
                         f"{n_channels}", field="ProfileLength")
    amp_stored = bool(flags & 1)
    if "AmplitudeStored" in uvp and int(uvp["AmplitudeStored"]) != int(amp_stored):
        raise InputError(path, f"AmplitudeStored={uvp['AmplitudeStored']} disagrees with "
                         f"header flags={flags}", field="AmplitudeStored")
    doppler_stored = not int(uvp.get("DoNotStoreDoppler", 0))
    expected = RECORD_HEADER_SIZE + 2 * n_channels * (int(doppler_stored) + int(amp_stored))
    if record_size != expected:
        raise InputError(path, f"record_size {record_size} != 16 + 2 x {n_channels} channels "
                         f"x {int(doppler_stored) + int(amp_stored)} blocks = {expected}",
                         field="record_size")
    if not doppler_stored:
        raise InputError(path, "file holds no Doppler block (DoNotStoreDoppler=1)")
    return amp_stored


def _valid_records(path: Path, rec: np.ndarray, uvp: Mapping[str, object],
                   mux: Mapping[str, object], transducer: int | None) -> np.ndarray:
    """Select the records to return, as indices.

    They are valid (status 0, §3.4), of ``transducer`` in a multiplexed file (§7), with
    strictly increasing times.
    """
    keep = rec["status"] == 0
    if int(uvp.get("UseMultiplexer", 0)):
        owner = _mux_assignment(path, mux, rec.size)
        sockets = np.unique(owner)
        if transducer is None:
            raise InputError(path, "multiplexed file (UseMultiplexer=1) holds transducers "
                             f"{sockets.tolist()}: pass transducer=<number> to read one "
                             "(assignment rule of FORMAT.md §7, unverified)")
        if transducer not in sockets:
            raise InputError(path, f"transducer {transducer} is not in the multiplexer table "
                             f"(transducers {sockets.tolist()})", field="Table")
        warnings.warn(f"{path}: multiplexed records assigned by the MUX-table rule of FORMAT.md "
                      "§7, which is unverified", stacklevel=3)
        keep &= owner == transducer
    index = np.flatnonzero(keep)
    if index.size == 0:
        raise InputError(path, f"none of the {rec.size} records is a valid profile (status 0)")
    ticks = rec["time"][index]
    if index.size > 1 and np.any(np.diff(ticks) <= 0):
        k = int(np.flatnonzero(np.diff(ticks) <= 0)[0])
        raise InputError(path, f"profile times are not strictly increasing at record "
                         f"{index[k + 1]} ({ticks[k]} then {ticks[k + 1]} ticks)", field="time")
    return index


def _velocity(path: Path, raw: np.ndarray, uvp: Mapping[str, object],
              angle_correction: bool) -> np.ndarray:
    """Convert raw Doppler counts to the along-beam velocity [m s-1].

    ΔV scale (§5.1), interpreting mode (§5.2), optional division by sin(Angle) (§5.3).
    """
    lo, hi = int(uvp.get("RawDataMin", -128)), int(uvp.get("RawDataMax", 127))
    rmin, rmax = int(raw.min()), int(raw.max())
    if rmin < lo or rmax > hi:
        raise InputError(path, f"raw Doppler values {rmin}..{rmax} leave the declared range "
                         f"RawDataMin..RawDataMax = {lo}..{hi} (corrupt records)", field="doppler")
    dv = velocity_resolution(uvp)
    vrange = dv * float(uvp["RawDataRange"])
    velocity = raw * dv  # float64 (time, channel), §5.1
    mode = int(uvp.get("VelocityInterpretingMode", 0))
    if mode in (1, -1):
        warnings.warn(f"{path}: VelocityInterpretingMode={mode} is implemented from one source "
                      "only (FORMAT.md §5.2) and unverified", stacklevel=3)
        if mode == 1:
            velocity = np.where(velocity < 0, velocity + vrange, velocity)
        else:
            velocity = np.where(velocity > 0, velocity - vrange, velocity)
    elif mode != 0:
        raise InputError(path, f"unknown VelocityInterpretingMode {mode}",
                         field="VelocityInterpretingMode")
    angle = float(uvp.get("Angle", 90))
    if angle_correction:
        if np.isclose(np.sin(np.radians(angle)), 0.0):
            raise InputError(path, f"Angle={angle} deg: cannot divide by sin(Angle)", field="Angle")
        velocity = velocity / np.sin(np.radians(angle))
    return velocity


def _attributes(path: Path, head: np.void, uvp: Mapping[str, object],
                mux: Mapping[str, object]) -> dict[str, object]:
    """Collect every file parameter as ``mfprof_<Key>`` and the derived attributes.

    Those of :func:`read_mfprof`'s dataset.
    """
    start_ticks = int(head["start_time"])
    dv = velocity_resolution(uvp)
    attrs: dict[str, object] = {f"{ATTR_PREFIX}{k}": v for k, v in uvp.items()}
    attrs.update({f"{ATTR_PREFIX}{k}": v for k, v in mux.items()})
    attrs.update({
        "source_file": str(path),
        "instrument": "Met-Flow UVP-DUO (UVP Monitor .mfprof)",
        "mfprof_start_time_filetime": start_ticks,
        "start_time": _filetime_to_iso(start_ticks),
        "start_time_zone": "unknown (UVP Monitor PC clock)",
        "velocity_resolution": dv,
        "velocity_range": dv * float(uvp["RawDataRange"]),
        "pulse_repetition_frequency": float(uvp["SoundSpeed"]) / (
            2 * float(uvp["MaximumDepth"]) * 1e-3),
        "mfprof_records_stored": int(head["n_profiles"]),
    })
    return attrs


# --------------------------------------------------------------------------------------------
# writer
# --------------------------------------------------------------------------------------------

def parameters_from_attrs(attrs: Mapping[str, object]) -> dict[str, object]:
    """Recover the file parameters from a dataset's ``mfprof_*`` attributes.

    Parameters
    ----------
    attrs : mapping
        Attributes as :func:`read_mfprof` stores them.

    Returns
    -------
    dict
        File parameters by their key names (FORMAT.md §4.2), without the attributes the
        reader derives from the header.

    Examples
    --------
    >>> parameters_from_attrs({"mfprof_Frequency": 4e6, "mfprof_records_stored": 3, "x": 1})
    {'Frequency': 4000000.0}
    """
    skip = {"mfprof_start_time_filetime", "mfprof_records_stored"}
    return {k[len(ATTR_PREFIX):]: v for k, v in attrs.items()
            if k.startswith(ATTR_PREFIX) and k not in skip}


def write_mfprof(path: str | Path, data: xr.Dataset | Mapping[str, np.ndarray],
                 params: Mapping[str, object] | None = None, *, start_time: int | None = None,
                 n_records: int | None = None, encoding: str = "cp1252") -> Path:
    """Write a ``.mfprof`` file atomically (temporary file in the same folder, then rename).

    Velocities are quantised to counts of ΔV (§5.1); a velocity beyond the raw range raises
    ``ValueError`` (alias it first if that is what the instrument would do). Times are rounded
    to 100 ns ticks.

    Parameters
    ----------
    path : str or pathlib.Path
        Output file.
    data : xarray.Dataset or mapping
        A dataset as returned by :func:`read_mfprof` (``time``, ``beam_velocity`` and
        optionally ``amplitude``), or a mapping with arrays ``time`` [s] (n,) and
        ``beam_velocity`` [m s-1] (n, n_channels), optionally ``amplitude`` [counts].
    params : mapping, optional
        File parameters by their file key names (``Frequency`` [Hz], ``SoundSpeed``
        [m s-1], ``MaximumDepth`` [mm], ``StartChannel`` [mm], ``ChannelDistance`` [mm],
        ``ChannelWidth`` [mm], ``SampleTime`` [ms], ..., and the MUX keys). Default: the
        ``mfprof_*`` attributes of ``data`` (:func:`parameters_from_attrs`); keys not given
        come from the UVP Monitor template.
    start_time : int, optional
        Absolute start as a Windows FILETIME [100 ns ticks since 1601]; default the
        dataset's ``mfprof_start_time_filetime`` attribute, else 2020-01-01T00:00:00.
    n_records : int, optional
        Records to allocate (≥ number of profiles); the extra records are written unfilled
        (status 3, zeros), as when a measurement is stopped early (FORMAT.md §3.4).
    encoding : str, optional
        Code page of the parameter block.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        For data of the wrong shape, non-finite or out-of-range velocities, times that do not
        increase, or missing geometry and acoustic parameters.

    References
    ----------
    .. [1] Met-Flow UVP Monitor file format, ``shared/data/metflow/FORMAT.md``.

    Examples
    --------
    See :func:`read_mfprof`.
    """
    path = Path(path)
    attrs = dict(data.attrs) if isinstance(data, xr.Dataset) else {}
    given = dict(parameters_from_attrs(attrs) if params is None else params)
    if start_time is None:
        start_time = int(attrs.get("mfprof_start_time_filetime",
                                   FILETIME_UNIX_EPOCH + 1_577_836_800 * 10_000_000))
    time = np.asarray(data["time"], dtype=float)
    vel = np.asarray(data["beam_velocity"], dtype=float)
    amp = data["amplitude"] if "amplitude" in data else None
    if vel.ndim != 2 or time.shape != (vel.shape[0],):
        raise ValueError(f"beam_velocity must be (time, channel) with time (n,), got "
                         f"{vel.shape} and {time.shape}")
    n, n_channels = vel.shape
    if n == 0 or n_channels == 0:
        raise ValueError("nothing to write: no profile or no channel")
    if not np.all(np.isfinite(vel)):
        raise ValueError("beam_velocity holds NaN or inf; the format has no missing value")
    if isinstance(data, xr.Dataset) and (
            data["beam_velocity"].attrs.get("angle_correction", 0)):
        raise ValueError("data were read with angle_correction; write along-beam velocities")
    ticks = np.rint(time * 1e7).astype(np.int64)
    if np.any(np.diff(ticks) <= 0) or ticks[0] < 0:
        raise ValueError("times must be >= 0 and strictly increasing (at 100 ns resolution)")
    total = n if n_records is None else int(n_records)
    if total < n:
        raise ValueError(f"n_records={total} is less than the {n} profiles to write")
    uvp, mux = _complete_parameters(given, time, n_channels, total, amp is not None)
    rec = _records(uvp, ticks, vel, amp, total)
    header = np.zeros(1, dtype=_HEADER)
    header["signature"] = SIGNATURE + b"\n4\n"
    header["param_offset"] = HEADER_SIZE + total * rec.dtype.itemsize
    header["n_profiles"] = total
    header["flags"] = int(amp is not None)
    header["record_size"] = rec.dtype.itemsize
    header["n_channels"] = n_channels
    header["start_time"] = start_time
    block = format_parameters(uvp, mux, encoding)
    with atomic_path(path) as tmp, open(tmp, "wb") as f:
        f.write(header.tobytes())
        f.write(rec.tobytes())
        f.write(block)
    return path


def _complete_parameters(given: Mapping[str, object], time: np.ndarray, n_channels: int,
                         total: int, amp_stored: bool
                         ) -> tuple[dict[str, object], dict[str, object]]:
    """Complete the UVP and MUX sections to write.

    The template (§4.2, §4.3) overlaid with ``given``, the layout keys set from the data, and
    the smallest ``MaximumDepth`` covering every channel when none is given.
    """
    uvp = {k: given.get(k, v) for k, v in _UVP_TEMPLATE.items()}
    uvp.update({k: v for k, v in given.items() if k not in _MUX_KEYS})
    mux = {k: given.get(k, v) for k, v in _MUX_TEMPLATE.items()}
    missing = [k for k in ("Frequency", "StartChannel", "ChannelDistance", "ChannelWidth",
                           "SoundSpeed") if uvp.get(k) is None]
    if missing:
        raise ValueError(f"write_mfprof needs the parameters {missing}")
    dt_ms = float(np.median(np.diff(time))) * 1e3 if time.size > 1 else 0.0
    uvp["ProfileLength"] = n_channels
    uvp["AmplitudeStored"] = int(amp_stored)
    uvp["DoNotStoreDoppler"] = 0
    for key, value in (("ProfilesPerBlock", total), ("SampleTime", int(round(dt_ms))),
                       ("LastValidChannel", n_channels - 1)):
        if uvp.get(key) is None:
            uvp[key] = value
    if uvp.get("MaximumDepth") is None:  # the smallest d_max that covers every channel [mm]
        last = float(uvp["StartChannel"]) + (n_channels - 1) * float(uvp["ChannelDistance"])
        uvp["MaximumDepth"] = float(np.ceil((last + float(uvp["ChannelWidth"])) * 100) / 100)
    return uvp, mux


def _records(uvp: Mapping[str, object], ticks: np.ndarray, vel: np.ndarray, amp,
             total: int) -> np.ndarray:
    """Build the ``total`` records (§3): the profiles as counts of ΔV, then unfilled ones."""
    n, n_channels = vel.shape
    dv = velocity_resolution(uvp)
    counts = np.rint(vel / dv)
    lo, hi = int(uvp["RawDataMin"]), int(uvp["RawDataMax"])
    if counts.min() < lo or counts.max() > hi:
        raise ValueError(f"velocities {vel.min():.4g}..{vel.max():.4g} m/s exceed the raw range "
                         f"{lo}..{hi} counts of {dv:.4g} m/s (Nyquist limit)")
    rec = np.zeros(total, dtype=_record_dtype(n_channels, True, amp is not None))
    rec["status"][n:] = 3
    rec["source"][:n] = 20  # the value every real file holds (FORMAT.md §3)
    rec["time"][:n] = ticks
    rec["doppler"][:n] = counts.astype(np.int16)
    if amp is not None:
        a = np.asarray(amp)
        if a.shape != vel.shape:
            raise ValueError(f"amplitude shape {a.shape} != beam_velocity shape {vel.shape}")
        if not np.all(np.isfinite(a)) or np.any(a != np.rint(a)):
            raise ValueError("amplitude must hold whole (raw) counts")
        rec["amplitude"][:n] = a.astype(np.int16)
    return rec


# --------------------------------------------------------------------------------------------
# xarray backend
# --------------------------------------------------------------------------------------------

class MfprofBackendEntrypoint(BackendEntrypoint):
    """``xr.open_dataset(path, engine="mfprof")``: see :func:`read_mfprof`."""

    description = "Met-Flow UVP Monitor profile files (.mfprof), flumekit reader"
    url = "https://github.com/flumekit"  # documentation lives in flumekit.io.mfprof
    open_dataset_parameters = ("filename_or_obj", "drop_variables", "positive", "transducer",
                               "angle_correction", "encoding")

    def open_dataset(self, filename_or_obj, *, drop_variables=None,
                     positive: str = "away_from_transducer", transducer: int | None = None,
                     angle_correction: bool = False, encoding: str = "cp1252") -> xr.Dataset:
        """Open a ``.mfprof`` file as :func:`read_mfprof` does, without ``drop_variables``."""
        ds = read_mfprof(filename_or_obj, positive=positive, transducer=transducer,
                         angle_correction=angle_correction, encoding=encoding)
        if drop_variables:
            ds = ds.drop_vars(drop_variables, errors="ignore")
        return ds

    def guess_can_open(self, filename_or_obj) -> bool:
        """Tell whether a path is a ``.mfprof`` file: by its suffix, else its signature."""
        try:
            p = Path(os.fspath(filename_or_obj))
        except TypeError:
            return False
        if p.suffix.lower() == ".mfprof":
            return True
        try:
            with open(p, "rb") as f:
                return f.read(len(SIGNATURE)) == SIGNATURE
        except OSError:
            return False

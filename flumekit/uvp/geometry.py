"""UVP beam geometry: channel positions in the flume and the flap's position.

Coordinates (raw/README.md): x = 0 at the flap hinge, positive towards the beach; z = 0 at the
hinge axis (0.10 m above the bed). A beam leaves its transducer face at (x_b, z_b) with the
angle a_b above the horizontal (towards +x): UP2 horizontal, UP1 at -π/6, UP3 at +π/6
(Brito et al. 2020, §2.3 and Fig. 2). Along-beam velocities are positive away from the
transducer, so that a beam measures v_b = u cos a_b + w sin a_b (Eqs. (4)-(6) in Brito et al.
2020, with UP1 at a = -α).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.campaign import UVP


def channel_positions(distance, beam_x: float, beam_z: float, angle: float
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Positions of the channels of one beam.

    Parameters
    ----------
    distance : array_like
        Distance of each channel from the transducer face along the beam [m].
    beam_x : float
        X of the transducer face [m].
    beam_z : float
        Z of the transducer face [m].
    angle : float
        Beam angle above the horizontal, towards +x [rad].

    Returns
    -------
    x, z : Channel positions [m], ``distance`` broadcast with the other arguments.

    Examples
    --------
    The upward beam UP3 (+30°) of a UVP mounted 0.30 m above the hinge: since sin 30° = 1/2, the
    channels 0.2 and 0.4 m along the beam lie 0.1 and 0.2 m above the face, and r cos 30°
    towards the flap.

    >>> import numpy as np
    >>> from flumekit.uvp import channel_positions
    >>> x, z = channel_positions([0.2, 0.4], beam_x=-0.37, beam_z=0.30, angle=np.pi / 6)
    >>> x.round(4).tolist(), z.round(4).tolist()  # -0.37 + r √3/2, 0.30 + r/2
    ([-0.1968, -0.0236], [0.4, 0.5])
    """
    r = np.asarray(distance, dtype=float)
    return beam_x + r * np.cos(angle), beam_z + r * np.sin(angle)


def channel_distances(uvp: UVP) -> np.ndarray:
    """Distance of each channel from the transducer face [m] (campaign UVP settings).

    Parameters
    ----------
    uvp : UVP
        Campaign UVP settings: ``start_channel``, ``channel_distance`` [m] and
        ``n_channels``.

    Returns
    -------
    numpy.ndarray
        Distances [m], shape (n_channels,): start_channel + k channel_distance.

    Examples
    --------
    The UVP-DUO of Brito et al. (2020): 360 channels 0.74 mm apart from 2 cm off the face.

    >>> from flumekit.campaign import UVP, Beam
    >>> from flumekit.uvp import channel_distances
    >>> up2 = Beam("UP2", x=-0.37, dz=0.0, angle=0.0)  # one horizontal transducer
    >>> uvp = UVP(frequency=2e6, sampling_rate=11.6, n_channels=360, start_channel=0.02,
    ...           channel_distance=0.00074, channel_width=0.00074, sound_speed=1480.0,
    ...           beams=(up2,))
    >>> r = channel_distances(uvp)
    >>> r.size, round(float(r[0]), 5), round(float(r[-1]), 5)  # last: 0.02 + 359 x 0.74 mm
    (360, 0.02, 0.28566)
    """
    return uvp.start_channel + np.arange(uvp.n_channels) * uvp.channel_distance


def beam_geometry(uvp: UVP, uvp_elevation: float, distance=None) -> xr.Dataset:
    """Channel positions of every beam of a run.

    Parameters
    ----------
    uvp : UVP
        Campaign UVP settings (beams with face x, dz and angle).
    uvp_elevation : float
        Elevation of the run's UVP mounting (UP2 face) above the hinge [m].
    distance : array_like
        Channel distances [m]; default from the campaign settings.

    Returns
    -------
    xarray.Dataset
        Dataset with dims ``(beam, channel)``: ``x`` and ``z`` [m]; coordinates ``beam``,
        ``channel``, ``distance`` [m] and ``beam_angle`` [rad].

    Examples
    --------
    The three beams of Brito et al. (2020) at -30°, 0 and +30° from one mounting 0.30 m above
    the hinge, at two channel distances: the inclined beams fan out by ±r sin 30° = ±r/2.

    >>> import numpy as np
    >>> from flumekit.campaign import UVP, Beam
    >>> from flumekit.uvp import beam_geometry
    >>> beams = tuple(Beam(name, -0.37, 0.0, np.radians(deg))
    ...               for name, deg in (("UP1", -30), ("UP2", 0), ("UP3", 30)))
    >>> uvp = UVP(2e6, 11.6, 360, 0.02, 0.00074, 0.00074, 1480.0, beams)
    >>> g = beam_geometry(uvp, 0.30, distance=[0.1, 0.2])
    >>> dict(g.sizes)
    {'beam': 3, 'channel': 2}
    >>> g.z.round(3).values.tolist()  # 0.30 - r/2, 0.30, 0.30 + r/2
    [[0.25, 0.2], [0.3, 0.3], [0.35, 0.4]]
    """
    r = channel_distances(uvp) if distance is None else np.asarray(distance, dtype=float)
    names = [b.name for b in uvp.beams]
    angle = np.array([b.angle for b in uvp.beams])
    bx = np.array([b.x for b in uvp.beams])
    bz = uvp_elevation + np.array([b.dz for b in uvp.beams])
    x, z = channel_positions(r[None, :], bx[:, None], bz[:, None], angle[:, None])
    ds = xr.Dataset(
        {"x": (("beam", "channel"), x), "z": (("beam", "channel"), z)},
        coords={"beam": names, "channel": np.arange(r.size), "distance": ("channel", r),
                "beam_angle": ("beam", angle)})
    return conventions.annotate(ds)


def flap_face_x(z, theta, thickness: float) -> np.ndarray:
    """X of the flap's seaward (wavemaker-side) face at elevation z [m].

    The face is the line x' = -thickness/2 of the flap frame rotated by θ about the hinge
    (θ > 0 when the top moves towards the beach): x = z tan θ - thickness / (2 cos θ).

    Parameters
    ----------
    z : array_like
        Elevation above the hinge [m].
    theta : array_like
        Flap angle [rad], broadcastable with ``z``.
    thickness : float
        Flap thickness [m] (0.17 m in Brito et al. 2020, §2.2).

    Returns
    -------
    numpy.ndarray
        X of the face [m], ``z`` and ``theta`` broadcast.

    Raises
    ------
    ValueError
        A flap angle outside (-π/2, π/2).

    Examples
    --------
    Upright, the face of a 0.17 m thick flap is at x = -0.085 m at every height; tilted by
    0.1 rad towards the beach, it moves by z tan θ (and the half thickness grows by 1/cos θ).

    >>> from flumekit.uvp import flap_face_x
    >>> flap_face_x([0.0, 0.5], 0.0, 0.17).tolist()
    [-0.085, -0.085]
    >>> flap_face_x([0.0, 0.5], 0.1, 0.17).round(4).tolist()  # 0.5 tan 0.1 - 0.085 / cos 0.1
    [-0.0854, -0.0353]
    """
    theta = np.asarray(theta, dtype=float)
    if np.any(np.abs(theta) >= np.pi / 2):
        raise ValueError("flap angle must lie within (-pi/2, pi/2)")
    return np.asarray(z, dtype=float) * np.tan(theta) - thickness / (2.0 * np.cos(theta))


def inside_flap(x, z, theta, thickness: float, margin: float = 0.0) -> np.ndarray:
    """Mask of (x, z) within ``margin`` of the flap's seaward face or behind it [bool].

    The region behind the face is masked up to any height (conservative: the beams of the flume
    set-up do not reach over the flap top).

    Parameters
    ----------
    x, z : array_like
        Point coordinates [m], broadcastable.
    theta : array_like
        Flap angle [rad], broadcastable with ``x`` and ``z``.
    thickness : float
        Flap thickness [m].
    margin : float
        Distance in x in front of the face that is masked too [m].

    Returns
    -------
    numpy.ndarray
        True where the point is masked.

    Examples
    --------
    With the upright 0.17 m flap (face at x = -0.085 m) and a 1 cm margin, a point at
    x = -0.09 m is masked with the points behind the face; one at -0.2 m is not.

    >>> from flumekit.uvp import inside_flap
    >>> inside_flap([-0.2, -0.09, -0.05], 0.3, 0.0, 0.17, margin=0.01).tolist()
    [False, True, True]
    """
    return np.asarray(x, dtype=float) > flap_face_x(z, theta, thickness) - margin

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
    x, z : Channel positions [m], shaped like ``distance``.
    """
    r = np.asarray(distance, dtype=float)
    return beam_x + r * np.cos(angle), beam_z + r * np.sin(angle)


def channel_distances(uvp: UVP) -> np.ndarray:
    """Distance of each channel from the transducer face [m] (campaign UVP settings)."""
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
    """
    theta = np.asarray(theta, dtype=float)
    if np.any(np.abs(theta) >= np.pi / 2):
        raise ValueError("flap angle must lie within (-pi/2, pi/2)")
    return np.asarray(z, dtype=float) * np.tan(theta) - thickness / (2.0 * np.cos(theta))


def inside_flap(x, z, theta, thickness: float, margin: float = 0.0) -> np.ndarray:
    """Mask of (x, z) within ``margin`` of the flap's seaward face or behind it [bool].

    The region behind the face is masked up to any height (conservative: the beams of the flume
    set-up do not reach over the flap top).
    """
    return np.asarray(x, dtype=float) > flap_face_x(z, theta, thickness) - margin

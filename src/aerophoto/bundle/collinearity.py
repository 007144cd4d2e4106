"""The collinearity equations (уравнения коллинеарности), vectorised over a whole block, with their derivatives.

The camera model is :mod:`aerophoto.geometry`'s: a ground vector is ``R @ (x, y, −f)``
for a photo point (x, y) in mm, and a ground point P is imaged at

    x = −f · c₁/c₃,   y = −f · c₂/c₃,   c = Rᵀ (P − S)                      (1)

with S the projection centre.  :func:`aerophoto.geometry.ground_to_photo` does this
for one :class:`~aerophoto.geometry.Pose` (α, λ, κ); the adjustment needs it for
thousands of (photo, point) pairs at once and needs its derivatives, and a
parametrisation of the rotation with no singularity at α = 0 (where λ is
undefined).  So the exterior orientation of a photo (элементы внешнего
ориентирования) is held here as six numbers

    (X_S, Y_S, Z_S in m;  ω, φ, κ in radians),   R = R_x(ω) · R_y(φ) · R_z(κ)

— ω the tilt across the flight (поперечный угол наклона), φ the tilt along it
(продольный угол наклона), κ the swing/heading (угол поворота).  For a vertical photo
R = R_z(κ) and κ is :attr:`aerophoto.geometry.Pose.kappa_deg` in radians.
:func:`eo_from_pose` converts a Pose through :func:`aerophoto.geometry.rotation_matrix`
(so the two models are one; ``tests/physics/test_bundle.py`` checks (1) against
``ground_to_photo``).
"""

from __future__ import annotations

import math

import numpy as np

from .. import _validate as V
from ..geometry import Pose, rotation_matrix

__all__ = ["rotation_opk", "opk_from_matrix", "eo_from_pose", "eo_from_poses", "project", "project_jacobian"]


def _rx(a):
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)


def _ry(a):
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def _drx(a):
    c, s = np.cos(a), np.sin(a)
    z = np.zeros_like(a)
    return np.stack([np.stack([z, z, z], -1), np.stack([z, -s, -c], -1), np.stack([z, c, -s], -1)], -2)


def _dry(a):
    c, s = np.cos(a), np.sin(a)
    z = np.zeros_like(a)
    return np.stack([np.stack([-s, z, c], -1), np.stack([z, z, z], -1), np.stack([-c, z, -s], -1)], -2)


def _drz(a):
    c, s = np.cos(a), np.sin(a)
    z = np.zeros_like(a)
    return np.stack([np.stack([-s, -c, z], -1), np.stack([c, -s, z], -1), np.stack([z, z, z], -1)], -2)


@V.checked(omega=V.values(), phi=V.values(), kappa=V.values())
def rotation_opk(omega, phi, kappa) -> np.ndarray:
    """R = R_x(ω)·R_y(φ)·R_z(κ), shape (..., 3, 3), camera → ground; angles in radians (broadcast)."""
    V.check_broadcast(omega=omega, phi=phi, kappa=kappa)
    return _rotation_opk(omega, phi, kappa)


def _rotation_opk(omega, phi, kappa) -> np.ndarray:
    """:func:`rotation_opk` without the entry checks (the adjustment's inner loops)."""
    o, p, k = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (omega, phi, kappa)))
    return _rx(o) @ _ry(p) @ _rz(k)


def _check_R(name, R):
    R = V.check_finite_array(name, R)
    if R.ndim < 2 or R.shape[-2:] != (3, 3):
        raise ValueError(f"{name} has shape {R.shape}; expected rotation matrices (..., 3, 3)")


@V.checked(R=V.Spec(_check_R))
def opk_from_matrix(R) -> np.ndarray:
    """The angles (ω, φ, κ) in radians, shape (..., 3), of rotation matrices R (..., 3, 3); |φ| < 90°."""
    R = np.asarray(R, dtype=float)
    phi = np.arcsin(np.clip(R[..., 0, 2], -1.0, 1.0))
    omega = np.arctan2(-R[..., 1, 2], R[..., 2, 2])
    kappa = np.arctan2(-R[..., 0, 1], R[..., 0, 0])
    return np.stack([omega, phi, kappa], axis=-1)


@V.checked(pose=Pose)
def eo_from_pose(pose: Pose) -> np.ndarray:
    """The six exterior-orientation numbers (X, Y, Z m; ω, φ, κ rad), shape (6,), of a geometry Pose."""
    return np.concatenate([pose.centre, opk_from_matrix(rotation_matrix(pose))])


@V.checked(poses=V.sequence(V.of_type(Pose), min_len=1))
def eo_from_poses(poses) -> np.ndarray:
    """:func:`eo_from_pose` for a sequence of Poses, shape (n, 6)."""
    return np.array([eo_from_pose(p) for p in poses], dtype=float).reshape(-1, 6)


def _check_rows(eo, XYZ_m):
    if np.shape(eo)[0] != np.shape(XYZ_m)[0]:
        raise ValueError(f"eo has {np.shape(eo)[0]} rows and XYZ_m {np.shape(XYZ_m)[0]}; one photo row per point")


@V.checked(eo=V.array(ndim=2, last=6), XYZ_m=V.array(ndim=2, last=3), f_mm=V.number(0.0, 2000.0, lo_open=True))
def project(eo, XYZ_m, f_mm: float) -> np.ndarray:
    """Collinearity (1): photo coordinates (N, 2) in mm of ground points ``XYZ_m`` (N, 3) on photos ``eo`` (N, 6).

    Row i of ``eo`` is the photo that sees row i of ``XYZ_m`` (gather them with the
    observation indices first).  No check that the point is in front of the camera.
    """
    _check_rows(eo, XYZ_m)
    return _project(eo, XYZ_m, f_mm)


def _project(eo, XYZ_m, f_mm: float) -> np.ndarray:
    eo = np.asarray(eo, dtype=float)
    R = _rotation_opk(eo[:, 3], eo[:, 4], eo[:, 5])
    c = np.einsum("nji,nj->ni", R, np.asarray(XYZ_m, dtype=float) - eo[:, :3])
    return -f_mm * c[:, :2] / c[:, 2:3]


@V.checked(eo=V.array(ndim=2, last=6), XYZ_m=V.array(ndim=2, last=3), f_mm=V.number(0.0, 2000.0, lo_open=True))
def project_jacobian(eo, XYZ_m, f_mm: float):
    """Photo coordinates and their derivatives.

    Returns
    -------
    xy : (N, 2) mm
    d_eo : (N, 2, 6) ∂(x, y)/∂(X_S, Y_S, Z_S, ω, φ, κ), mm per m and mm per radian
    d_pt : (N, 2, 3) ∂(x, y)/∂(X, Y, Z) of the ground point, mm per m
    """
    _check_rows(eo, XYZ_m)
    return _project_jacobian(eo, XYZ_m, f_mm)


def _project_jacobian(eo, XYZ_m, f_mm: float):
    eo = np.asarray(eo, dtype=float)
    o, p, k = eo[:, 3], eo[:, 4], eo[:, 5]
    Rx, Ry, Rz = _rx(o), _ry(p), _rz(k)
    R = Rx @ Ry @ Rz
    d = np.asarray(XYZ_m, dtype=float) - eo[:, :3]
    c = np.einsum("nji,nj->ni", R, d)
    inv = 1.0 / c[:, 2]
    xy = -f_mm * c[:, :2] * inv[:, None]
    # ∂(x, y)/∂c: rows (x, y), columns c1, c2, c3
    dxy_dc = np.zeros((len(eo), 2, 3))
    dxy_dc[:, 0, 0] = -f_mm * inv
    dxy_dc[:, 1, 1] = -f_mm * inv
    dxy_dc[:, 0, 2] = f_mm * c[:, 0] * inv**2
    dxy_dc[:, 1, 2] = f_mm * c[:, 1] * inv**2
    Rt = np.swapaxes(R, 1, 2)
    d_pt = dxy_dc @ Rt  # ∂c/∂P = Rᵀ
    d_eo = np.empty((len(eo), 2, 6))
    d_eo[:, :, :3] = -d_pt
    for j, dR in enumerate((_drx(o) @ Ry @ Rz, Rx @ _dry(p) @ Rz, Rx @ Ry @ _drz(k))):
        dc = np.einsum("nji,nj->ni", dR, d)
        d_eo[:, :, 3 + j] = np.einsum("nab,nb->na", dxy_dc, dc)
    return xy, d_eo, d_pt


def _deg(x):  # small helper for messages
    return math.degrees(float(x))

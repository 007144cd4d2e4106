"""Stereo pairs (guide §8): the base, x-parallax, heights from parallaxes, the stereo model, anaglyphs, matching.

Two neighbouring photos of a strip that overlap (here by p_x ≈ 60 %) are a
**stereo pair** (стереопара); looked at so that each eye sees one of them, they
fuse into a three-dimensional **stereo model** (стереомодель) — the **direct
stereo effect** (прямой стереоэффект).  Swapped (left photo to the right eye),
hills look like hollows: the **reverse stereo effect** (обратный стереоэффект).

Conventions and symbols
-----------------------
* The *left* photo is the earlier one (photo 1), the *right* one the next
  along the strip; their x axes point along the flight.
* **Photo base** b (базис фотографирования на снимке), mm: the distance on a
  photo from its principal point to the image of the neighbour's principal
  point (b₁ on the left photo, b₂ on the right; the guide's b_x = l(100 − p_x)/100
  of §2 is its planned value).  **Air base** B (базис фотографирования), m: the
  distance between the two projection centres S₁S₂.  Over ground at the flying
  height H: b = B·f/H = B/m.
* **x-parallax** (продольный параллакс) p = x_left − x_right, mm: positive for
  every point, larger for higher points; **y-parallax** (поперечный параллакс)
  q = y_left − y_right, zero for every point of a correctly oriented pair.
* **Normalised (epipolar) photos**: both projection centres keep their places;
  both photos are turned to one orientation R_n whose x axis runs along the air
  base S₁S₂ and whose z axis is as near the vertical as that allows.  On them
  the rows are epipolar lines (q = 0 for every point) and the parallax
  equations hold exactly, with Z measured along the (almost vertical) z axis:

      X = B·x/p,   Y = B·y/p,   Z = −B·f/p   (metres, from S₁, x, y, p, f in mm)

  so a point's height above a datum H below S₁ is h = H − B·f/p; and the
  height difference of two points whose parallaxes differ by Δp is

      Δh = H·Δp/(p + Δp) ≈ H·Δp/b   (H over the lower point, p its parallax ≈ b).

Units: mm on the photos, m on the ground.  Bad input (p ≤ 0, b + Δp ≤ 0, a
point at or above the camera, H ≤ 0, …) raises ValueError naming the value.
Anaglyphs are red–cyan: the red channel carries the left photo (red filter over
the LEFT eye), green and blue the right one.  Parallax matching is normalised
cross-correlation along the rows of normalised photos (scikit-image's
:func:`skimage.feature.match_template` for single points — in the browser
book the same algorithm with numpy and scipy — and box filters for dense
maps).  Physics only (layer 2): images are plain arrays.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _validate as V
from . import geometry as g
from ._validate import check_finite_array, check_int_range, check_positive, check_range

__all__ = [
    "EYE_BASE_MM", "VIEWING_DISTANCE_MM", "STEREOSCOPE_BASE_MM", "StereoPair", "photo_base_mm", "air_base_m",
    "base_height_ratio", "x_parallax_mm", "y_parallax_mm", "parallax_mm", "model_point", "height_difference_m",
    "parallax_difference_mm", "flying_height_from_point", "air_base_from_point", "vertical_exaggeration",
    "normal_rotation", "to_normal", "from_normal", "NormalImage", "normalise_image", "anaglyph", "side_by_side",
    "match_points", "dense_parallax", "DenseParallax",
]

#: the mean eye base (средний глазной базис), mm — the spacing of conjugate points for free viewing
EYE_BASE_MM = 65.0
#: the distance of comfortable near vision, mm (a stereoscope's lenses put the photos about there)
VIEWING_DISTANCE_MM = 250.0
#: spacing of conjugate points under a lens-mirror stereoscope (линзово-зеркальный стереоскоп), mm — a typical
#: instrument's mirror base; set it to yours (the distance between the outer mirrors' centres)
STEREOSCOPE_BASE_MM = 250.0


# =========================================================================== the pair's geometry
def photo_base_mm(B_m, H_m, f_mm):
    """Photo base b = B·f/H, mm (B air base and H flying height in m, f in mm)."""
    B = _positive_array("B_m", B_m, "m")
    H = _positive_array("H_m", H_m, "m")
    f = check_positive("f_mm", f_mm, unit="mm")
    return _out(B * f / H)


def air_base_m(b_mm, m):
    """Air base B = b·m, metres, from the photo base b (mm) and the scale denominator m."""
    b = _positive_array("b_mm", b_mm, "mm")
    mm = check_positive("m", m)
    return _out(b * mm / 1000.0)


def base_height_ratio(B_m, H_m):
    """The base-to-height ratio B/H (= b/f for a vertical pair)."""
    return _out(_positive_array("B_m", B_m, "m") / _positive_array("H_m", H_m, "m"))


def x_parallax_mm(x_left_mm, x_right_mm):
    """x-parallax p = x_left − x_right, mm (array_like, broadcast)."""
    return _out(_diff("x_left_mm", x_left_mm, "x_right_mm", x_right_mm))


def y_parallax_mm(y_left_mm, y_right_mm):
    """y-parallax q = y_left − y_right, mm: zero for every point of a correctly oriented (normalised) pair."""
    return _out(_diff("y_left_mm", y_left_mm, "y_right_mm", y_right_mm))


def _diff(na, a, nb, b):
    a, b = check_finite_array(na, a), check_finite_array(nb, b)
    try:
        np.broadcast_shapes(a.shape, b.shape)
    except ValueError:
        raise ValueError(f"{na} has shape {a.shape} and {nb} {b.shape}; "
                         "they must match (one value per point)") from None
    return a - b


def parallax_mm(B_m, f_mm, H_m, h_m=0.0):
    """The x-parallax of a point h metres above the datum, p = B·f/(H − h), mm (H: flying height above the datum)."""
    B = _positive_array("B_m", B_m, "m")
    f = check_positive("f_mm", f_mm, unit="mm")
    H = _positive_array("H_m", H_m, "m")
    h = check_finite_array("h_m", h_m)
    if np.any(h >= H):
        raise ValueError(f"h_m = {float(np.max(h)):g} is at or above the camera; the valid range is h_m < H_m = "
                         f"{float(np.min(H)):g} m")
    return _out(B * f / (H - h))


def model_point(x_left_mm, y_left_mm, p_mm, B_m, f_mm, H_m=None):
    """The parallax equations: a point of the stereo model from its left-photo coordinates and its x-parallax.

    Parameters
    ----------
    x_left_mm, y_left_mm : array_like
        Coordinates on the left (normalised) photo, mm.
    p_mm : array_like
        x-parallax p = x_left − x_right, mm (p > 0).
    B_m : float
        Air base, m.
    f_mm : float
        Focal length, mm.
    H_m : float, optional
        Flying height of S₁ above a datum, m: then the third column is the
        height above it, h = H − B·f/p; otherwise Z = −B·f/p (from S₁, negative).

    Returns
    -------
    ndarray (..., 3): X = B·x/p, Y = B·y/p (m, from S₁ along the photo's x and y axes) and Z or h (m).
    """
    x = check_finite_array("x_left_mm", x_left_mm)
    y = check_finite_array("y_left_mm", y_left_mm)
    p = check_finite_array("p_mm", p_mm)
    if np.any(p <= 0):
        raise ValueError(f"p_mm = {float(np.min(p)):g}: an x-parallax must be positive (the point in front of both "
                         "cameras); the valid range is p_mm > 0")
    B = check_positive("B_m", B_m, unit="m")
    f = check_positive("f_mm", f_mm, unit="mm")
    X = B * x / p
    Y = B * y / p
    Z = -B * f / p
    if H_m is not None:
        Z = check_positive("H_m", H_m, unit="m") + Z
    X, Y, Z = np.broadcast_arrays(X, Y, Z)
    return np.stack([X, Y, Z], axis=-1)


def height_difference_m(dp_mm, b_mm, H_m, *, approx: bool = False):
    """Height difference from a parallax difference, Δh = H·Δp/(b + Δp) (guide §8; the parallax-bar formula).

    Parameters
    ----------
    dp_mm : array_like
        Parallax difference Δp = p_point − p_reference, mm (positive: the point is higher).
    b_mm : float or array_like
        Parallax of the reference point, mm — the photo base b when the
        reference lies at the height the base was measured for.
    H_m : float
        Flying height above the reference point, m.
    approx : bool
        The small-Δp form Δh ≈ H·Δp/b (good while Δp ≪ b).

    Returns
    -------
    Δh, m (the sign of Δp).
    """
    dp = check_finite_array("dp_mm", dp_mm)
    b = _positive_array("b_mm", b_mm, "mm")
    H = _positive_array("H_m", H_m, "m")
    if approx:
        if np.any(np.abs(H * dp / b) >= H):
            raise ValueError(f"dp_mm = {float(np.max(np.abs(dp))):g} gives |Δh| ≥ H: "
                             "the valid range is |dp_mm| < b_mm")
        return _out(H * dp / b)
    if np.any(b + dp <= 0):
        raise ValueError(f"b_mm + dp_mm = {float(np.min(b + dp)):g}: the point's parallax b + Δp must be positive "
                         "(a point below the reference by the whole flying height has none); the valid range is "
                         "dp_mm > −b_mm")
    dh = H * dp / (b + dp)
    if np.any(dh >= H * (1.0 - 1e-6)):
        raise ValueError(f"dp_mm = {float(np.max(dp)):g} puts the point at the camera "
                         f"(Δh → H = {float(np.max(H)):g} m); "
                         "the valid range keeps Δh below the flying height (dp_mm ≪ 10⁶·b_mm)")
    return _out(dh)


def parallax_difference_mm(dh_m, b_mm, H_m, *, approx: bool = False):
    """Parallax difference of a height difference, Δp = b·Δh/(H − Δh) (≈ b·Δh/H), mm — the inverse of
    :func:`height_difference_m`."""
    dh = check_finite_array("dh_m", dh_m)
    b = _positive_array("b_mm", b_mm, "mm")
    H = _positive_array("H_m", H_m, "m")
    if approx:
        return _out(b * dh / H)
    if np.any(dh >= H):
        raise ValueError(f"dh_m = {float(np.max(dh)):g} reaches the camera; the valid range is dh_m < H_m = "
                         f"{float(np.min(H)):g} m")
    return _out(b * dh / (H - dh))


def flying_height_from_point(B_m, f_mm, p_mm, Z_m=0.0):
    """Height of the projection centres from a point of known height Z: Z_S = Z + B·f/p, m.

    (The flying height above that point is B·f/p.)
    """
    B = _positive_array("B_m", B_m, "m")
    f = check_positive("f_mm", f_mm, unit="mm")
    p = _positive_array("p_mm", p_mm, "mm")
    return _out(check_finite_array("Z_m", Z_m) + B * f / p)


def air_base_from_point(p_mm, f_mm, H_m):
    """Air base from the parallax of a point H metres below the cameras, B = p·H/f, m."""
    p = _positive_array("p_mm", p_mm, "mm")
    f = check_positive("f_mm", f_mm, unit="mm")
    return _out(p * _positive_array("H_m", H_m, "m") / f)


def vertical_exaggeration(B_m, H_m, eye_base_mm=EYE_BASE_MM, viewing_distance_mm=VIEWING_DISTANCE_MM):
    """How much taller the stereo model looks than the ground: V = (B/H)/(e/d).

    The eyes see the model from the viewing distance d with the eye base e;
    the cameras saw the ground from H with the base B.  Heights look V times
    exaggerated relative to horizontal distances (V ≈ 3–4 for B/H ≈ 0.6 at
    25 cm; below 1 the model looks flattened).
    """
    e = check_positive("eye_base_mm", eye_base_mm, unit="mm", hi=200.0)
    d = check_positive("viewing_distance_mm", viewing_distance_mm, unit="mm", hi=5000.0)
    return _out(base_height_ratio(B_m, H_m) / (e / d))


def _positive_array(name, x, unit):
    a = check_finite_array(name, x)
    if np.any(a <= 0):
        raise ValueError(f"{name} = {float(np.min(a)):g} {unit}; the valid range is {name} > 0 {unit}")
    return a if a.ndim else float(a)


@dataclass(frozen=True)
class StereoPair:
    """The geometry of a vertical stereo pair over level ground (guide §2, §8).

    Parameters
    ----------
    f_mm : float
        Focal length f, mm.
    B_m : float
        Air base B, m.
    H_m : float
        Flying height H above the ground, m.
    frame_mm : float
        Side of the frame l, mm (180).
    """

    f_mm: float
    B_m: float
    H_m: float
    frame_mm: float = 180.0

    def __post_init__(self):
        s = object.__setattr__
        s(self, "f_mm", check_positive("f_mm", self.f_mm, unit="mm", hi=g.MAX_F_MM))
        s(self, "B_m", check_positive("B_m", self.B_m, unit="m", hi=1e6))
        s(self, "H_m", check_positive("H_m", self.H_m, unit="m", hi=1e6))
        s(self, "frame_mm", check_positive("frame_mm", self.frame_mm, unit="mm", hi=g.MAX_FRAME_MM))

    @classmethod
    def from_plan(cls, f_mm: float, m: float, px_percent: float, frame_mm: float = 180.0) -> "StereoPair":
        """The pair of a flight plan (guide §2): H = f·m, B = l·m·(1 − p_x/100)."""
        px = check_range("px_percent", px_percent, 0.0, 100.0, hi_open=True, unit="%")
        H = g.flying_height_m(f_mm, m)
        return cls(f_mm, frame_mm / 1000.0 * m * (1.0 - px / 100.0), H, frame_mm)

    @property
    def m(self) -> float:
        """Scale denominator H/f."""
        return self.H_m / (self.f_mm / 1000.0)

    @property
    def b_mm(self) -> float:
        """Photo base b = B·f/H, mm."""
        return self.B_m * self.f_mm / self.H_m

    @property
    def overlap_percent(self) -> float:
        """Forward overlap p_x = (l − b)/l·100, %."""
        return 100.0 * (1.0 - self.b_mm / self.frame_mm)

    @property
    def base_height_ratio(self) -> float:
        """B/H (= b/f)."""
        return self.B_m / self.H_m

    def parallax_mm(self, h_m=0.0):
        """x-parallax of a point h metres above the ground, p = B·f/(H − h), mm."""
        return parallax_mm(self.B_m, self.f_mm, self.H_m, h_m)

    def dp_mm(self, h_m):
        """Parallax difference of a point h above the ground against the ground, mm."""
        return parallax_difference_mm(h_m, self.b_mm, self.H_m)

    def height_precision_m(self, sigma_p_mm: float = 0.01) -> float:
        """Height error of one parallax reading error σ_p: σ_h = H·σ_p/b, m."""
        return self.H_m * check_positive("sigma_p_mm", sigma_p_mm, unit="mm") / self.b_mm

    def vertical_exaggeration(self, eye_base_mm=EYE_BASE_MM, viewing_distance_mm=VIEWING_DISTANCE_MM) -> float:
        return float(vertical_exaggeration(self.B_m, self.H_m, eye_base_mm, viewing_distance_mm))

    def table(self, h_m: float = 10.0) -> pd.DataFrame:
        """The pair's numbers, with a point h metres high."""
        rows = [
            ("Focal length f", "mm", self.f_mm),
            ("Flying height H", "m", self.H_m),
            ("Air base B", "m", self.B_m),
            ("Photo base b = B·f/H", "mm", self.b_mm),
            ("Forward overlap p_x", "%", self.overlap_percent),
            ("B/H", "", self.base_height_ratio),
            ("Parallax of the ground p = b", "mm", float(self.parallax_mm(0.0))),
            (f"Parallax difference of h = {h_m:g} m", "mm", float(self.dp_mm(h_m))),
            ("Height error of σ_p = 0.01 mm", "m", self.height_precision_m(0.01)),
            ("Vertical exaggeration (e 65 mm, d 250 mm)", "×", self.vertical_exaggeration()),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


# =========================================================================== normalised (epipolar) photos
@V.checked(pose_left=g.Pose, pose_right=g.Pose)
def normal_rotation(pose_left: g.Pose, pose_right: g.Pose) -> np.ndarray:
    """The common orientation R_n of the normalised pair: x along S₁S₂, z as near the vertical as that allows.

    Returns a 3×3 rotation whose columns are the normalised camera's x, y, z
    axes in ground coordinates (as :func:`aerophoto.geometry.rotation_matrix`).
    """
    base = pose_right.centre - pose_left.centre
    Bn = float(np.linalg.norm(base))
    if Bn <= 0:
        raise ValueError("pose_left and pose_right have the same projection centre; a stereo pair needs a base B > 0")
    x = base / Bn
    up = np.array([0.0, 0.0, 1.0])
    z = up - (up @ x) * x
    if np.linalg.norm(z) < 1e-9:
        raise ValueError("the air base is vertical; a stereo pair needs a base with a horizontal component")
    z /= np.linalg.norm(z)
    y = np.cross(z, x)
    return np.column_stack([x, y, z])


@V.checked(camera=g.Camera, pose=g.Pose, R_n=V.shape(3, 3), xy_mm=V.array(last=2))
def to_normal(camera: g.Camera, pose: g.Pose, R_n, xy_mm) -> np.ndarray:
    """Photo points (…, 2) of a photo taken at ``pose`` → the same rays on the normalised photo (R_n, same f), mm."""
    xy = check_finite_array("xy_mm", xy_mm)
    f = camera.f_mm
    cam = np.concatenate([xy, np.full(xy.shape[:-1] + (1,), -f)], axis=-1)
    c = cam @ g.rotation_matrix(pose).T @ np.asarray(R_n)
    return np.stack([-f * c[..., 0] / c[..., 2], -f * c[..., 1] / c[..., 2]], axis=-1)


@V.checked(camera=g.Camera, pose=g.Pose, R_n=V.shape(3, 3), xy_mm=V.array(last=2))
def from_normal(camera: g.Camera, pose: g.Pose, R_n, xy_mm) -> np.ndarray:
    """Points (…, 2) of the normalised photo (R_n) → the same rays on the photo taken at ``pose``, mm."""
    xy = check_finite_array("xy_mm", xy_mm)
    f = camera.f_mm
    cam = np.concatenate([xy, np.full(xy.shape[:-1] + (1,), -f)], axis=-1)
    c = cam @ np.asarray(R_n).T @ g.rotation_matrix(pose)
    return np.stack([-f * c[..., 0] / c[..., 2], -f * c[..., 1] / c[..., 2]], axis=-1)


@dataclass(frozen=True, eq=False)
class NormalImage:
    """A piece of a normalised photo: pixel (row, col) centre at x = x0 + (col + ½)·p, y = y_top − (row + ½)·p (mm).

    Attributes
    ----------
    image : ndarray (rows, cols) float32, 0…1, NaN where the original photo does not reach
    x0_mm, y_top_mm : float
        The window's left and top edges, mm on the normalised photo.
    pixel_mm : float
    """

    image: np.ndarray
    x0_mm: float
    y_top_mm: float
    pixel_mm: float

    @property
    def extent_mm(self) -> tuple:
        """(left, right, bottom, top) for ``imshow(..., extent=...)``."""
        r, c = self.image.shape
        return (self.x0_mm, self.x0_mm + c * self.pixel_mm, self.y_top_mm - r * self.pixel_mm, self.y_top_mm)

    def mm_to_pixel(self, xy_mm) -> np.ndarray:
        """(…, 2) mm → (row, col), fractional."""
        xy = np.asarray(xy_mm, float)
        p = self.pixel_mm
        return np.stack([(self.y_top_mm - xy[..., 1]) / p - 0.5, (xy[..., 0] - self.x0_mm) / p - 0.5], axis=-1)

    def pixel_to_mm(self, rc) -> np.ndarray:
        rc = np.asarray(rc, float)
        p = self.pixel_mm
        return np.stack([self.x0_mm + (rc[..., 1] + 0.5) * p, self.y_top_mm - (rc[..., 0] + 0.5) * p], axis=-1)


@V.checked(image=V.image(), camera=g.Camera, pose=g.Pose, R_n=V.shape(3, 3), window_mm=V.shape(4))
def normalise_image(image, camera: g.Camera, pose: g.Pose, R_n, window_mm, pixel_mm: float) -> NormalImage:
    """Resample a photo onto its normalised (epipolar) photo, over a window (bilinear).

    Parameters
    ----------
    image : ndarray (n, n)
        The photo, row 0 at its top (+y), covering the whole frame (:class:`aerophoto.render.Photo` convention).
    window_mm : (x0, x1, y0, y1)
        The piece of the normalised photo to make, mm.
    pixel_mm : float
        Its pixel, mm (0.005 ≤ p ≤ 5; at most 4096 pixels a side).
    """
    from scipy.ndimage import map_coordinates

    img = np.asarray(image, dtype=np.float32)
    if img.ndim != 2 or img.shape[0] != img.shape[1]:
        raise ValueError(f"image has shape {img.shape}; it must be a square photo (n, n)")
    p = check_range("pixel_mm", pixel_mm, 0.005, 5.0, unit="mm")
    x0, x1, y0, y1 = (float(v) for v in check_finite_array("window_mm", window_mm).reshape(4))
    if not (x1 > x0 and y1 > y0):
        raise ValueError(f"window_mm = {window_mm!r} must be (x0, x1, y0, y1) with x1 > x0 and y1 > y0")
    nc = check_int_range("window columns", int(round((x1 - x0) / p)), 1, 4096)
    nr = check_int_range("window rows", int(round((y1 - y0) / p)), 1, 4096)
    xs = x0 + (np.arange(nc) + 0.5) * p
    ys = y1 - (np.arange(nr) + 0.5) * p
    XX, YY = np.meshgrid(xs, ys)
    src = from_normal(camera, pose, R_n, np.stack([XX, YY], axis=-1))
    n = img.shape[0]
    h, q = camera.half_mm, camera.frame_mm / n
    rows = (h - src[..., 1]) / q - 0.5
    cols = (src[..., 0] + h) / q - 0.5
    out = map_coordinates(img, [rows.ravel(), cols.ravel()], order=1, mode="constant", cval=np.nan,
                          output=np.float32).reshape(nr, nc)
    outside = (rows < -0.5) | (rows > n - 0.5) | (cols < -0.5) | (cols > n - 0.5)
    out[outside] = np.nan
    return NormalImage(out, x0, y1, p)


# =========================================================================== seeing it
@V.checked(left=V.image(2, 3), right=V.image(2, 3))
def anaglyph(left, right, *, background: float = 0.5) -> np.ndarray:
    """A red–cyan anaglyph (rows, cols, 3) float32: red = left photo, green and blue = right photo.

    Seen through red–cyan glasses with the **red filter over the left eye**
    each eye gets its photo (the direct stereo effect); ``anaglyph(right,
    left)`` swaps them (the reverse stereo effect).  Both images 0…1, the same
    shape; NaN shows as ``background`` in its channel.
    """
    L = np.asarray(left, dtype=np.float32)
    R = np.asarray(right, dtype=np.float32)
    if L.shape != R.shape or L.ndim != 2:
        raise ValueError(f"left {L.shape} and right {R.shape} must be 2-D images of the same shape")
    bg = check_range("background", background, 0.0, 1.0)
    out = np.empty(L.shape + (3,), np.float32)
    out[..., 0] = np.where(np.isfinite(L), L, bg)
    out[..., 1] = np.where(np.isfinite(R), R, bg)
    out[..., 2] = out[..., 1]
    np.clip(out, 0.0, 1.0, out=out)
    return out


@V.checked(left=V.image(2, 3), right=V.image(2, 3), background=V.number())
def side_by_side(left, right, separation_px: int, *, background: float = 1.0) -> np.ndarray:
    """The two photos side by side, the right one ``separation_px`` to the right of the left (one array).

    With both pieces cut from normalised photos over windows ``p₀`` apart (the
    right window at x − p₀), conjugate points of parallax p₀ land exactly
    ``separation_px`` apart: print it at true size with the separation equal
    to your eye base (free viewing, :data:`EYE_BASE_MM`) or your stereoscope's
    base (:data:`STEREOSCOPE_BASE_MM`).  The pieces must not be wider than the
    separation.  NaN and the gap show as ``background``.
    """
    L = np.asarray(left, dtype=np.float32)
    R = np.asarray(right, dtype=np.float32)
    if L.shape != R.shape or L.ndim != 2:
        raise ValueError(f"left {L.shape} and right {R.shape} must be 2-D images of the same shape")
    rows, cols = L.shape
    sep = check_int_range("separation_px", separation_px, cols, 100000)
    out = np.full((rows, sep + cols), float(background), np.float32)
    out[:, :cols] = np.where(np.isfinite(L), L, background)
    out[:, sep:sep + cols] = np.where(np.isfinite(R), R, background)
    return out


# =========================================================================== matching parallaxes
def _ncc(image, template, *, prefer_library: bool = True) -> np.ndarray:
    """Normalised cross-correlation of ``template`` at every position inside ``image`` ("valid" placement).

    γ(u, v) = Σ(I − Ī)(T − T̄) / sqrt(Σ(I − Ī)² · Σ(T − T̄)²), the sums over the
    template's window with its top-left corner at image[u, v] (Ī the window's
    mean), and 0 where the denominator is not above the machine epsilon of the
    working float type (flat windows): :func:`skimage.feature.match_template`
    with ``pad_input=False``.

    Parameters
    ----------
    image : ndarray (rows, cols)
        Where to search (a strip of rows of the right photo), image units.
    template : ndarray (t_rows, t_cols)
        The window of the left photo, no larger than ``image``.
    prefer_library : bool
        Use scikit-image when it can be imported (the installed book); with
        False, or when it cannot (the browser book: Pyodide has no
        scikit-image), the same computation with numpy and scipy.

    Returns
    -------
    ndarray (rows − t_rows + 1, cols − t_cols + 1)
        γ, −1…1; float32 for a float32 (or float16) image, else float64.

    Notes
    -----
    The fallback repeats scikit-image's algorithm step for step, not just its
    formula: the image zero-padded by the template's size, window sums Σ I,
    Σ I² from cumulative sums, Σ I·T by :func:`scipy.signal.fftconvolve`,
    numerator Σ I·T − Σ I·T̄, denominator sqrt((Σ I² − (Σ I)²/N)·Σ(T − T̄)²),
    all in the image's float type (float32 for the photos).  That arithmetic
    is part of the result: on a float32 photo the direct float64 sum of the
    formula differs from scikit-image's by ~1e-4 in γ on ordinary windows and
    up to ~0.02 (0.07 px of disparity) on nearly flat ones (water, σ ≈ 0.003),
    whereas the step-for-step copy agrees with it to rounding.
    """
    if prefer_library:
        try:
            from skimage.feature import match_template
        except ImportError:
            pass
        else:
            return match_template(image, template)
    from scipy.signal import fftconvolve

    img = np.asarray(image)
    tpl = np.asarray(template)
    if img.ndim != 2 or tpl.ndim != 2 or img.shape[0] < tpl.shape[0] or img.shape[1] < tpl.shape[1]:
        raise ValueError(f"image {img.shape} and template {tpl.shape} must be 2-D, the template no larger")
    ftype = np.float32 if img.dtype in (np.float16, np.float32) else np.float64  # scikit-image's working type
    th, tw = tpl.shape
    padded = np.pad(img.astype(ftype, copy=False), ((th, th), (tw, tw)))

    def window_sum(a):
        cs = np.cumsum(a, axis=0)
        cs = cs[th:-1] - cs[:-th - 1]
        cs = np.cumsum(cs, axis=1)
        return cs[:, tw:-1] - cs[:, :-tw - 1]

    s1 = window_sum(padded)
    s2 = window_sum(padded ** 2)
    t_mean = tpl.mean()
    t_ssd = np.sum((tpl - t_mean) ** 2)
    xcorr = fftconvolve(padded, tpl[::-1, ::-1], mode="valid")[1:-1, 1:-1]
    num = xcorr - s1 * t_mean
    den = s2 - (s1 * s1) / (th * tw)
    den *= t_ssd
    np.sqrt(np.maximum(den, 0), out=den)
    out = np.zeros_like(xcorr, dtype=ftype)
    ok = den > np.finfo(ftype).eps
    out[ok] = num[ok] / den[ok]
    return out[th - 1:img.shape[0], tw - 1:img.shape[1]]


@V.checked(left=V.image(), right=V.image(), rc=V.points(2), half_window=V.whole(1, 500),
           d_min=V.whole(-100_000, 100_000), d_max=V.whole(-100_000, 100_000))
def match_points(left, right, rc, *, half_window: int = 7, d_min: int = 0, d_max: int = 40):
    """Disparities of single points by normalised cross-correlation along their rows (epipolar lines).

    The template is the left image's (2w+1)² window about each (row, col);
    it is slid along the same rows of the right image over disparities
    d = col_left − col_right in [d_min, d_max] (:func:`skimage.feature.match_template`),
    and the peak is refined by a parabola through its neighbours.  Without
    scikit-image (the browser book) the same correlation is computed in numpy
    (:func:`_ncc`, a step-for-step copy of scikit-image's).

    Returns ``(d, peak)``: the disparity (pixels, fractional; NaN where the
    window leaves an image) and the correlation at the peak (−1…1).
    """
    if np.shape(left) != np.shape(right):
        raise ValueError(f"left {np.shape(left)} and right {np.shape(right)} must be images of the same shape")
    L = np.nan_to_num(np.asarray(left, dtype=np.float32), nan=0.5)
    R = np.nan_to_num(np.asarray(right, dtype=np.float32), nan=0.5)
    w = check_int_range("half_window", half_window, 1, 64)
    lo = int(d_min)
    hi = int(d_max)
    if hi <= lo:
        raise ValueError(f"d_max = {d_max} must exceed d_min = {d_min}")
    rc = np.asarray(rc, dtype=float).reshape(-1, 2)
    d_out = np.full(len(rc), np.nan)
    peak = np.full(len(rc), np.nan)
    rows, cols = L.shape
    for i, (r, c) in enumerate(np.rint(rc).astype(int)):
        c0 = c - hi - w
        c1 = c - lo + w + 1
        if r - w < 0 or r + w + 1 > rows or c - w < 0 or c + w + 1 > cols or c0 < 0 or c1 > cols:
            continue
        tpl = L[r - w:r + w + 1, c - w:c + w + 1]
        res = _ncc(R[r - w:r + w + 1, c0:c1], tpl)[0]  # index j ↔ right column c0 + w + j
        j = int(np.argmax(res))
        frac = 0.0
        if 0 < j < len(res) - 1:
            a, b, cc = res[j - 1], res[j], res[j + 1]
            den = a - 2 * b + cc
            frac = 0.5 * (a - cc) / den if den < 0 else 0.0
        d_out[i] = c - (c0 + w + j + frac)
        peak[i] = float(res[j])
    return d_out, peak


@dataclass(frozen=True, eq=False)
class DenseParallax:
    """Disparities of every pixel of the left image (see :func:`dense_parallax`).

    Attributes
    ----------
    d_px : ndarray (rows, cols)
        Disparity col_left − col_right, pixels (NaN where unknown).
    peak : ndarray (rows, cols)
        The correlation at the chosen disparity, −1…1.
    second : ndarray (rows, cols)
        The best correlation more than one pixel away from the chosen disparity
        (near the peak: a repetitive pattern, e.g. furrows, matches there as well).
    contrast : ndarray (rows, cols)
        The template's standard deviation (texture), image units.
    consistent : ndarray (rows, cols) bool
        Matching the right image back to the left lands within a pixel of the
        start (the left–right check; all True when it was not made).
    """

    d_px: np.ndarray
    peak: np.ndarray
    second: np.ndarray
    contrast: np.ndarray
    consistent: np.ndarray

    def reliable(self, min_peak: float = 0.8, min_margin: float = 0.2, min_contrast: float = 0.015) -> np.ndarray:
        """Where the match is trustworthy: a high, unique peak on textured ground that matches back."""
        with np.errstate(invalid="ignore"):
            return (np.isfinite(self.d_px) & (self.peak >= min_peak) & (self.peak - self.second >= min_margin)
                    & (self.contrast >= min_contrast) & self.consistent)


@V.checked(left=V.image(), right=V.image(), half_window=V.whole(1, 500),
           d_min=V.whole(-100_000, 100_000), d_max=V.whole(-100_000, 100_000))
def dense_parallax(left, right, *, half_window: int = 5, d_min: int = 0, d_max: int = 40,
                   check: bool = True) -> DenseParallax:
    """Normalised cross-correlation of every pixel along its row, for every whole disparity, with box filters.

    For each d in [d_min, d_max] the right image shifted by d is correlated
    with the left over (2w+1)² windows (means, variances and the covariance
    by :func:`scipy.ndimage.uniform_filter`); the best d per pixel is refined
    by a parabola.  The same NCC as :func:`match_points`, for the whole image
    at once.  With ``check`` the right image is matched back to the left
    (the left–right consistency check, :attr:`DenseParallax.consistent`).
    """
    L = np.asarray(left, dtype=np.float64)
    R = np.asarray(right, dtype=np.float64)
    if L.shape != R.shape or L.ndim != 2:
        raise ValueError(f"left {L.shape} and right {R.shape} must be 2-D images of the same shape")
    w = check_int_range("half_window", half_window, 1, 64)
    lo, hi = int(d_min), int(d_max)
    if hi <= lo or hi - lo > 512:
        raise ValueError(f"d_min = {d_min}, d_max = {d_max}: the valid range is d_min < d_max ≤ d_min + 512")
    first = _dense(L, R, w, lo, hi)
    if not check:
        return first
    back = _dense(R[:, ::-1], L[:, ::-1], w, lo, hi)
    d_back = back.d_px[:, ::-1]  # for each right pixel: col_left − col_right of its match in the left image
    rows, cols = first.d_px.shape
    c_r = np.rint(np.arange(cols)[None, :] - np.nan_to_num(first.d_px, nan=-10 * cols)).astype(np.int64)
    ok = (c_r >= 0) & (c_r < cols) & np.isfinite(first.d_px)
    db = d_back[np.arange(rows)[:, None], np.clip(c_r, 0, cols - 1)]
    with np.errstate(invalid="ignore"):
        consistent = ok & (np.abs(db - first.d_px) <= 1.0)
    return DenseParallax(first.d_px, first.peak, first.second, first.contrast, consistent)


def _dense(L, R, w, lo, hi) -> DenseParallax:
    """The box-filter NCC for every d in [lo, hi]; the best d per pixel and the best rival more than 1 away."""
    from scipy.ndimage import uniform_filter

    size = 2 * w + 1
    okL = np.isfinite(L)
    L0 = np.where(okL, L, 0.0)
    mL = uniform_filter(L0, size, mode="nearest")
    vL = uniform_filter(L0 * L0, size, mode="nearest") - mL * mL
    rows, cols = L.shape
    ds = np.arange(lo, hi + 1)
    scores = np.full((len(ds), rows, cols), -np.inf)
    for k, d in enumerate(ds):
        Rs = np.full_like(R, np.nan)
        if d >= 0:
            Rs[:, d:] = R[:, :cols - d] if d else R
        else:
            Rs[:, :d] = R[:, -d:]
        ok = np.isfinite(Rs) & okL
        R0 = np.where(ok, Rs, 0.0)
        mR = uniform_filter(R0, size, mode="nearest")
        vR = uniform_filter(R0 * R0, size, mode="nearest") - mR * mR
        cov = uniform_filter(L0 * R0, size, mode="nearest") - mL * mR
        den = np.sqrt(np.clip(vL, 0, None) * np.clip(vR, 0, None))
        ncc = np.where(den > 1e-9, cov / np.where(den > 1e-9, den, 1.0), -1.0)
        valid = uniform_filter(ok.astype(float), size, mode="nearest") > 0.999
        scores[k] = np.where(valid, ncc, -np.inf)
    best = np.argmax(scores, axis=0)
    peak = np.take_along_axis(scores, best[None], 0)[0]
    a = np.take_along_axis(scores, np.clip(best - 1, 0, len(ds) - 1)[None], 0)[0]
    c = np.take_along_axis(scores, np.clip(best + 1, 0, len(ds) - 1)[None], 0)[0]
    inner = (best > 0) & (best < len(ds) - 1) & np.isfinite(a) & np.isfinite(c)
    den = a - 2 * peak + c
    with np.errstate(invalid="ignore", divide="ignore"):
        frac = np.where(inner & (den < 0), 0.5 * (a - c) / np.where(den < 0, den, -1.0), 0.0)
    d = ds[best] + frac
    d = np.where(np.isfinite(peak), d, np.nan)
    near = np.abs(np.arange(len(ds))[:, None, None] - best[None]) <= 1
    scores[near] = -np.inf
    second = scores.max(axis=0)
    second = np.where(np.isfinite(second), second, -1.0)
    peak = np.where(np.isfinite(peak), peak, np.nan)
    return DenseParallax(d, peak, second, np.sqrt(np.clip(vL, 0, None)), np.ones(d.shape, bool))


def _out(x):
    """A float for a scalar result, else the array."""
    a = np.asarray(x, dtype=float)
    return float(a) if a.ndim == 0 else a

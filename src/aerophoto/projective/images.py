"""Resampling whole photos through a 2-D transformation (guide §10, §12): scikit-image's warp.

A photo rendered by :mod:`aerophoto.render` is an array ``image[row, col]``
whose pixel centres sit at photo millimetres

    x = −l/2 + (col + 0.5)·p,    y = +l/2 − (row + 0.5)·p,    p = l/n_px

(row 0 at the top, +y).  :func:`warp_photo` resamples such an image onto a
raster of another plane — the plan, the screen of a photo transformer — given
the transformation from photo mm to that plane's units (a
:class:`aerophoto.plane.Projective2D`, :class:`~aerophoto.plane.Affine2D`,
:class:`~aerophoto.plane.Similarity2D` or a 3×3 matrix).  The output raster
follows the same convention: its pixel (r, c) has its centre at

    X = x_min + (c + 0.5)·q,    Y = y_max − (r + 0.5)·q

so ``imshow(out.image, extent=out.extent)`` (origin "upper") shows it in the
plane's units.  Each output pixel takes the value of the photo at the
inverse image of its centre (bilinear by default:
:func:`skimage.transform.warp` with the composed homogeneous matrix; in the
browser book, which has no scikit-image, the same resampling written with
scipy, equal to it); pixels whose inverse image falls off the photo get
``cval`` (NaN by default).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _validate as V
from .._validate import check_finite_array, check_int_range, check_positive, check_range

__all__ = ["MAX_OUTPUT_PIXELS", "Raster", "photo_pixel_matrix", "raster_pixel_matrix", "as_matrix", "warp_photo",
           "warp_raster"]

#: most pixels of an output raster (work-size guard)
MAX_OUTPUT_PIXELS = 16_000_000


@dataclass(frozen=True)
class Raster:
    """A resampled image and where it lies.

    Attributes
    ----------
    image : ndarray (rows, cols), float
        Row 0 at the top (largest Y); NaN where nothing fell.
    extent : tuple (x_min, x_max, y_min, y_max)
        For ``imshow(..., extent=extent)``, in the plane's units.
    pixel : float
        Pixel size q in the plane's units.
    """

    image: np.ndarray
    extent: tuple
    pixel: float

    def pixel_centres(self) -> np.ndarray:
        """Centres (rows, cols, 2) of the raster's pixels in the plane's units."""
        x0, _, _, y1 = self.extent
        r, c = self.image.shape[:2]
        X = x0 + (np.arange(c) + 0.5) * self.pixel
        Y = y1 - (np.arange(r) + 0.5) * self.pixel
        out = np.empty((r, c, 2))
        out[..., 0] = X[None, :]
        out[..., 1] = Y[:, None]
        return out

    def value_at(self, xy) -> np.ndarray:
        """Bilinear value at points (…, 2) in the plane's units (NaN off the raster)."""
        from scipy.ndimage import map_coordinates

        p = np.asarray(xy, dtype=float)
        x0, _, _, y1 = self.extent
        col = (p[..., 0] - x0) / self.pixel - 0.5
        row = (y1 - p[..., 1]) / self.pixel - 0.5
        out = map_coordinates(self.image, [row.ravel(), col.ravel()], order=1, mode="constant", cval=np.nan)
        return out.reshape(p.shape[:-1])


def photo_pixel_matrix(frame_mm: float, n_px: int) -> np.ndarray:
    """3×3 matrix taking a photo's (col, row, 1) to photo mm (x, y, 1) (the render convention)."""
    ell = check_positive("frame_mm", frame_mm, unit="mm", hi=500.0)
    n = check_int_range("n_px", n_px, 1, 100000)
    p = ell / n
    h = ell / 2.0
    return np.array([[p, 0.0, -h + 0.5 * p], [0.0, -p, h - 0.5 * p], [0.0, 0.0, 1.0]])


@V.checked(extent=V.shape(4), pixel=V.number(0.0, lo_open=True))
def raster_pixel_matrix(extent, pixel: float) -> np.ndarray:
    """3×3 matrix taking an output raster's (col, row, 1) to the plane's (X, Y, 1)."""
    x0, _, _, y1 = (float(e) for e in extent)
    q = float(pixel)
    return np.array([[q, 0.0, x0 + 0.5 * q], [0.0, -q, y1 - 0.5 * q], [0.0, 0.0, 1.0]])


def as_matrix(transform) -> np.ndarray:
    """The 3×3 homogeneous matrix of a Similarity2D / Affine2D / Projective2D or of a 3×3 array."""
    if hasattr(transform, "matrix"):
        M = np.asarray(transform.matrix(), dtype=float)
    else:
        M = check_finite_array("transform", transform, ndim=2)
    if M.shape != (3, 3) or not np.all(np.isfinite(M)):
        raise ValueError(f"transform has shape {M.shape}; expected a 2-D transformation or a finite 3×3 matrix")
    if abs(np.linalg.det(M)) < 1e-300:
        raise ValueError("the transformation is singular (determinant 0): it cannot be inverted to resample")
    return M


def _extent(extent):
    x0, x1, y0, y1 = (check_range(f"extent[{k}]", e, -1e12, 1e12) for k, e in enumerate(extent))
    if not (x1 > x0 and y1 > y0):
        raise ValueError(f"extent = {tuple(extent)}; expected (x_min, x_max, y_min, y_max) with x_max > x_min, "
                         "y_max > y_min")
    return x0, x1, y0, y1


def _warp(image: np.ndarray, inverse: np.ndarray, shape: tuple, *, order: int = 1, cval: float = np.nan,
          prefer_library: bool = True) -> np.ndarray:
    """Projective resampling: out[r, c] = image at (col, row) = the projection of ``inverse`` @ (c, r, 1).

    Parameters
    ----------
    image : ndarray (rows, cols), float
        The input image.
    inverse : ndarray (3, 3)
        Homogeneous matrix taking an output pixel's (col, row, 1) to the input's (col, row, w).
    shape : (rows, cols)
        The output's shape.
    order : int
        Interpolation order 0…5.
    cval : float
        Value wherever the interpolation reaches outside the input.
    prefer_library : bool
        Use :func:`skimage.transform.warp` (``mode="constant"``, ``clip=False``,
        ``preserve_range=True``) when it can be imported (the installed book);
        with False, or when it cannot (the browser book: Pyodide has no
        scikit-image), the same resampling with numpy and scipy, which
        reproduces it pixel for pixel, NaN mask included: orders 0, 2, 4, 5
        by :func:`scipy.ndimage.map_coordinates` with mode "grid-constant"
        (what scikit-image itself passes to scipy for its "constant"; plain
        "constant" would drop the cval's share near the edge), orders 1 and 3
        as scikit-image's own Cython code does them (:func:`_convolve`:
        bilinear, and bicubic by cubic convolution, not scipy's B-spline).

    Returns
    -------
    ndarray (rows, cols), float
    """
    if prefer_library:
        try:
            from skimage.transform import warp
        except ImportError:
            pass
        else:
            return warp(image, inverse, output_shape=shape, order=order, mode="constant", cval=cval, clip=False,
                        preserve_range=True)
    img = np.asarray(image, dtype=float)
    H = np.asarray(inverse, dtype=float)
    rows, cols = (int(n) for n in shape)
    # the source coordinates, computed in scikit-image's own order of operations (a tie of order 0 at x.5
    # then falls the same way)
    if order in (1, 3):  # its Cython code: (H₀₀·c + H₀₁·r + H₀₂)/(H₂₀·c + H₂₁·r + H₂₂), and its interpolation
        r, c = np.mgrid[0:rows, 0:cols].astype(float)
        w = H[2, 0] * c + H[2, 1] * r + H[2, 2]
        col = (H[0, 0] * c + H[0, 1] * r + H[0, 2]) / w
        row = (H[1, 0] * c + H[1, 1] * r + H[1, 2]) / w
        return _convolve(img, row.ravel(), col.ravel(), order, float(cval)).reshape(rows, cols)
    from scipy.ndimage import map_coordinates

    # ProjectiveTransform on (col, row, 1) column by column (warp_coords), then scipy
    cr = np.indices((cols, rows), dtype=float).reshape(2, -1).T
    h = np.hstack((cr, np.ones((cr.shape[0], 1)))) @ H.T
    div = np.where(h[:, 2] == 0, np.finfo(float).eps, h[:, 2])
    xy = h[:, :2] / div[:, None]
    coords = xy.T.reshape(2, cols, rows).swapaxes(1, 2)[::-1]  # (row, col) grids, each (rows, cols)
    return map_coordinates(img, coords, order=order, mode="grid-constant", cval=float(cval), prefilter=order > 1)


def _convolve(img: np.ndarray, row: np.ndarray, col: np.ndarray, order: int, cval: float,
              chunk: int = 1 << 18) -> np.ndarray:
    """scikit-image's bilinear (order 1) or bicubic (order 3) value of ``img`` at (row, col) (N,), off the image cval.

    Order 1: the taps floor and ceil of each coordinate (one pixel when it is
    whole), weights 1 − t and t.  Order 3: cubic convolution with a = −0.5
    (Catmull–Rom) over the taps floor − 1 … floor + 2.  A tap off the image
    counts as ``cval`` whatever its weight, as in scikit-image (so with a NaN
    cval a bicubic sample within a pixel of the edge is NaN).
    """
    n_r, n_c = img.shape
    out = np.empty(row.shape)

    def taps(x):
        x0 = np.floor(x)
        t = x - x0
        i0 = x0.astype(np.int64)
        if order == 1:
            return (i0, i0 + (t > 0)), (1.0 - t, t)
        return ((i0 - 1, i0, i0 + 1, i0 + 2),
                (0.5 * t * (-1.0 + t * (2.0 - t)), 1.0 + t * t * (-2.5 + 1.5 * t),
                 0.5 * t * (1.0 + t * (4.0 - 3.0 * t)), 0.5 * t * t * (t - 1.0)))

    for a in range(0, row.size, chunk):
        (ri, wr), (cj, wc) = taps(row[a:a + chunk]), taps(col[a:a + chunk])
        acc = np.zeros(ri[0].shape)
        for r, w_r in zip(ri, wr):
            in_r = (r >= 0) & (r < n_r)
            line = np.zeros(acc.shape)
            for c, w_c in zip(cj, wc):
                ok = in_r & (c >= 0) & (c < n_c)
                line += w_c * np.where(ok, img[np.clip(r, 0, n_r - 1), np.clip(c, 0, n_c - 1)], cval)
            acc += w_r * line
        out[a:a + chunk] = acc
    return out


@V.checked(image=V.image(2, 3), to_plane_of_pixels=V.shape(3, 3), extent=V.shape(4), cval=V.fill())
def warp_raster(image, to_plane_of_pixels: np.ndarray, transform, extent, pixel: float, *, order: int = 1,
                cval: float = np.nan) -> Raster:
    """Resample ``image`` whose (col, row, 1) map to its own plane by ``to_plane_of_pixels`` (3×3).

    ``transform`` takes the image's plane to the output plane; the output
    covers ``extent`` (x_min, x_max, y_min, y_max) with pixels of size
    ``pixel`` (output units).  See :func:`warp_photo` for photos.  Without
    scikit-image (the browser book) the same resampling is done with scipy
    (:func:`_warp`).
    """
    img = check_finite_array("image", image, ndim=2)
    A_in = np.asarray(to_plane_of_pixels, dtype=float)
    T = as_matrix(transform)
    x0, x1, y0, y1 = _extent(extent)
    q = check_positive("pixel", pixel)
    cols = max(1, int(math.ceil((x1 - x0) / q - 1e-9)))
    rows = max(1, int(math.ceil((y1 - y0) / q - 1e-9)))
    if rows * cols > MAX_OUTPUT_PIXELS:
        raise ValueError(f"the output raster would have {rows}×{cols} pixels; the valid range is at most "
                         f"{MAX_OUTPUT_PIXELS} pixels (choose a larger pixel or a smaller extent)")
    order = check_int_range("order", order, 0, 5)
    ext = (x0, x0 + cols * q, y1 - rows * q, y1)
    A_out = raster_pixel_matrix(ext, q)
    inverse = np.linalg.inv(A_in) @ np.linalg.inv(T) @ A_out  # output (col, row) → input (col, row)
    out = _warp(img, inverse, (rows, cols), order=order, cval=float(cval))
    return Raster(out, ext, q)


@V.checked(image=V.image(2, 3), extent=V.shape(4), cval=V.fill())
def warp_photo(image, transform, extent, pixel: float, *, frame_mm: float = 180.0, order: int = 1,
               cval: float = np.nan) -> Raster:
    """Resample a photo (render's pixel convention) onto another plane.

    Parameters
    ----------
    image : ndarray (n_px, n_px)
        The photo; its side is ``frame_mm``.
    transform : Projective2D, Affine2D, Similarity2D or 3×3 array
        Photo mm → output plane (e.g. plan mm): a projective transformation
        fitted on four control points rectifies a photo of flat ground (guide §12).
    extent : (x_min, x_max, y_min, y_max)
        The output window in the output plane's units; the raster is cut to
        whole pixels from the top-left corner.
    pixel : float
        Output pixel size q in the output units.
    order : int
        Interpolation order 0…5 (1 = bilinear).
    cval : float
        Value of output pixels whose source lies off the photo.

    Returns
    -------
    :class:`Raster`
    """
    img = check_finite_array("image", image, ndim=2)
    if img.shape[0] != img.shape[1]:
        raise ValueError(f"image has shape {img.shape}; a photo is square, (n_px, n_px)")
    return warp_raster(img, photo_pixel_matrix(frame_mm, img.shape[0]), transform, extent, pixel, order=order,
                       cval=cval)

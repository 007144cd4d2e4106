"""What makes a photo readable (дешифрируемость): the shooting conditions of guide §9 as physics.

Guide §9 lists the conditions of photographing that decide how well a photo can be interpreted
(дешифрирование).  Each is a parameter of :class:`Conditions`, and each changes the photo in a physically
motivated way (the colour renderer :mod:`aerophoto.site.colour` applies them; this module holds the formulas,
layer 2, pure):

==  ===========================  ===================================================================================
§9  condition (Russian)          what it does to the photo here
==  ===========================  ===================================================================================
1   season (время года)          the classes' spectra change (:data:`aerophoto.spectral.SEASONS`): winter snow
                                 hides fields, roads and water; spring and autumn have wet soil and leaf-off or dull
                                 vegetation (lower landscape contrast)
2   time of day (время дня)      sun elevation e and azimuth A: shadows of length L = h / tan e falling away from
                                 the sun (:func:`shadow_length_m`), slopes shaded by their steepness and exposure
                                 (:func:`slope_illumination`, Lambert's law with the renderer's ambient 0.35)
3   moisture (влажность)         the topsoil's volumetric moisture θ: soil darker and more uniform
                                 (:func:`aerophoto.spectral.moisture_factor`), standing water on wet meadows and
                                 bogs
4   landscape contrast           what the classes' spectra give; measured by :func:`contrast`
    (контраст ландшафта)
5   haze (задымленность)         the meteorological visibility V: the air below the aircraft adds its own brightness
                                 and lowers contrast (:func:`haze`, Koschmieder and a two-stream layer)
6   tilt (угол наклона)          α of the camera: scale varies across the photo, objects hide each other (the
                                 renderer's exact central projection)
7   exposure and speed           image motion δ = W·t/m on the photo (:func:`image_motion_mm`), a blur along the
    (выдержка, скорость)         flight line (:func:`motion_blur`)
8   steep slopes (крутизна)      relief shading and shadows of slopes (condition 2 on the DEM)
==  ===========================  ===================================================================================

Sources: :data:`aerophoto.spectral.SOURCES` (spectra, haze); image motion as in guide §2 (t_max = δ·M/W); shading
by Lambert's cosine law relative to level ground (as :func:`aerophoto.site.raycast.shading`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _validate as V
from . import spectral as sp
from ._validate import check_range

__all__ = ["Conditions", "CONDITIONS", "AMBIENT", "shadow_length_m", "shadow_azimuth_deg", "slope_illumination",
           "image_motion_mm", "motion_blur", "haze", "contrast", "conditions_table", "SEASONS"]

SEASONS = sp.SEASONS
#: light in shadow as a share of full sun on level ground (the renderer's, :data:`aerophoto.render.AMBIENT`)
AMBIENT = 0.35


@dataclass(frozen=True)
class Conditions:
    """The shooting conditions of guide §9 (see the module notes).

    Parameters
    ----------
    season : one of :data:`SEASONS` ("summer", "autumn", "spring", "winter")
    sun_elevation_deg : the sun's elevation e, 5…90°
    sun_azimuth_deg : the sun's azimuth A, clockwise from north, 0…360°
    visibility_km : meteorological visibility V, 1…100 km; None: no air at all (the ground's own reflectance)
    moisture_pct : the topsoil's volumetric moisture θ above the season's, 0…30 %
    speed_kmh : ground speed W, 0…600 km/h
    exposure_ms : exposure time t, 0…20 ms
    alpha_deg : tilt α of the camera, 0…10°
    """

    season: str = "summer"
    sun_elevation_deg: float = 45.0
    sun_azimuth_deg: float = 150.0
    visibility_km: float | None = 30.0
    moisture_pct: float = 0.0
    speed_kmh: float = 200.0
    exposure_ms: float = 2.0
    alpha_deg: float = 0.0

    def __post_init__(self):
        if self.season not in SEASONS:
            raise ValueError(f"season = {self.season!r} is not one of the seasons {list(SEASONS)}")
        s = object.__setattr__
        s(self, "sun_elevation_deg", check_range("sun_elevation_deg", self.sun_elevation_deg, 5.0, 90.0, unit="°"))
        s(self, "sun_azimuth_deg", check_range("sun_azimuth_deg", self.sun_azimuth_deg, 0.0, 360.0, unit="°"))
        if self.visibility_km is not None:
            s(self, "visibility_km", check_range("visibility_km", self.visibility_km, 1.0, 100.0, unit="km"))
        s(self, "moisture_pct", check_range("moisture_pct", self.moisture_pct, 0.0, 30.0, unit="%"))
        s(self, "speed_kmh", check_range("speed_kmh", self.speed_kmh, 0.0, 600.0, unit="km/h"))
        s(self, "exposure_ms", check_range("exposure_ms", self.exposure_ms, 0.0, 20.0, unit="ms"))
        s(self, "alpha_deg", check_range("alpha_deg", self.alpha_deg, 0.0, 10.0, unit="°"))

    @property
    def sun_direction(self) -> np.ndarray:
        """Unit vector towards the sun (X east, Y north, Z up)."""
        a, e = math.radians(self.sun_azimuth_deg), math.radians(self.sun_elevation_deg)
        return np.array([math.sin(a) * math.cos(e), math.cos(a) * math.cos(e), math.sin(e)])


#: §9's list of conditions: number, English, Russian
CONDITIONS = (
    (1, "season", "время года"), (2, "time of day: sun elevation and azimuth", "время дня"),
    (3, "moisture of the objects", "влажность объектов"), (4, "landscape contrast", "контраст ландшафта"),
    (5, "haze, smoke in the air", "задымленность воздуха"), (6, "tilt of the negative", "угол наклона аэронегатива"),
    (7, "exposure time and the aircraft's speed", "длительность выдержки и скорость полёта"),
    (8, "steep slopes of hills and ravines", "значительная крутизна склонов гор и оврагов"),
)


@V.checked(h_m=V.values(0.0))
def shadow_length_m(h_m, sun_elevation_deg):
    """Length of the shadow of a height h on level ground: L = h / tan e, metres (h ≥ 0, 1° ≤ e ≤ 90°)."""
    e = check_range("sun_elevation_deg", sun_elevation_deg, 1.0, 90.0, unit="°")
    h = np.asarray(h_m, float)
    if np.any(~np.isfinite(h)) or np.any(h < 0):
        raise ValueError(f"h_m = {h_m!r} is outside the valid range h_m ≥ 0 (m)")
    return h / math.tan(math.radians(e))


def shadow_azimuth_deg(sun_azimuth_deg) -> float:
    """The direction shadows fall in: away from the sun, A + 180°, degrees clockwise from north."""
    A = check_range("sun_azimuth_deg", sun_azimuth_deg, 0.0, 360.0, unit="°")
    return (A + 180.0) % 360.0


@V.checked(slope_deg=V.values(0.0, 90.0), aspect_deg=V.values(), ambient=V.number(0.0, 1.0))
def slope_illumination(slope_deg, aspect_deg, sun_elevation_deg, sun_azimuth_deg, ambient: float = AMBIENT):
    """Brightness of a slope relative to level ground in full sun (Lambert): a + (1 − a)·max(cos i, 0)/sin e.

    ``cos i = cos s·sin e + sin s·cos e·cos(A − aspect)``: slope s, its aspect (the way it faces, clockwise from
    north), sun elevation e and azimuth A, degrees.  1 on level ground; brighter on slopes facing the sun; a on
    slopes turned away (guide §9, conditions 2 and 8).
    """
    s = np.radians(np.asarray(slope_deg, float))
    if np.any(~np.isfinite(s)) or np.any((s < 0) | (s > math.pi / 2)):
        raise ValueError(f"slope_deg = {slope_deg!r} is outside the valid range 0 ≤ slope_deg ≤ 90 (°)")
    e = math.radians(check_range("sun_elevation_deg", sun_elevation_deg, 1.0, 90.0, unit="°"))
    A = math.radians(check_range("sun_azimuth_deg", sun_azimuth_deg, 0.0, 360.0, unit="°"))
    asp = np.radians(np.asarray(aspect_deg, float))
    cos_i = np.cos(s) * math.sin(e) + np.sin(s) * math.cos(e) * np.cos(A - asp)
    return ambient + (1.0 - ambient) * np.clip(cos_i, 0.0, None) / math.sin(e)


def image_motion_mm(speed_kmh, exposure_ms, m):
    """Image motion on the photo while the shutter is open: δ = W·t/m, mm (W km/h, t ms, scale 1:m).

    The guide's §2 limits it (δ ≤ 0.1 mm, t_max = δ·M/W); here it is the blur it makes (§9, condition 7).
    """
    W = check_range("speed_kmh", speed_kmh, 0.0, 2000.0, unit="km/h") / 3.6
    t = check_range("exposure_ms", exposure_ms, 0.0, 1000.0, unit="ms") / 1000.0
    mm = check_range("m", m, 1.0, 1e7, unit="")
    return W * t / mm * 1000.0


@V.checked(image=V.image(2, 3), axis=V.whole(0, 1))
def motion_blur(image, length_px: float, axis: int = 1) -> np.ndarray:
    """Blur along ``axis`` by a uniform smear of ``length_px`` pixels (fractional; ≤ 1 px leaves it as it is).

    The image of a point moving at a constant speed during the exposure is a line of length δ: the photo is
    convolved with a box of that length (the ends weighted by the fraction), edges replicated.  Any trailing
    axes (bands) are blurred alike.
    """
    L = check_range("length_px", length_px, 0.0, 200.0, unit="px")
    img = np.asarray(image)
    if L <= 1.0:
        return img
    k = int(math.ceil(L))
    if k % 2 == 0:
        k += 1
    w = np.ones(k)
    extra = (k - L) / 2.0  # take it off both ends
    w[0] -= extra
    w[-1] -= extra
    w /= w.sum()
    from scipy.ndimage import correlate1d

    return correlate1d(img, w.astype(img.dtype if img.dtype.kind == "f" else float), axis=axis, mode="nearest")


@V.checked(rho=V.image(0, 1, 2, 3))
def haze(rho, band: str, visibility_km, H_m: float):
    """What the camera sees of ground reflectance ρ in a band through the air below it (guide §9, condition 5).

    ρ* = R + T²ρ/(1 − Rρ) with the layer of :func:`aerophoto.spectral.haze_layer` for the aerosol of visibility V
    (km) and the air below H (m), at the band's centre wavelength.  ``visibility_km=None``: no air, ρ* = ρ.
    """
    if visibility_km is None:
        return np.asarray(rho)
    wl = sp.BANDS[band].centre_um if band in sp.BANDS else None
    if wl is None:
        raise ValueError(f"band = {band!r} is not one of the bands {list(sp.BANDS)}")
    ta, tr = sp.path_optical_depth(wl, visibility_km, H_m)
    R, T = sp.haze_layer(ta, tr)
    return sp.apparent_reflectance(rho, np.float32(R), np.float32(T))


@V.checked(image=V.image(1, 2, 3))
def contrast(image, mask=None) -> float:
    """The photo's contrast: standard deviation over mean of the brightness (RMS contrast), where ``mask``."""
    a = np.asarray(image, float)
    if mask is not None:
        a = a[np.asarray(mask, bool)]
    mu = float(a.mean())
    return float(a.std() / mu) if mu > 0 else 0.0


def conditions_table() -> pd.DataFrame:
    """§9's eight conditions of photographing, with what the book's renderer does for each."""
    how = ("spectra of every class by season (snow, leaf-off, wet soil)", "sun: shadows L = h/tan e, slope shading",
           "topsoil moisture: darker, more uniform soil; water on wet meadows", "the classes' spectra (measured as RMS "
           "contrast)", "visibility V: haze brightens and lowers contrast", "α: the exact central projection",
           "δ = W·t/m: smear along the flight line", "relief shading by steepness and exposure")
    return pd.DataFrame({"condition": [c[1] for c in CONDITIONS], "Russian": [c[2] for c in CONDITIONS],
                         "in the model": how}, index=pd.Index([c[0] for c in CONDITIONS], name="§9"))

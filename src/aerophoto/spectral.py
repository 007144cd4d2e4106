"""Spectral reflectance of the land covers the book photographs: a soil model after guide §14, and typical spectra.

What a photo shows in a band is, before the camera and the air, the ground's **reflectance** ρ (коэффициент
спектральной яркости, КСЯ): the share of the sunlight falling on a surface that it sends back, 0…1, a function
of the wavelength λ.  This module holds the reflectance of everything on the virtual site (layer 2: pure functions
and data; the site maps its land cover onto it in :mod:`aerophoto.site.colour`).

Bands
-----
:data:`BANDS`: the six reflective bands of the Landsat Thematic Mapper — blue 0.45–0.52, green 0.52–0.60, red
0.63–0.69, near infrared (NIR) 0.76–0.90, short-wave infrared SWIR-1 1.55–1.75 and SWIR-2 2.08–2.35 µm — taken as
flat (boxcar) responses; a band's value is the mean of the curve over its interval (:func:`band_mean`).
:data:`CAMERAS` names sets of bands: a colour film, a colour-infrared (spectrozonal, спектрозональный) film, the
Thematic Mapper.

Soil: the model of guide §14
----------------------------
§14 gives the facts the model must reproduce; each factor below is documented with its source.

* **Shape of a dry soil's curve**: brightness rises smoothly from 0.4 to 1.6…2.0 µm and falls gently to 2.5 µm
  (§14).  ``ρ_min(λ) = ρ_p · S(λ)``, ``S = (1 − 0.72·e^{−(λ−0.4)/0.42}) · (1 − 0.35·max(0, λ − 1.9)²)`` (λ in µm),
  the "minimally altered" curve form of Stoner & Baumgardner (1981); ρ_p by parent material (:data:`PARENTS`).
  A weak clay Al–OH dip at 2.2 µm (Clark et al., 1990) and hygroscopic water (2 µm of water, below) stay even
  in air-dry soil.
* **Humus** (гумус): the integral brightness falls linearly with humus (and iron oxides) up to 5 %, then along a
  parabola; it is most sensitive in the red zone (§14).  ``ρ = ρ_min·(1 − s(λ)·g(H))`` with
  ``g(H) = H`` for H ≤ 5 % and ``g = 5 + (H−5) − (H−5)²/20`` up to 15 % (a parabola continuing the line with the
  same slope and flattening to zero slope at 15 %; constant beyond), and ``s(λ) = 0.02 + 0.055·e^{−((λ−0.66)/0.8)²}``
  per % (largest at the red band).  The sensitivities are the book's, set so that a chernozem of 8 % humus has a
  red reflectance near 0.1 and a grey forest soil of 3 % near 0.2 (the order of the curves in Stoner &
  Baumgardner, 1981).
* **Particle size** (микроструктура): brightness rises exponentially as the particles get finer, most of all below
  0.4 mm (§14, after the laboratory series of Bowers & Hanks, 1965).  ``F(d) = 1 + 0.6·e^{−d/0.13 mm}``: 95 % of
  the rise happens below 0.4 mm.  The amplitude 0.6 is the book's choice.
* **Clods** (макроструктура): coarse clods shade each other, and the more so the lower the sun (§14; Cierniewski,
  1987).  ``f = 1 − (1 − a)·min(0.5, r·cot e)`` with the clod roughness r (0 harrowed … 0.15 fresh ploughing),
  the sun's elevation e and the shadow's share of light a = 0.35.
* **Moisture** (влажность): wet soil is darker at every wavelength, because water filling the pores lowers the
  contrast of refractive indices and traps light (Ångström, 1925; Twomey, Bohren & Mergenthaler, 1986), and it has
  absorption dips at 1.45 and 1.95 µm (§14), where water itself absorbs.  Reflectance falls exponentially with
  moisture (Lobell & Asner, 2002).  ``ρ_wet = ρ_dry · [0.5 + 0.5·e^{−θ/12 %}] · e^{−2·α_w(λ)·d(θ)}``, with the
  pure-water absorption coefficient α_w (:func:`water_absorption_per_cm`: Hale & Querry, 1973, below 0.67 µm;
  Kou, Labrie & Chylek, 1993, above) and an effective water layer ``d = 2 µm + 1 µm per % of volumetric
  moisture θ`` passed twice (Beer–Lambert; the water-film idea of Bach & Mauser, 1994).  The half-darkening limit
  (Twomey et al. find wet surfaces about half as bright) and the film's 1 µm per % are the book's calibration:
  at θ = 30 % the dips are ≈ 20 % deep at 1.45 µm and ≈ 55 % at 1.93 µm, the order of laboratory curves.

Other land covers: typical spectra
----------------------------------
Vegetation, water, roads, roofs, snow… are not modelled from physics: :data:`ENDMEMBERS` holds, per band, values
typical of each material in published spectral libraries (USGS splib07, Kokaly et al., 2017; ECOSTRESS/ASTER,
Meerdink et al., 2019 and Baldridge et al., 2009; urban materials, Herold et al., 2004; mosses and bogs, Bubier
et al., 1997; snow, Wiscombe & Warren, 1980), rounded to 0.005 and reduced to band means.  They are
representative, not measurements of one sample: the same class varies by ±20–30 % in nature.  A land-cover class
of the site (:data:`COVERS`) is a **linear mixture** of end members and, where the ground shows, of the local soil
(the mixture model of Adams, Smith & Johnson, 1986), and the mixture changes with the season (:data:`SEASONS`):
summer (full leaf), autumn (dull vegetation, wet soil), spring (leaf-off, last year's grass, wet soil) and winter
(snow on the open ground, guide §9).

The air: haze
-------------
:func:`path_optical_depth` — aerosol from the meteorological visibility V by Koschmieder's law σ = 3.912/V (minus
the air's own 0.0116 km⁻¹), spread over an aerosol scale height of 1.2 km with Ångström's λ^−1.3; Rayleigh
scattering after Hansen & Travis (1974) over a scale height of 8.4 km — each counted below the aircraft only.
:func:`apparent_reflectance` — the haze below the aircraft as a non-absorbing scattering layer over a Lambertian
ground: the two-stream layer of Bohren (1987), ``R = τ'/(2 + τ')``, ``T = 1 − R`` with τ' = (1 − g)·τ (aerosol
asymmetry g = 0.7, Rayleigh g = 0), added to the ground by ``ρ* = R + T²ρ/(1 − Rρ)``.  The haze adds its own
brightness and lowers every contrast: more in blue than in the infrared.

References: :data:`SOURCES`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from . import _validate as V
from ._validate import check_range

__all__ = ["WAVELENGTHS_UM", "Band", "BANDS", "BAND_NAMES", "CAMERAS", "band_mean", "bands_of",
           "water_absorption_per_cm", "PARENTS", "dry_shape", "humus_g", "humus_sensitivity", "particle_factor",
           "clod_factor", "moisture_factor", "soil_reflectance", "soil_bands", "SoilBandTable", "soil_band_table",
           "HUMUS_LINEAR_PCT", "HUMUS_FLAT_PCT", "PARTICLE_SCALE_MM", "WATER_BANDS_UM", "ENDMEMBERS", "COVERS",
           "SEASONS", "SEASON_RU", "SEASON_MOISTURE_PCT", "mixture", "cover_bands", "rayleigh_optical_depth",
           "aerosol_optical_depth", "path_optical_depth", "haze_layer", "apparent_reflectance", "SOURCES"]

#: the wavelength grid of the curves, µm (0.40 … 2.50, step 0.01)
WAVELENGTHS_UM = np.round(np.arange(0.40, 2.5001, 0.01), 3)
WAVELENGTHS_UM.flags.writeable = False


# =========================================================================== bands
@dataclass(frozen=True)
class Band:
    """A spectral band with a flat response between ``lo_um`` and ``hi_um`` (µm)."""

    name: str
    label: str
    ru: str
    lo_um: float
    hi_um: float
    colour: str  # how the explorer draws it

    @property
    def centre_um(self) -> float:
        return 0.5 * (self.lo_um + self.hi_um)


#: the Landsat Thematic Mapper's reflective bands (TM1–TM5, TM7), as boxcars
BANDS = {
    "blue": Band("blue", "blue (TM1)", "синяя", 0.45, 0.52, "#0072B2"),
    "green": Band("green", "green (TM2)", "зелёная", 0.52, 0.60, "#009E73"),
    "red": Band("red", "red (TM3)", "красная", 0.63, 0.69, "#D55E00"),
    "nir": Band("nir", "near infrared (TM4)", "ближняя инфракрасная", 0.76, 0.90, "#CC79A7"),
    "swir1": Band("swir1", "short-wave infrared 1.6 µm (TM5)", "коротковолновая ИК 1,6 мкм", 1.55, 1.75, "#E69F00"),
    "swir2": Band("swir2", "short-wave infrared 2.2 µm (TM7)", "коротковолновая ИК 2,2 мкм", 2.08, 2.35, "#777777"),
}
BAND_NAMES = tuple(BANDS)

#: cameras (sets of bands) the spectral explorer can draw, and the bands each shows as red, green, blue
CAMERAS = {
    "colour film": ("red", "green", "blue"),
    "colour-infrared film": ("nir", "red", "green"),
    "Thematic Mapper 5-4-3": ("swir1", "nir", "red"),
    "Thematic Mapper 7-4-2": ("swir2", "nir", "green"),
}

#: where liquid water absorbs most within 0.4–2.5 µm (guide §14: 1.45 and 1.95 µm), µm
WATER_BANDS_UM = (1.45, 1.95)


def _band_index(band: str) -> int:
    if band not in BANDS:
        raise ValueError(f"band = {band!r} is not one of the bands {list(BANDS)}")
    return BAND_NAMES.index(band)


@functools.lru_cache(maxsize=8)
def _band_mask(band: str) -> np.ndarray:
    b = BANDS[band]
    m = (WAVELENGTHS_UM >= b.lo_um - 1e-9) & (WAVELENGTHS_UM <= b.hi_um + 1e-9)
    m.flags.writeable = False
    return m


@V.checked(curve=V.array(min_len=1))
def band_mean(curve, band: str) -> np.ndarray:
    """The mean of a curve on :data:`WAVELENGTHS_UM` (last axis) over a band's interval."""
    _band_index(band)
    c = np.asarray(curve, float)
    if c.shape[-1] != len(WAVELENGTHS_UM):
        raise ValueError(f"curve has {c.shape[-1]} samples; expected {len(WAVELENGTHS_UM)} (WAVELENGTHS_UM)")
    return c[..., _band_mask(band)].mean(axis=-1)


@V.checked(curve=V.array(min_len=1))
def bands_of(curve) -> np.ndarray:
    """A curve's six band means, in :data:`BAND_NAMES` order (last axis)."""
    return np.stack([band_mean(curve, b) for b in BAND_NAMES], axis=-1)


# =========================================================================== water absorption
#: absorption coefficient of pure liquid water, cm⁻¹: Hale & Querry (1973, α = 4πk/λ) to 0.65 µm,
#: Kou, Labrie & Chylek (1993) from 0.667 µm (their table read at these wavelengths)
_WATER_KNOTS = np.array([
    (0.40, 5.84e-4), (0.45, 2.85e-4), (0.50, 2.51e-4), (0.55, 4.48e-4), (0.60, 2.28e-3), (0.65, 3.17e-3),
    (0.667, 4.67e-3), (0.70, 6.68e-3), (0.719, 1.24e-2), (0.74, 2.77e-2), (0.76, 2.86e-2), (0.80, 2.25e-2),
    (0.82, 2.33e-2), (0.84, 3.95e-2), (0.90, 6.36e-2), (0.94, 0.182), (0.976, 0.487), (1.00, 0.407),
    (1.07, 0.141), (1.10, 0.193), (1.152, 1.04), (1.20, 1.27), (1.25, 1.116), (1.298, 1.297), (1.351, 3.24),
    (1.40, 16.96), (1.449, 32.70), (1.501, 21.60), (1.548, 12.18), (1.602, 7.61), (1.65, 6.16), (1.70, 5.89),
    (1.748, 7.26), (1.81, 9.16), (1.851, 11.13), (1.879, 31.77), (1.901, 98.49), (1.93, 136.73), (1.96, 115.41),
    (2.00, 77.28), (2.05, 47.65), (2.10, 28.72), (2.155, 22.33), (2.202, 20.14), (2.252, 21.20), (2.304, 26.67),
    (2.358, 37.89), (2.403, 51.46), (2.451, 71.78), (2.50, 100.53),
])


@V.checked(wl_um=V.values(0.0, 100.0, lo_open=True))
def water_absorption_per_cm(wl_um) -> np.ndarray:
    """Absorption coefficient α_w of pure liquid water at λ (µm, 0.4 ≤ λ ≤ 2.5), cm⁻¹ (log-linear between knots).

    Peaks within the range: 32.7 cm⁻¹ at 1.45 µm and 137 cm⁻¹ at 1.93 µm (guide §14's absorption bands).
    """
    wl = np.asarray(wl_um, float)
    if np.any(~np.isfinite(wl)) or np.any((wl < 0.4 - 1e-9) | (wl > 2.5 + 1e-9)):
        raise ValueError(f"wl_um = {wl_um!r} is outside the valid range 0.4 ≤ wl_um ≤ 2.5 (µm)")
    return np.exp(np.interp(wl, _WATER_KNOTS[:, 0], np.log(_WATER_KNOTS[:, 1])))


# =========================================================================== soil
#: parent materials: peak reflectance ρ_p of the dry, humus-free, coarse (d → ∞) mineral soil
PARENTS = {"loam": 0.34, "sand": 0.42, "clay": 0.30}
#: humus: linear up to this content, % (guide §14) …
HUMUS_LINEAR_PCT = 5.0
#: … then a parabola that flattens out here, % (the book's choice)
HUMUS_FLAT_PCT = 15.0
#: particle size scale d₀ of F(d) = 1 + 0.6·exp(−d/d₀), mm: 95 % of the rise below 0.4 mm (guide §14)
PARTICLE_SCALE_MM = 0.13
_PARTICLE_GAIN = 0.6
_WET_LIMIT = 0.5  # broadband darkening of saturated soil (× dry)
_WET_THETA = 12.0  # its e-folding moisture, %
_FILM_UM_PER_PCT = 1.0  # effective water layer per % of volumetric moisture, µm
_FILM_DRY_UM = 2.0  # hygroscopic water of air-dry soil, µm
_SHADOW_SHARE = 0.35  # light in a clod's shadow, as a share of full sun (the renderer's ambient light)


@V.checked(wl_um=V.values(0.0, 100.0, lo_open=True))
def dry_shape(wl_um) -> np.ndarray:
    """S(λ): the shape of a dry, humus-free mineral soil's curve (peak ≈ 1 near 1.9 µm), with the 2.2 µm clay dip."""
    wl = np.asarray(wl_um, float)
    rise = 1.0 - 0.72 * np.exp(-(wl - 0.40) / 0.42)
    fall = 1.0 - 0.35 * np.clip(wl - 1.9, 0.0, None) ** 2
    clay = 1.0 - 0.05 * np.exp(-0.5 * ((wl - 2.205) / 0.025) ** 2)
    return rise * fall * clay


@V.checked(humus_pct=V.values(0.0, 100.0))
def humus_g(humus_pct) -> np.ndarray:
    """g(H): the humus term, linear up to 5 % (guide §14), then a parabola flattening at 15 % (constant beyond)."""
    H = np.asarray(humus_pct, float)
    if np.any(~np.isfinite(H)) or np.any(H < 0) or np.any(H > 100):
        raise ValueError(f"humus_pct = {humus_pct!r} is outside the valid range 0 ≤ humus_pct ≤ 100 (%)")
    a, b = HUMUS_LINEAR_PCT, HUMUS_FLAT_PCT
    x = np.clip(H, a, b) - a
    return np.where(H <= a, H, a + x - x * x / (2.0 * (b - a)))


@V.checked(wl_um=V.values(0.0, 100.0, lo_open=True))
def humus_sensitivity(wl_um) -> np.ndarray:
    """s(λ): the fractional darkening per unit of g, largest in the red band (guide §14)."""
    wl = np.asarray(wl_um, float)
    return 0.02 + 0.055 * np.exp(-(((wl - 0.66) / 0.8) ** 2))


@V.checked(particle_mm=V.values(0.0, 1e3, lo_open=True))
def particle_factor(particle_mm) -> np.ndarray:
    """F(d) = 1 + 0.6·exp(−d/0.13 mm): brighter as the particles get finer, most below 0.4 mm (guide §14)."""
    d = np.asarray(particle_mm, float)
    if np.any(~np.isfinite(d)) or np.any(d <= 0) or np.any(d > 20):
        raise ValueError(f"particle_mm = {particle_mm!r} is outside the valid range 0 < particle_mm ≤ 20 (mm)")
    return 1.0 + _PARTICLE_GAIN * np.exp(-d / PARTICLE_SCALE_MM)


@V.checked(roughness=V.values(0.0, 1.0))
def clod_factor(roughness, sun_elevation_deg) -> np.ndarray:
    """Darkening by the clods' shadows: 1 − 0.65·min(0.5, r·cot e) (r clod roughness 0…0.3, e sun elevation, °)."""
    r = np.asarray(roughness, float)
    if np.any(~np.isfinite(r)) or np.any((r < 0) | (r > 0.3)):
        raise ValueError(f"roughness = {roughness!r} is outside the valid range 0 ≤ roughness ≤ 0.3")
    e = check_range("sun_elevation_deg", sun_elevation_deg, 1.0, 90.0, unit="degrees")
    share = np.minimum(0.5, r / math.tan(math.radians(e)))
    return 1.0 - (1.0 - _SHADOW_SHARE) * share


@V.checked(wl_um=V.values(0.0, 100.0, lo_open=True), moisture_pct=V.values(0.0, 100.0))
def moisture_factor(wl_um, moisture_pct) -> np.ndarray:
    """The factor wet/dry at λ for a volumetric moisture θ (%): broadband darkening × water-film absorption.

    ``[0.5 + 0.5·exp(−θ/12)] · exp(−2·α_w(λ)·(2 µm + 1 µm·θ))``, relative to an oven-dry soil (θ = 0).
    Broadcasts λ and θ.
    """
    th = np.asarray(moisture_pct, float)
    if np.any(~np.isfinite(th)) or np.any((th < 0) | (th > 60)):
        raise ValueError(f"moisture_pct = {moisture_pct!r} is outside the valid range 0 ≤ moisture_pct ≤ 60 (%)")
    d_cm = (_FILM_DRY_UM + _FILM_UM_PER_PCT * th) * 1e-4
    broad = _WET_LIMIT + (1.0 - _WET_LIMIT) * np.exp(-th / _WET_THETA)
    return broad * np.exp(-2.0 * water_absorption_per_cm(wl_um) * d_cm)


@V.checked(wl_um=V.optional(V.values(0.0, 100.0, lo_open=True)), roughness=V.number(0.0, 1.0))
def soil_reflectance(wl_um=None, *, moisture_pct: float = 10.0, humus_pct: float = 3.0, particle_mm: float = 0.1,
                     parent: str = "loam", roughness: float = 0.0, sun_elevation_deg: float = 45.0) -> np.ndarray:
    """The soil's reflectance curve ρ(λ) (guide §14; see the module notes).

    Parameters
    ----------
    wl_um : array_like or None
        Wavelengths, µm, 0.4…2.5 (None: :data:`WAVELENGTHS_UM`).
    moisture_pct : volumetric moisture θ of the topsoil, %, 0…60
    humus_pct : humus content H, %, 0…100 (the effect flattens above 15 %)
    particle_mm : particle (micro-aggregate) diameter d, mm, 0 < d ≤ 20
    parent : parent material, one of :data:`PARENTS`
    roughness : clod roughness r (0 harrowed … 0.15 fresh ploughing), 0…0.3
    sun_elevation_deg : the sun's elevation e, ° (only with clods)

    Returns
    -------
    ndarray, the shape of ``wl_um``: reflectance 0…1.
    """
    wl = WAVELENGTHS_UM if wl_um is None else np.asarray(wl_um, float)
    if parent not in PARENTS:
        raise ValueError(f"parent = {parent!r} is not one of the parent materials {list(PARENTS)}")
    check_range("moisture_pct", moisture_pct, 0.0, 60.0, unit="%")
    check_range("humus_pct", humus_pct, 0.0, 100.0, unit="%")
    check_range("particle_mm", particle_mm, 0.0, 20.0, lo_open=True, unit="mm")
    rho = PARENTS[parent] * dry_shape(wl) * particle_factor(particle_mm) * clod_factor(roughness, sun_elevation_deg)
    rho = rho * (1.0 - humus_sensitivity(wl) * humus_g(humus_pct)) * moisture_factor(wl, moisture_pct)
    return np.clip(rho, 0.0, 1.0)


def soil_bands(**soil) -> np.ndarray:
    """The six band means of :func:`soil_reflectance` (keywords as there), :data:`BAND_NAMES` order."""
    return bands_of(soil_reflectance(None, **soil))


@dataclass(frozen=True, eq=False)
class SoilBandTable:
    """Band values of soils for many pixels at once, exact for the model: ρ_band = P·F·C·(A₀(θ) − g·A₁(θ)).

    ``A0``, ``A1`` (bands, moisture steps) are the band means of S(λ)·m(λ, θ) and S(λ)·s(λ)·m(λ, θ) on the
    moisture grid ``theta_pct`` (0…60 %, step 0.25 %); between steps they are interpolated linearly.
    """

    theta_pct: np.ndarray
    A0: np.ndarray
    A1: np.ndarray

    def bands(self, moisture_pct, humus_pct, particle_mm, parent_peak, roughness=0.0, sun_elevation_deg=45.0,
              band_index=None) -> np.ndarray:
        """(…, k) band values for per-pixel moisture θ (%), humus H (%), particle d (mm) and parent peak ρ_p."""
        th = np.clip(np.asarray(moisture_pct, np.float32), 0.0, 60.0)
        pos = th / np.float32(self.theta_pct[1] - self.theta_pct[0])
        i0 = np.minimum(pos.astype(np.int64), len(self.theta_pct) - 2)
        w = (pos - i0).astype(np.float32)
        g = humus_g(np.clip(humus_pct, 0.0, 100.0)).astype(np.float32)
        scale = (np.asarray(parent_peak, np.float32) * particle_factor(particle_mm).astype(np.float32)
                 * clod_factor(roughness, sun_elevation_deg).astype(np.float32))
        idx = range(len(BAND_NAMES)) if band_index is None else band_index
        out = []
        for k in idx:
            a0 = self.A0[k, i0] * (1 - w) + self.A0[k, i0 + 1] * w
            a1 = self.A1[k, i0] * (1 - w) + self.A1[k, i0 + 1] * w
            out.append(scale * (a0 - g * a1))
        return np.clip(np.stack(out, axis=-1), 0.0, 1.0)


@functools.lru_cache(maxsize=1)
def soil_band_table() -> SoilBandTable:
    """The tabulated band integrals of the soil model (computed once)."""
    th = np.arange(0.0, 60.0001, 0.25)
    wl = WAVELENGTHS_UM
    m = moisture_factor(wl[None, :], th[:, None])  # (θ, λ)
    S = dry_shape(wl)
    s = humus_sensitivity(wl)
    A0 = np.stack([band_mean(S * m, b) for b in BAND_NAMES]).astype(np.float32)
    A1 = np.stack([band_mean(S * s * m, b) for b in BAND_NAMES]).astype(np.float32)
    for a in (th, A0, A1):
        a.flags.writeable = False
    return SoilBandTable(th, A0, A1)


# =========================================================================== other materials: typical spectra
#: pure materials (end members): Russian name, source, band values (blue, green, red, NIR, SWIR-1, SWIR-2)
ENDMEMBERS = {
    "deep water": ("глубокая вода", "USGS splib07", (0.050, 0.040, 0.020, 0.010, 0.005, 0.003)),
    "shallow water": ("мелководье", "USGS splib07 (water over sand)", (0.090, 0.110, 0.085, 0.030, 0.010, 0.005)),
    "green grass": ("зелёная трава", "USGS splib07 (lawn grass)", (0.040, 0.090, 0.050, 0.380, 0.240, 0.130)),
    "green crop": ("зелёные посевы", "ECOSTRESS (wheat, full cover)", (0.035, 0.080, 0.040, 0.450, 0.240, 0.120)),
    "dry grass": ("сухая трава, сено", "USGS splib07 (dry grass)", (0.080, 0.120, 0.150, 0.300, 0.340, 0.250)),
    "straw": ("солома, стерня", "ECOSTRESS (wheat straw)", (0.120, 0.170, 0.210, 0.300, 0.360, 0.280)),
    "pine crowns": ("кроны сосны", "USGS splib07 (pine, canopy)", (0.030, 0.050, 0.030, 0.220, 0.110, 0.050)),
    "spruce crowns": ("кроны ели", "USGS splib07 (spruce, canopy)", (0.020, 0.040, 0.025, 0.170, 0.080, 0.035)),
    "broadleaf crowns": ("кроны лиственных", "USGS splib07 (aspen, oak canopy)",
                         (0.035, 0.070, 0.040, 0.380, 0.190, 0.080)),
    "autumn leaves": ("осенняя листва", "ECOSTRESS (senescent leaves)", (0.040, 0.090, 0.100, 0.320, 0.240, 0.120)),
    "bare branches": ("голые ветви", "ECOSTRESS (bark, twigs)", (0.060, 0.080, 0.100, 0.170, 0.220, 0.170)),
    "shrub leaves": ("листья кустарника", "USGS splib07 (willow)", (0.040, 0.085, 0.050, 0.340, 0.200, 0.100)),
    "sphagnum": ("сфагнум", "Bubier et al. 1997", (0.040, 0.070, 0.075, 0.220, 0.140, 0.070)),
    "sedge and reed": ("осока, тростник", "Bubier et al. 1997", (0.040, 0.070, 0.050, 0.270, 0.170, 0.080)),
    "asphalt": ("асфальт", "Herold et al. 2004", (0.060, 0.070, 0.080, 0.100, 0.130, 0.130)),
    "gravel": ("гравий", "ASTER (limestone gravel)", (0.180, 0.220, 0.250, 0.300, 0.340, 0.310)),
    "dirt road": ("грунтовая дорога", "ASTER (compacted soil)", (0.140, 0.180, 0.230, 0.290, 0.360, 0.320)),
    "ballast": ("щебень балласта", "ASTER (crushed granite)", (0.100, 0.110, 0.120, 0.140, 0.160, 0.150)),
    "slate roof": ("шифер", "Herold et al. 2004 (asbestos cement)", (0.220, 0.240, 0.250, 0.270, 0.300, 0.280)),
    "red iron roof": ("крашеное железо (красное)", "Herold et al. 2004", (0.060, 0.070, 0.250, 0.350, 0.350, 0.300)),
    "felt roof": ("рубероид", "Herold et al. 2004 (tar paper)", (0.050, 0.055, 0.060, 0.070, 0.080, 0.080)),
    "wall": ("стены", "Herold et al. 2004 (plaster)", (0.300, 0.320, 0.330, 0.380, 0.420, 0.380)),
    "concrete": ("бетон", "Herold et al. 2004", (0.220, 0.250, 0.270, 0.320, 0.360, 0.330)),
    "dry sand": ("сухой песок", "USGS splib07 (quartz sand)", (0.200, 0.260, 0.320, 0.400, 0.480, 0.420)),
    "snow": ("снег", "Wiscombe & Warren 1980 (fresh, 0.1 mm grains)", (0.950, 0.950, 0.940, 0.850, 0.120, 0.060)),
    "old snow": ("старый снег, лёд", "Wiscombe & Warren 1980 (1 mm grains)", (0.850, 0.850, 0.820, 0.650, 0.060, 0.030)),
}

#: the seasons of the photos (guide §9, condition 1), their Russian names and the topsoil's extra moisture, %
SEASONS = ("summer", "autumn", "spring", "winter")
SEASON_RU = {"summer": "лето", "autumn": "осень", "spring": "весна (без листвы)", "winter": "зима (снег)"}
SEASON_MOISTURE_PCT = {"summer": 0.0, "autumn": 8.0, "spring": 12.0, "winter": 12.0}

_M = dict  # a mixture: end member (or "soil") → fraction

#: the land-cover classes: Russian name, and per season the mixture of end members and the local "soil"
COVERS = {
    "deep water": ("глубокая вода", {"summer": _M(**{"deep water": 1}), "winter": _M(**{"old snow": 1})}),
    "shallow water": ("мелководье", {"summer": _M(**{"shallow water": 1}), "winter": _M(**{"old snow": 1})}),
    "sand bank": ("отмель, песок", {"summer": _M(**{"dry sand": 1}), "winter": _M(snow=1)}),
    "ploughed field": ("пашня (зябь)", {"summer": _M(soil=1), "winter": _M(snow=1)}),
    "crop": ("посевы", {"summer": _M(**{"green crop": 0.9, "soil": 0.1}),
                        "autumn": _M(**{"green crop": 0.35, "soil": 0.65}),
                        "spring": _M(**{"green crop": 0.25, "soil": 0.75}), "winter": _M(snow=1)}),
    "stubble": ("стерня", {"summer": _M(straw=0.75, soil=0.25), "autumn": _M(straw=0.6, soil=0.4),
                           "spring": _M(soil=1), "winter": _M(snow=1)}),
    "fallow": ("залежь, пар", {"summer": _M(**{"green grass": 0.45, "dry grass": 0.15, "soil": 0.4}),
                               "autumn": _M(**{"dry grass": 0.5, "soil": 0.5}),
                               "spring": _M(**{"dry grass": 0.4, "soil": 0.6}), "winter": _M(snow=1)}),
    "meadow": ("луг", {"summer": _M(**{"green grass": 0.95, "dry grass": 0.05}),
                       "autumn": _M(**{"green grass": 0.4, "dry grass": 0.6}),
                       "spring": _M(**{"dry grass": 0.7, "green grass": 0.2, "soil": 0.1}), "winter": _M(snow=1)}),
    "mown meadow": ("скошенный луг", {"summer": _M(**{"dry grass": 0.55, "green grass": 0.45}),
                                      "autumn": _M(**{"dry grass": 0.7, "green grass": 0.3}),
                                      "spring": _M(**{"dry grass": 0.8, "soil": 0.2}), "winter": _M(snow=1)}),
    "wet meadow": ("сырой луг", {"summer": _M(**{"green grass": 0.75, "shallow water": 0.25}),
                                 "autumn": _M(**{"dry grass": 0.45, "green grass": 0.25, "shallow water": 0.3}),
                                 "spring": _M(**{"dry grass": 0.6, "shallow water": 0.4}),
                                 "winter": _M(snow=1)}),
    "haystack": ("стог сена", {"summer": _M(**{"dry grass": 1}), "winter": _M(**{"snow": 0.7, "dry grass": 0.3})}),
    "pine forest": ("сосновый лес", {"summer": _M(**{"pine crowns": 1}),
                                     "winter": _M(**{"pine crowns": 0.8, "snow": 0.2})}),
    "spruce forest": ("еловый лес", {"summer": _M(**{"spruce crowns": 1}),
                                     "winter": _M(**{"spruce crowns": 0.85, "snow": 0.15})}),
    "deciduous forest": ("лиственный лес", {"summer": _M(**{"broadleaf crowns": 1}),
                                            "autumn": _M(**{"autumn leaves": 1}),
                                            "spring": _M(**{"bare branches": 0.6, "dry grass": 0.4}),
                                            "winter": _M(**{"bare branches": 0.45, "snow": 0.55})}),
    "shrub": ("кустарник", {"summer": _M(**{"shrub leaves": 0.85, "green grass": 0.15}),
                            "autumn": _M(**{"autumn leaves": 0.8, "dry grass": 0.2}),
                            "spring": _M(**{"bare branches": 0.5, "dry grass": 0.5}),
                            "winter": _M(**{"bare branches": 0.35, "snow": 0.65})}),
    "raised bog": ("верховое болото", {"summer": _M(**{"sphagnum": 0.85, "shallow water": 0.15}),
                                       "autumn": _M(**{"sphagnum": 0.8, "shallow water": 0.2}),
                                       "spring": _M(**{"sphagnum": 0.7, "shallow water": 0.3}),
                                       "winter": _M(snow=1)}),
    "low bog": ("низинное болото", {"summer": _M(**{"sedge and reed": 0.8, "shallow water": 0.2}),
                                    "autumn": _M(**{"dry grass": 0.6, "shallow water": 0.4}),
                                    "spring": _M(**{"dry grass": 0.55, "shallow water": 0.45}),
                                    "winter": _M(snow=1)}),
    "asphalt road": ("асфальтовая дорога", {"summer": _M(asphalt=1), "winter": _M(asphalt=0.6, snow=0.4)}),
    "gravel road": ("гравийная дорога", {"summer": _M(gravel=1), "winter": _M(snow=1)}),
    "dirt road": ("грунтовая дорога", {"summer": _M(**{"dirt road": 1}), "autumn": _M(**{"dirt road": 0.5, "soil": 0.5}),
                                       "spring": _M(**{"dirt road": 0.4, "soil": 0.6}), "winter": _M(snow=1)}),
    "railway": ("железная дорога", {"summer": _M(ballast=1), "winter": _M(ballast=0.5, snow=0.5)}),
    "ditch": ("кювет", {"summer": _M(**{"green grass": 0.7, "shallow water": 0.3}),
                        "autumn": _M(**{"dry grass": 0.5, "shallow water": 0.5}),
                        "spring": _M(**{"dry grass": 0.4, "shallow water": 0.6}), "winter": _M(snow=1)}),
    "dam": ("плотина", {"summer": _M(**{"green grass": 0.6, "dirt road": 0.4}), "winter": _M(snow=1)}),
    "garden": ("сад, огород", {"summer": _M(**{"shrub leaves": 0.5, "green grass": 0.2, "soil": 0.3}),
                               "autumn": _M(**{"autumn leaves": 0.4, "soil": 0.6}),
                               "spring": _M(**{"bare branches": 0.3, "soil": 0.7}),
                               "winter": _M(**{"bare branches": 0.2, "snow": 0.8})}),
    "slate roof": ("шиферная крыша", {"summer": _M(**{"slate roof": 1}), "winter": _M(snow=1)}),
    "red iron roof": ("железная крыша", {"summer": _M(**{"red iron roof": 1}), "winter": _M(snow=0.8, **{"red iron roof": 0.2})}),
    "flat roof": ("плоская крыша", {"summer": _M(**{"felt roof": 1}), "winter": _M(snow=1)}),
    "wall": ("стена", {"summer": _M(wall=1)}),
    "structure": ("сооружение", {"summer": _M(concrete=1)}),
}


def mixture(cover: str, season: str = "summer") -> dict:
    """The end members (and ``"soil"``) of a land-cover class in a season, with their fractions (summing to 1).

    A season the class does not list falls back to summer (a road or a wall does not change in autumn).
    """
    if cover not in COVERS:
        raise ValueError(f"cover = {cover!r} is not one of the land-cover classes {list(COVERS)}")
    if season not in SEASONS:
        raise ValueError(f"season = {season!r} is not one of the seasons {list(SEASONS)}")
    table = COVERS[cover][1]
    return dict(table.get(season, table["summer"]))


def cover_bands(cover: str, season: str = "summer", soil=None) -> np.ndarray:
    """The six band values of a class in a season: Σ fraction × end member (``soil``: the local soil's six bands).

    A class that shows soil needs ``soil`` (e.g. :func:`soil_bands`); (6,) array, :data:`BAND_NAMES` order.
    """
    out = np.zeros(len(BAND_NAMES))
    for name, f in mixture(cover, season).items():
        if name == "soil":
            if soil is None:
                raise ValueError(f"cover = {cover!r} shows the soil in {season}: give soil = its six band values")
            out += f * np.asarray(soil, float)
        else:
            out += f * np.asarray(ENDMEMBERS[name][2], float)
    return out


# =========================================================================== the air
_KOSCHMIEDER = 3.912  # contrast threshold 2 %: V = 3.912/σ
_RAYLEIGH_550_PER_KM = 0.0116  # the clean air's own extinction at sea level, km⁻¹
AEROSOL_SCALE_HEIGHT_KM = 1.2
RAYLEIGH_SCALE_HEIGHT_KM = 8.4
ANGSTROM_EXPONENT = 1.3
AEROSOL_ASYMMETRY = 0.7


@V.checked(wl_um=V.values(0.0, 100.0, lo_open=True))
def rayleigh_optical_depth(wl_um) -> np.ndarray:
    """τ_R(λ) of the whole atmosphere (Hansen & Travis, 1974): 0.008569·λ⁻⁴·(1 + 0.0113·λ⁻² + 0.00013·λ⁻⁴), λ µm."""
    wl = np.asarray(wl_um, float)
    return 0.008569 * wl**-4 * (1.0 + 0.0113 * wl**-2 + 0.00013 * wl**-4)


@V.checked(wl_um=V.values(0.0, 100.0, lo_open=True))
def aerosol_optical_depth(wl_um, visibility_km: float) -> np.ndarray:
    """τ_a(λ) of the whole aerosol layer for a meteorological visibility V (km, 1…100).

    Koschmieder's law σ = 3.912/V at 0.55 µm (less the clean air's 0.0116 km⁻¹), over a scale height of
    1.2 km, with Ångström's λ^−1.3.
    """
    V = check_range("visibility_km", visibility_km, 1.0, 100.0, unit="km")
    sigma = max(_KOSCHMIEDER / V - _RAYLEIGH_550_PER_KM, 0.0)
    return sigma * AEROSOL_SCALE_HEIGHT_KM * (np.asarray(wl_um, float) / 0.55) ** -ANGSTROM_EXPONENT


@V.checked(wl_um=V.values(0.0, 100.0, lo_open=True))
def path_optical_depth(wl_um, visibility_km: float, H_m: float) -> tuple:
    """(τ_aerosol, τ_Rayleigh) of the air below an aircraft H metres above the ground (0 < H ≤ 20 000 m)."""
    H = check_range("H_m", H_m, 0.0, 20000.0, lo_open=True, unit="m") / 1000.0
    ta = aerosol_optical_depth(wl_um, visibility_km) * (1.0 - math.exp(-H / AEROSOL_SCALE_HEIGHT_KM))
    tr = rayleigh_optical_depth(wl_um) * (1.0 - math.exp(-H / RAYLEIGH_SCALE_HEIGHT_KM))
    return ta, tr


@V.checked(tau_aerosol=V.values(0.0), tau_rayleigh=V.values(0.0))
def haze_layer(tau_aerosol, tau_rayleigh) -> tuple:
    """(R, T): reflectance and transmittance of the non-absorbing haze layer, two-stream (Bohren, 1987).

    ``τ' = (1 − g)·τ_a + τ_R`` (g = 0.7 for the aerosol, 0 for the air), ``R = τ'/(2 + τ')``, ``T = 1 − R``.
    """
    V.check_broadcast(tau_aerosol=tau_aerosol, tau_rayleigh=tau_rayleigh)
    ts = (1.0 - AEROSOL_ASYMMETRY) * np.asarray(tau_aerosol, float) + np.asarray(tau_rayleigh, float)
    R = ts / (2.0 + ts)
    return R, 1.0 - R


@V.checked(rho=V.image(0, 1, 2, 3), R=V.values(0.0, 1.0, hi_open=True), T=V.values(0.0, 1.0))
def apparent_reflectance(rho, R, T) -> np.ndarray:
    """What the camera sees of a ground of reflectance ρ under a layer (R, T): ρ* = R + T²ρ/(1 − Rρ)."""
    V.check_broadcast(rho=rho, R=R, T=T)
    rho = np.asarray(rho)
    return R + T * T * rho / (1.0 - R * rho)


#: the spectral model's sources (the closing notes of chapters 08 and 13 list them)
SOURCES = (
    "Presnyakov V.V., Tyuklenkova E.P. Photogrammetry: course-design guide. Penza, 2014 — §9, §14 (the facts the "
    "soil model reproduces; the conditions of photographing).",
    "Stoner E.R., Baumgardner M.F. Characteristic variations in reflectance of surface soils. Soil Science Society "
    "of America Journal 45 (1981) 1161–1165 — the shapes of soil curves.",
    "Bowers S.A., Hanks R.J. Reflection of radiant energy from soils. Soil Science 100 (1965) 130–138 — moisture, "
    "organic matter and particle size; the exponential rise below 0.4 mm.",
    "Cierniewski J. A model for soil surface roughness influence on the spectral response of bare soils in the "
    "visible and near-infrared range. Remote Sensing of Environment 23 (1987) 97–115 — clods and the sun.",
    "Ångström A. The albedo of various surfaces of ground. Geografiska Annaler 7 (1925) 323–342; Twomey S.A., "
    "Bohren C.F., Mergenthaler J.L. Reflectance and albedo differences between wet and dry surfaces. Applied Optics "
    "25 (1986) 431–437 — why wet soil is darker.",
    "Lobell D.B., Asner G.P. Moisture effects on soil reflectance. Soil Science Society of America Journal 66 "
    "(2002) 722–727 — the exponential fall with moisture, stronger in the SWIR.",
    "Bach H., Mauser W. Modelling and model verification of the spectral reflectance of soils under varying "
    "moisture conditions. Proc. IGARSS'94, 2354–2356 — the water film in Beer's law.",
    "Hale G.M., Querry M.R. Optical constants of water in the 200-nm to 200-µm wavelength region. Applied Optics 12 "
    "(1973) 555–563; Kou L., Labrie D., Chylek P. Refractive indices of water and ice in the 0.65–2.5 µm spectral "
    "range. Applied Optics 32 (1993) 3531–3540 — water's absorption at 1.45 and 1.93 µm.",
    "Clark R.N., King T.V.V., Klejwa M., Swayze G.A., Vergo N. High spectral resolution reflectance spectroscopy of "
    "minerals. Journal of Geophysical Research 95 (B8) (1990) 12653–12680 — the clay dip at 2.2 µm.",
    "Kokaly R.F. et al. USGS Spectral Library Version 7. U.S. Geological Survey Data Series 1035 (2017); Meerdink "
    "S.K. et al. The ECOSTRESS spectral library version 1.0. Remote Sensing of Environment 230 (2019) 111196; "
    "Baldridge A.M. et al. The ASTER spectral library version 2.0. Remote Sensing of Environment 113 (2009) "
    "711–715 — vegetation, water, minerals and man-made materials.",
    "Herold M., Roberts D.A., Gardner M.E., Dennison P.E. Spectrometry for urban area remote sensing. Remote "
    "Sensing of Environment 91 (2004) 304–319 — asphalt, roofs, walls.",
    "Bubier J.L., Rock B.N., Crill P.M. Spectral reflectance measurements of boreal wetland and forest mosses. "
    "Journal of Geophysical Research 102 (D24) (1997) 29483–29494 — bogs.",
    "Wiscombe W.J., Warren S.G. A model for the spectral albedo of snow. I: Pure snow. Journal of the Atmospheric "
    "Sciences 37 (1980) 2712–2733 — snow.",
    "Adams J.B., Smith M.O., Johnson P.E. Spectral mixture modeling: a new analysis of rock and soil types at the "
    "Viking Lander 1 site. Journal of Geophysical Research 91 (B8) (1986) 8098–8112 — linear mixtures.",
    "Koschmieder H. Theorie der horizontalen Sichtweite. Beiträge zur Physik der freien Atmosphäre 12 (1924) 33–53; "
    "Ångström A. On the atmospheric transmission of sun radiation and on dust in the air. Geografiska Annaler 11 "
    "(1929) 156–166; Hansen J.E., Travis L.D. Light scattering in planetary atmospheres. Space Science Reviews 16 "
    "(1974) 527–610; Bohren C.F. Multiple scattering of light and some of its observable consequences. American "
    "Journal of Physics 55 (1987) 524–533 — haze.",
    "Schowengerdt R.A. Remote sensing: models and methods for image processing (Russian ed. Moscow, Technosphera, "
    "2010) — the guide's reference [10] on spectral signatures and band composites.",
)

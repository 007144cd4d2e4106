"""The spectral explorer: a soil's reflectance curve under a camera's bands, and a patch of the site (chapter 13).

The pure part, :func:`explore`, computes for one topsoil (moisture θ, humus H, particle size d, clods and the
sun) its reflectance curve ρ(λ) (:func:`aerophoto.spectral.soil_reflectance`, guide §14), the same soil dried,
the band values of a camera, and the band composite of a patch of the site whose soil cover
(:func:`aerophoto.site.soils.soil_layer`) is moved the same way — wetter, more humus, finer, as a different
day or a different field would be.  :class:`SpectralView` draws it (curve and bands left, the patch right);
:class:`SpectralExplorerDemo` binds the sliders.  :func:`plot_soil_facts` reproduces guide §14's statements from
the model (a static figure), :func:`plot_patch` shows a student's patch and its survey map.

The demo opens on variant 00's patch (tasks 13.2–13.3 of the guide's example) with a leached chernozem's
typical topsoil; the patch's own cells keep their differences (the sliders set the chernozem's values, every
other cell shifts with it).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.collections import LineCollection

from .. import plots, spectral
from ..blit import nearest_pixels
from ..i18n import t
from ..widgets import LiveDemo, Param

__all__ = ["REFERENCE", "ExplorerResult", "explore", "SpectralView", "SpectralExplorerDemo", "plot_soil_facts",
           "plot_soil_map", "plot_patch", "demo_patch", "overlay_figure", "OVERLAY_EXTENT_M"]

#: the soil the sliders start from: the leached chernozem of the site (aerophoto.site.soils, class 0)
REFERENCE = {"moisture_pct": 18.0, "humus_pct": 7.5, "particle_mm": 1.0}
CAMERA_NAMES = tuple(spectral.CAMERAS)


@functools.lru_cache(maxsize=1)
def demo_patch():
    """Variant 00's soil patch (the layer of task 13.3's patch), built once."""
    from ..site.soils import soil_layer
    from ..labs import ch13
    from ..variants import variant_for_index

    p = ch13.patch_of(variant_for_index(0))
    return soil_layer(extent_m=p.extent_m, spacing_m=p.spacing_m)


@functools.lru_cache(maxsize=8)
def _stretch(camera: str) -> float:
    """The composite's white point for a camera: the brightest band value of the patch on the reference day."""
    return float(demo_patch().bands(spectral.CAMERAS[camera]).max())


@dataclass(frozen=True)
class ExplorerResult:
    """One state of the explorer.

    Attributes
    ----------
    soil : the topsoil's keywords of :func:`aerophoto.spectral.soil_reflectance`
    camera : a name of :data:`aerophoto.spectral.CAMERAS`
    curve, dry_curve : (211,) reflectance on :data:`aerophoto.spectral.WAVELENGTHS_UM`, and with θ = 0
    bands, dry_bands : (6,) band means (:data:`aerophoto.spectral.BAND_NAMES` order)
    composite : (ny, nx, 3) the patch's composite in the camera's bands, 0…1
    extent_km : (X0, X1, Y0, Y1) of the patch, km
    """

    soil: dict
    camera: str
    curve: np.ndarray
    dry_curve: np.ndarray
    bands: np.ndarray
    dry_bands: np.ndarray
    composite: np.ndarray
    extent_km: tuple

    def table(self) -> pd.DataFrame:
        shown = spectral.CAMERAS[self.camera]
        rows = []
        for k, name in enumerate(spectral.BAND_NAMES):
            rows.append((name, self.bands[k], self.dry_bands[k], 100.0 * self.bands[k] / self.dry_bands[k],
                         "RGB"[shown.index(name)] if name in shown else ""))
        return pd.DataFrame(rows, columns=["band", "ρ", "ρ dry", "wet/dry, %", "as"]).set_index("band")


def explore(moisture_pct: float = 18.0, humus_pct: float = 7.5, particle_mm: float = 1.0,
            sun_elevation_deg: float = 45.0, roughness: float = 0.05,
            camera: str = "colour-infrared film", patch=None) -> ExplorerResult:
    """The curve, band values and the patch's composite for one topsoil (see the module notes).

    ``patch``: a :class:`aerophoto.site.soils.SoilLayer` (None: :func:`demo_patch`).  The patch moves by
    θ − 18 %, H/7.5 % and d/1 mm from its own cells' values (the :data:`REFERENCE` chernozem's).
    """
    if camera not in spectral.CAMERAS:
        raise ValueError(f"camera = {camera!r} is not one of the cameras {list(spectral.CAMERAS)}")
    soil = dict(moisture_pct=moisture_pct, humus_pct=humus_pct, particle_mm=particle_mm, roughness=roughness,
                sun_elevation_deg=sun_elevation_deg)
    curve = spectral.soil_reflectance(None, **soil)
    dry = spectral.soil_reflectance(None, **{**soil, "moisture_pct": 0.0})
    layer = demo_patch() if patch is None else patch
    comp = layer.composite(camera, hi=_stretch(camera) if patch is None else None,
                           moisture_shift_pct=moisture_pct - REFERENCE["moisture_pct"],
                           humus_scale=humus_pct / REFERENCE["humus_pct"],
                           particle_scale=particle_mm / REFERENCE["particle_mm"], roughness=roughness,
                           sun_elevation_deg=sun_elevation_deg)
    X0, X1, Y0, Y1 = layer.extent_m
    return ExplorerResult(soil, camera, curve, dry, spectral.bands_of(curve), spectral.bands_of(dry), comp,
                          (X0 / 1000, X1 / 1000, Y0 / 1000, Y1 / 1000))


class SpectralView:
    """Reflectance curve with the camera's bands (left) and the patch's composite (right); ``update`` moves them."""

    def __init__(self, result: ExplorerResult | None = None, ax=None):
        fig, (ax_curve, ax_img) = plots.panels(ax, 2, figsize=(8.9, 4.1), width_ratios=(1.3, 1))
        self.fig, self.ax_curve, self.ax_img = fig, ax_curve, ax_img
        C = plots.COLORS
        a = ax_curve
        a.set_title("Soil reflectance ρ(λ) (КСЯ), guide §14", fontsize=12)
        a.set_xlabel("wavelength λ, µm")
        a.set_ylabel("reflectance ρ")
        a.set_xlim(0.4, 2.5)
        a.set_ylim(0.0, 0.6)
        self.spans = {}
        for name, b in spectral.BANDS.items():
            self.spans[name] = a.axvspan(b.lo_um, b.hi_um, color=b.colour, alpha=0.18, lw=0)
        for wl in spectral.WATER_BANDS_UM:
            a.axvline(wl, color=C["grey"], ls=":", lw=1)
        a.text(1.45, 0.57, "1.45", ha="center", fontsize=10, color=C["grey"])
        a.text(1.95, 0.57, "1.95 µm", ha="center", fontsize=10, color=C["grey"])
        wl = spectral.WAVELENGTHS_UM
        (self.dry,) = a.plot(wl, np.zeros_like(wl), ls="--", color=C["orange"], lw=1.5,
                             label="the same soil dry (θ = 0)")
        (self.curve,) = a.plot(wl, np.zeros_like(wl), color=C["black"], lw=2.2, label="the soil, ρ(λ)")
        self.levels = LineCollection([], colors=C["vermillion"], linewidths=4, label="band values (camera's bands)")
        a.add_collection(self.levels)
        a.legend(loc="upper left", fontsize=9)
        p = ax_img
        p.set_title("Patch of the site, bare soil")
        p.set_xlabel("X, km")
        p.set_ylabel("Y, km")
        p.grid(False)
        self.img = nearest_pixels(p.imshow(np.zeros((2, 2, 3)), origin="lower", interpolation="nearest"))
        if result is not None:
            self.update(result)

    def update(self, r: ExplorerResult) -> None:
        self.curve.set_ydata(r.curve)
        self.dry.set_ydata(r.dry_curve)
        shown = spectral.CAMERAS[r.camera]
        segs = []
        for k, name in enumerate(spectral.BAND_NAMES):
            on = name in shown
            self.spans[name].set_alpha(0.30 if on else 0.06)
            if on:
                b = spectral.BANDS[name]
                segs.append([(b.lo_um, r.bands[k]), (b.hi_um, r.bands[k])])
        self.levels.set_segments(segs)
        self.img.set_data(r.composite)
        if tuple(self.img.get_extent()) != tuple(r.extent_km):  # same patch: the axes (and their ticks) stay
            self.img.set_extent(r.extent_km)
        if r.camera != getattr(self, "_camera", None):  # a new title only with a new camera
            self._camera = r.camera
            self.ax_img.set_title(t("Patch: {bands} as RGB", bands="-".join(t(b.upper()) for b in shown)), fontsize=12)


class SpectralExplorerDemo(LiveDemo):
    """Live spectral explorer: moisture, humus, particle size, clods and the sun against a soil's curve.

    It opens on the guide's example (variant 00's patch) with the site's leached chernozem; the student's own
    patch is theirs to photograph in the task.
    """

    photo_frames = True  # a move changes the photo: its frames go as JPEG (plots.fast_frames; issue 32)
    title = "Spectral explorer: what moisture, humus and particle size do to a soil's reflectance"
    hint = ("Wet the soil (θ) and watch the dips at 1.45 and 1.95 µm deepen while every band darkens; add humus "
            "(the red band reacts most, and little beyond 5 %); make the particles finer than 0.4 mm.")
    params = (
        Param("moisture_pct", "θ (moisture), %", 0, 50, 1, REFERENCE["moisture_pct"], group="Soil",
              help="volumetric moisture of the topsoil"),
        Param("humus_pct", "H (humus), %", 0, 15, 0.5, REFERENCE["humus_pct"], group="Soil",
              help="humus content of the topsoil"),
        Param("particle_mm", "d (particle size), mm", 0.02, 2.0, 0.02, REFERENCE["particle_mm"], group="Soil",
              help="diameter of the particles (aggregates)"),
        Param("roughness", "r (clods)", 0.0, 0.15, 0.01, 0.05, group="Surface",
              help="clod roughness: 0 harrowed … 0.15 fresh ploughing"),
        Param("sun_elevation_deg", "e (sun elevation), °", 10, 90, 1, 45, group="Surface",
              help="the sun's elevation above the horizon (it matters through the clods' shadows)"),
        Param("camera", "camera", kind="choice", options=CAMERA_NAMES, default="colour-infrared film",
              group="Camera", help="which bands are shown as red, green and blue"),
    )

    def build(self):
        self.view = SpectralView()
        self.fig = self.view.fig
        # a move redraws the band spans, the curves and the composite; axes, ticks and titles stay cached
        self.animated = (*self.view.spans.values(), self.view.img)

    def compute(self, **v):
        return explore(**v)

    def render(self, result):
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="The soil in the bands",
                                            float_format="{:.3g}")


# --------------------------------------------------------------------------- static figures
def plot_soil_facts(ax=None):
    """Guide §14's statements reproduced from the model: four panels (curves by moisture, humus, particle
    size, and the depth of the water dips).  Returns the figure."""
    C = plots.COLORS
    if ax is None:
        fig = plots.figure(figsize=(10.4, 7.0))
        axes = fig.subplots(2, 2).ravel()
    else:
        axes = np.ravel(ax)
        fig = axes[0].figure
    wl = spectral.WAVELENGTHS_UM
    a = axes[0]
    for th, col in zip((0, 10, 20, 30, 40), ("#E69F00", "#56B4E9", "#009E73", "#0072B2", "#000000")):
        a.plot(wl, spectral.soil_reflectance(moisture_pct=th, humus_pct=3.0), color=col, label=f"θ = {th} %")
    for w in spectral.WATER_BANDS_UM:
        a.axvline(w, color=C["grey"], ls=":", lw=1)
    a.set(title="Moisture: darker everywhere, dips at 1.45 and 1.95 µm", xlabel="λ, µm", ylabel="ρ")
    a.legend(fontsize=9)
    a = axes[1]
    H = np.linspace(0, 15, 151)
    red = np.array([spectral.soil_bands(humus_pct=h, moisture_pct=10.0)[2] for h in H])
    nir = np.array([spectral.soil_bands(humus_pct=h, moisture_pct=10.0)[3] for h in H])
    a.plot(H, red, color=C["vermillion"], label="red band")
    a.plot(H, nir, color=C["purple"], label="near infrared")
    a.axvline(5.0, color=C["grey"], ls=":", lw=1)
    a.set(title="Humus: linear to 5 %, then flattening", xlabel="humus H, %", ylabel="ρ in the band")
    a.legend(fontsize=9)
    a = axes[2]
    d = np.linspace(0.02, 2.0, 100)
    a.plot(d, [spectral.soil_bands(particle_mm=x)[2] for x in d], color=C["vermillion"], label="red band")
    a.axvline(0.4, color=C["grey"], ls=":", lw=1)
    a.set(title="Particles: brighter as finer, most below 0.4 mm", xlabel="particle size d, mm",
          ylabel="ρ in the band")
    a.legend(fontsize=9)
    a = axes[3]
    th = np.linspace(0, 50, 51)
    for w, col in zip((1.45, 1.93), (C["blue"], C["black"])):
        ratio = [spectral.soil_reflectance([w], moisture_pct=t)[0] / spectral.soil_reflectance([w], moisture_pct=0)[0]
                 for t in th]
        a.plot(th, 100 * np.array(ratio), color=col, label=f"at {w} µm")
    a.plot(th, 100 * np.array([spectral.soil_reflectance([1.25], moisture_pct=t)[0]
                               / spectral.soil_reflectance([1.25], moisture_pct=0)[0] for t in th]),
           color=C["orange"], ls="--", label="at 1.25 µm (no dip)")
    a.set(title="What is left of the dry brightness", xlabel="moisture θ, %", ylabel="wet / dry, %")
    a.legend(fontsize=9)
    return fig


def plot_patch(patch, ax=None):
    """A student's patch (:class:`aerophoto.labs.ch13.Patch`): its composite and the survey's soil map."""
    from matplotlib.colors import ListedColormap

    from ..site.soils import SOIL_CLASSES

    if ax is None:
        fig = plots.figure(figsize=(10.4, 4.6))
        ax = fig.subplots(1, 2)
    a, b = ax
    fig = a.figure
    X0, X1, Y0, Y1 = (e / 1000 for e in patch.extent_m)
    a.imshow(patch.composite, origin="lower", extent=(X0, X1, Y0, Y1), interpolation="nearest")
    a.set(title="Your patch, colour infrared (bare soil)", xlabel="X, km", ylabel="Y, km")
    a.grid(False)
    cmap = ListedColormap([c.colour for c in SOIL_CLASSES.values()])
    b.imshow(patch.soil_map, origin="lower", extent=(X0, X1, Y0, Y1), cmap=cmap, vmin=-0.5,
             vmax=len(SOIL_CLASSES) - 0.5, interpolation="nearest")
    r, c = patch.pit
    s = patch.spacing_m / 1000
    for axx in (a, b):
        axx.plot([X0 + (c + 0.5) * s], [Y0 + (r + 0.5) * s], marker="x", color="white", ms=10, mew=3)
        axx.plot([X0 + (c + 0.5) * s], [Y0 + (r + 0.5) * s], marker="x", color="black", ms=8, mew=1.5)
    b.set(title="Field survey: the soil map", xlabel="X, km")
    b.grid(False)
    from matplotlib.patches import Patch as _P

    fig.legend(handles=[_P(color=cl.colour, label=f"{cl.name} ({cl.ru})") for cl in SOIL_CLASSES.values()],
               fontsize=9, loc="outside lower center", ncol=2)
    return fig


def plot_soil_map(layer=None, ax=None):
    """The soil classes of a :class:`aerophoto.site.soils.SoilLayer` (default: the whole site) as a map."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch as _P

    from ..site.soils import SOIL_CLASSES, soil_layer

    layer = soil_layer() if layer is None else layer
    if ax is None:
        fig = plots.figure(figsize=(10.4, 5.2))
        ax = fig.add_subplot(1, 1, 1)
    X0, X1, Y0, Y1 = (e / 1000 for e in layer.extent_m)
    cmap = ListedColormap([c.colour for c in SOIL_CLASSES.values()])
    ax.imshow(layer.code, origin="lower", extent=(X0, X1, Y0, Y1), cmap=cmap, vmin=-0.5,
              vmax=len(SOIL_CLASSES) - 0.5, interpolation="nearest")
    ax.set(title="The site's soil cover (the truth a field survey would find)", xlabel="X (east), km",
           ylabel="Y (north), km")
    ax.grid(False)
    ax.figure.legend(handles=[_P(color=c.colour, label=f"{c.name} ({c.ru})") for c in SOIL_CLASSES.values()],
                     fontsize=9, loc="outside lower center", ncol=2)
    return ax.figure


#: the overlay figure's example area: 1.6 km square of the site (X0, X1, Y0, Y1, m) — forest, floodplain, slopes
#: and hollows, on no student's patch exactly (the patches are chapter 13's tasks)
OVERLAY_EXTENT_M = (2000.0, 3600.0, 2300.0, 3900.0)
#: the sheets' colours (Okabe–Ito): tone, relief, vegetation and land use
_SHEET_COLOURS = ("#E69F00", "#0072B2", "#009E73")


def _outline(ax, labels, extent, colour, lw=1.2, sure=None):
    """Draw the boundaries of a map of areas as contour lines (solid; dashed where ``sure`` is False)."""
    X0, X1, Y0, Y1 = extent
    ny, nx = labels.shape
    xs = np.linspace(X0, X1, nx)
    ys = np.linspace(Y0, Y1, ny)
    for k in np.unique(labels):
        style = "solid" if sure is None or sure[k] else (0, (3, 2))
        ax.contour(xs, ys, (labels == k).astype(float), levels=[0.5], colors=[colour], linewidths=lw,
                   linestyles=[style])


def overlay_figure(layer=None, *, k: int = 4, ax=None):
    """The overlay technique of guide §14 (the Delft training centre's method) on a patch of the site's bare soil.

    Three transparent sheets over the colour-infrared photo: (1) the areas of one tone
    (:func:`aerophoto.soilmap.segment_tones`, ``k`` areas of the photo smoothed over two cells), (2) the relief — level ground, slopes, hollows — and
    (3) the vegetation and land use (:func:`aerophoto.site.soils.key_sheets`), each in its own colour; then the
    sheets laid together (:func:`aerophoto.soilmap.overlay`): the candidate soil contours, solid where the keys
    agree and dashed where they do not; and last the field survey's soil map with the same contours.
    ``layer`` a :class:`aerophoto.site.soils.SoilLayer` (default: :data:`OVERLAY_EXTENT_M` at 10 m cells);
    ``ax`` six Axes (2 × 3) or None.
    """
    from matplotlib.colors import ListedColormap

    from .. import soilmap
    from ..site.soils import COVER_SHEET, RELIEF_SHEET, SOIL_CLASSES, key_sheets, soil_layer

    layer = soil_layer(extent_m=OVERLAY_EXTENT_M, spacing_m=10.0) if layer is None else layer
    if ax is None:
        fig = plots.figure(figsize=(11.0, 7.8), layout="constrained")
        ax = fig.subplots(2, 3).ravel()
    axes = list(np.ravel(ax))
    if len(axes) != 6:
        raise ValueError(f"ax holds {len(axes)} Axes; give six (2 × 3) or None")
    fig = axes[0].figure
    ext = tuple(e / 1000.0 for e in layer.extent_m)
    from scipy.ndimage import gaussian_filter

    photo = layer.composite("colour-infrared film")
    # the interpreter generalises: tone areas of the photo smoothed over about two cells (no single-cell specks)
    tone = soilmap.segment_tones(gaussian_filter(photo, sigma=(2.0, 2.0, 0.0)), k, seed=0)
    keys = key_sheets(layer)
    areas, sure = soilmap.overlay([tone, keys["relief"], keys["cover"]])
    faded = 0.45 + 0.55 * photo  # the photo seen through the sheets
    sheets = ((tone, f"sheet 1: tone ({k} areas)"), (keys["relief"], "sheet 2: relief"),
              (keys["cover"], "sheet 3: vegetation, land use"))
    axes[0].imshow(photo, origin="lower", extent=ext, interpolation="nearest")
    axes[0].set_title("the photo, colour infrared")
    for a, (lab, title), colour in zip(axes[1:4], sheets, _SHEET_COLOURS):
        a.imshow(faded, origin="lower", extent=ext, interpolation="nearest")
        _outline(a, lab, ext, colour, lw=1.6)
        a.set_title(title, color=colour)
    for j, names in ((2, RELIEF_SHEET), (3, COVER_SHEET)):
        present = np.unique(sheets[j - 1][0])
        axes[j].text(0.02, 0.02, "\n".join(names[i] for i in present), transform=axes[j].transAxes, fontsize=8,
                     va="bottom", bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
    a = axes[4]
    a.imshow(faded, origin="lower", extent=ext, interpolation="nearest")
    for lab, colour in zip((tone, keys["relief"], keys["cover"]), _SHEET_COLOURS):
        _outline(a, lab, ext, colour, lw=0.8)
    a.set_title("the sheets laid together")
    a = axes[5]
    cmap = ListedColormap([c.colour for c in SOIL_CLASSES.values()])
    a.imshow(layer.code, origin="lower", extent=ext, cmap=cmap, vmin=-0.5, vmax=len(SOIL_CLASSES) - 0.5,
             interpolation="nearest", alpha=0.85)
    _outline(a, areas, ext, "black", lw=1.0, sure=sure)
    a.set_title("contours: solid sure, dashed doubtful;\nbeneath: the field survey's soil map", fontsize=10)
    for a in axes:
        a.set_xticks([])
        a.set_yticks([])
        a.grid(False)
        a.set_aspect("equal")
    from matplotlib.patches import Patch as _P

    fig.legend(handles=[_P(color=c.colour, label=f"{c.name} ({c.ru})") for c in SOIL_CLASSES.values()],
               fontsize=8, loc="outside lower center", ncol=3)
    return fig

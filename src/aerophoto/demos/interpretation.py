"""Chapter 08's live demos: what makes a photo readable, and table 10 as an interactive key (guide §9).

* :class:`ConditionsDemo` — one patch of the interpretation site (the river with an island, the tributary, spruce
  forest, the floodplain meadow with haystacks) in natural colour and colour infrared; sliders for the season,
  the sun's elevation e and azimuth A, the visibility V, the topsoil's moisture θ, the ground speed W and the
  exposure t.  The photos update in place (``AxesImage.set_data``); the table gives the photo's RMS contrast, the
  shadow length of a 20 m tree L = h/tan e and the image motion δ = W·t/m.  The patch is rendered once; a new sun
  recomputes only its shadows and shading (cached per position); every other slider only recolours.  It opens on the example (variant 00's
  conditions are the chapter's example: summer, e = 45°, A = 150°, V = 30 km).
* :class:`KeyDemo` — pick a row of table 10: a close-up of the site where that key applies — a square of a
  1:8 000 photo (:data:`KEY_PHOTO_M`) taken over that spot, seen through a magnifier — with the key in English and
  Russian (flow direction from islands and the tributary; pine, spruce and deciduous by tone and crown shape;
  railway against road by curvature; …).  A row seen for the first time shows a quick preview
  (:data:`KEY_PREVIEW_PX`) and then the full picture once the slider rests; a row seen before is instant.
* :func:`lab_figure` — the student's own photo with its numbered marks (the static figure of the lab).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import geometry as g
from .. import interpretation as ip
from .. import plots
from ..blit import nearest_pixels
from ..i18n import t
from ..i18n.numfmt import fmt_number
from ..widgets import LiveDemo, Param

__all__ = ["ConditionsResult", "conditions_model", "ConditionsView", "ConditionsDemo", "KEY_VIEWS", "KeyResult",
           "key_model", "KeyView", "KeyDemo", "lab_figure", "PATCH", "N_KEY_ROWS", "spectra_figure", "KEY_PHOTO_M",
           "KEY_PX", "KEY_PREVIEW_PX", "LAB_DPI", "detail_table", "DETAILS"]

#: the conditions demo's patch: centre X, Y (m), scale 1:m, pixels
PATCH = (620.0, 980.0, 4000.0, 320)
_SEASONS = (("summer (лето)", "summer"), ("autumn (осень)", "autumn"), ("spring, leaf-off (весна)", "spring"),
            ("winter, snow (зима)", "winter"))


def _site():
    from ..site.cover import interpretation_site

    return interpretation_site(0)


@dataclass(frozen=True, eq=False)
class ConditionsResult:
    natural: np.ndarray
    cir: np.ndarray
    conditions: ip.Conditions
    contrast: float
    shadow_m: float
    blur_mm: float
    blur_px: float

    def table(self) -> pd.DataFrame:
        c = self.conditions
        rows = [("RMS contrast of the photo (red band)", f"{self.contrast:.3f}"),
                ("shadow of a 20 m tree, L = h / tan e", f"{self.shadow_m:.1f} m"),
                ("shadows fall towards (azimuth)", f"{ip.shadow_azimuth_deg(c.sun_azimuth_deg):.0f}°"),
                ("image motion δ = W·t/m", t("{blur} mm = {px} px", blur=fmt_number(self.blur_mm, 3),
                                             px=fmt_number(self.blur_px, 1))),
                ("season", c.season)]
        return pd.DataFrame(rows, columns=["quantity", "value"]).set_index("quantity")


def conditions_model(season="summer", sun_elevation_deg=45.0, sun_azimuth_deg=150.0, visibility_km=30.0,
                     moisture_pct=0.0, speed_kmh=200.0, exposure_ms=2.0) -> ConditionsResult:
    """The patch's photo under these conditions (see the module notes)."""
    from ..site.colour import colour_geometry, colour_photo

    cond = ip.Conditions(season=season, sun_elevation_deg=sun_elevation_deg, sun_azimuth_deg=sun_azimuth_deg,
                         visibility_km=visibility_km, moisture_pct=moisture_pct, speed_kmh=speed_kmh,
                         exposure_ms=exposure_ms)
    isite = _site()
    X, Y, m, n = PATCH
    pose = g.Pose(X, Y, isite.site.mean_height_m + g.flying_height_m(100.0, m), 0.0, 0.0, 0.0)
    geom = colour_geometry(isite, g.Camera(100.0, 180.0), pose, n, sun_elevation_deg=cond.sun_elevation_deg,
                           sun_azimuth_deg=cond.sun_azimuth_deg)
    cp = colour_photo(geom, cond)
    red = cp.band("red")
    return ConditionsResult(natural=cp.natural_colour(), cir=cp.colour_infrared(), conditions=cond,
                            contrast=ip.contrast(red, geom.photo.valid), shadow_m=float(ip.shadow_length_m(20.0, cond.sun_elevation_deg)),
                            blur_mm=cp.blur_mm, blur_px=cp.blur_mm / geom.photo.pixel_mm)


class ConditionsView:
    """Natural colour (left) and colour infrared (right) of the patch; ``update`` sets the images' data."""

    def __init__(self, result: ConditionsResult | None = None, ax=None):
        if ax is None:
            fig = plots.figure(figsize=(8.8, 4.5))
            ax_nat, ax_cir = fig.subplots(1, 2)
        else:
            ax_nat, ax_cir = ax
            fig = ax_nat.figure
        self.fig, self.ax_nat, self.ax_cir = fig, ax_nat, ax_cir
        blank = np.zeros((PATCH[3], PATCH[3], 3), np.float32)
        h = 90.0
        self.im_nat = nearest_pixels(ax_nat.imshow(blank, extent=(-h, h, -h, h), interpolation="nearest"))
        self.im_cir = nearest_pixels(ax_cir.imshow(blank, extent=(-h, h, -h, h), interpolation="nearest"))
        ax_nat.set_title("natural colour (цветной)")
        ax_cir.set_title("colour infrared (спектрозональный)")
        for a in (ax_nat, ax_cir):
            a.set_xlabel("x, mm")
        ax_nat.set_ylabel("y, mm")
        # north arrow: the photo's +y is north (κ = 0)
        # (an arrow and a letter, not an annotation: it lies over the photo, so it is redrawn on every move, and an
        # annotation's arrow clipped to its text box costs some 6 ms a draw)
        ax_nat.text(80, 55, "N", color="white", ha="center", va="center")
        from matplotlib.patches import FancyArrowPatch

        ax_nat.add_patch(FancyArrowPatch((80, 62), (80, 80), arrowstyle="->", color="white", mutation_scale=10,
                                         shrinkA=0, shrinkB=0))
        if result is not None:
            self.update(result)

    def update(self, r: ConditionsResult) -> None:
        self.im_nat.set_data(r.natural)
        self.im_cir.set_data(r.cir)


class ConditionsDemo(LiveDemo):
    """What makes a photo readable: the shooting conditions of guide §9 on one patch of the site."""

    photo_frames = True  # a move changes the photo: its frames go as JPEG (plots.fast_frames; issue 32)
    title = "What makes a photo readable (дешифрируемость)"
    hint = ("Change the season, lower the sun, thicken the haze, wet the soil, slow the shutter: "
            "watch what you can still tell apart.")
    params = (
        Param("season", "season", default="summer", kind="choice", options=_SEASONS, group="Season and moisture"),
        Param("moisture_pct", "θ (soil moisture), %", 0, 30, 2, 0, group="Season and moisture",
              help="volumetric moisture of the topsoil above the season's"),
        # a new sun recomputes the patch's shadows over its cached render (about 70 ms)
        Param("sun_elevation_deg", "e (sun elevation), °", 10, 80, 5, 45, group="Sun",
              help="the sun's height above the horizon"),
        Param("sun_azimuth_deg", "A (sun azimuth), °", 90, 270, 15, 150, group="Sun",
              help="clockwise from north"),
        Param("visibility_km", "V (visibility), km", 2, 60, 1, 30, group="Air",
              help="meteorological visibility: smaller V, thicker haze"),
        Param("speed_kmh", "W (ground speed), km/h", 100, 500, 20, 200, group="Image motion"),
        Param("exposure_ms", "t (exposure), ms", 0.5, 20, 0.5, 2, group="Image motion"),
    )

    def build(self):
        self.view = ConditionsView()
        self.fig = self.view.fig
        # a move sets the two images' data: only they (and what lies over them) are redrawn
        self.animated = (self.view.im_nat, self.view.im_cir)

    def compute(self, **v):
        return conditions_model(**v)

    def render(self, result):
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="The photo under these conditions")


# =========================================================================== table 10 as a key
#: the close-ups of the interactive key: site object → (centre X, Y in m, scale denominator, what to look at)
KEY_VIEWS = {
    "river width": ((900.0, None), 3000.0, "the river between its banks: measure its width by the scale"),
    "island": ((505.0, None), 2500.0, "a blunt head upstream, a tail narrowing downstream"),
    "shallows": ((1330.0, None), 2000.0, "light water and a sand spit below the island's tail"),
    "current": ((None, None), 1800.0, "the current streaks the water along the flow; below the island's tail, where "
                "the two arms meet again, foam shows"),
    "tributary": ((610.0, 830.0), 5500.0, "the tributary meets the river at an acute angle pointing downstream; "
                  "the island narrows downstream too — the river flows east (right)"),
    "lake": ((270.0, 230.0), 3500.0, "a closed shoreline, a light shallow rim"),
    "pond": ((1322.0, 380.0), 2500.0, "the water is widest at the dam"),
    "dam": ((1322.0, 420.0), 2000.0, "the dam closes the pond at its downstream end: the brook flows north"),
    "raised bog": ((1300.0, 1400.0), 6000.0, "on the watershed, far from streams; mottled tone, bog lakelets, "
                   "sparse small pines"),
    "low bog": ((1330.0, 720.0), 4000.0, "a ribbon along the valley floor; shrub thick at its edges"),
    "pine forest": ((160.0, 1320.0), 1200.0, "even grey tone, convex crowns of one height"),
    "spruce forest": ((670.0, 1360.0), 1200.0, "darker, mottled; small pointed crowns with long thin shadows"),
    "deciduous forest": ((745.0, 200.0), 1200.0, "lighter, coarse grain of broad soft crowns"),
    "shrub": ((1330.0, 650.0), 1500.0, "lighter than forest, fine grain, short shadows"),
    "haystacks": ((None, None), 1200.0, "small round bright heaps with shadows on an even meadow"),
    "arable land": ((1300.0, 170.0), 4000.0, "straight boundaries, even tone, furrows"),
    "railway": ((700.0, 470.0), 7000.0, "even width, long straights joined by a curve of large radius"),
    "asphalt road": ((1000.0, 640.0), 3000.0, "dark, winding in tight curves, edged by ditches"),
    "gravel road": ((820.0, 420.0), 2500.0, "light, edged by ditches"),
}


def _key_rows():
    from .. import guide

    return [r for r in guide.ch08.TABLE_10 if r[5] is not None]


#: how many rows of table 10 the site illustrates (the key's slider runs over them)
N_KEY_ROWS = 19
#: the key's close-ups are squares of a photo of this scale (1:m, f = 100 mm) taken over each spot
KEY_PHOTO_M = 8000.0
#: pixels across a close-up, and across its quick preview
KEY_PX = 384
KEY_PREVIEW_PX = 128


@dataclass(frozen=True, eq=False)
class KeyResult:
    image: np.ndarray
    row: tuple
    look: str
    ground_m: float = 0.0  # the close-up's side on the ground, m

    def table(self) -> pd.DataFrame:
        g_, e, e_ru, k, k_ru, obj = self.row
        return pd.DataFrame({"": [f"{g_}: {e} ({e_ru})", k, k_ru, self.look]},
                            index=["table 10", "key", "признак", "on this photo"])


def key_model(row: int = 0, camera: str = "colour film", n_px: int = KEY_PX) -> KeyResult:
    """The close-up of table 10's row ``row`` (of the rows the site illustrates) and its key.

    The close-up is the square of a vertical 1:8 000 photo (f = 100 mm, :data:`KEY_PHOTO_M`) over the spot that
    covers 180 mm × m of the ground (m of :data:`KEY_VIEWS`), rendered at ``n_px`` pixels across (16…1024).
    """
    from ..site.colour import render_colour
    from ..site.cover import _river_y

    rows = _key_rows()
    if not 0 <= int(row) < len(rows):
        raise ValueError(f"row = {row!r} is outside the valid range 0 ≤ row ≤ {len(rows) - 1}")
    r = rows[int(row)]
    isite = _site()
    (X, Y), m, look = KEY_VIEWS[r[5]]
    if r[5] == "shallows":
        X = float(isite.features["islands"][1]["tail_m"][0])
    if r[5] == "current":
        X = float(isite.features["islands"][1]["tail_m"][0]) + 30.0
    if r[5] == "haystacks":
        X, Y = (float(v) for v in isite.features["haystacks"][0, :2])
    if Y is None:
        Y = float(_river_y(X))
    from .._validate import check_int_range

    n = check_int_range("n_px", n_px, 16, 1024)
    pose = g.Pose(X, Y, isite.site.mean_height_m + g.flying_height_m(100.0, KEY_PHOTO_M))
    side = 180.0 * m / KEY_PHOTO_M
    cp = render_colour(isite, g.Camera(100.0, 180.0), pose, n, ip.Conditions(speed_kmh=0.0), window_mm=(0, 0, side))
    return KeyResult(image=cp.composite(camera), row=r, look=look, ground_m=side * KEY_PHOTO_M / 1000.0)


class KeyView:
    """The close-up of one key, north up, with a scale bar; ``update`` swaps the image's data and moves the bar.

    The axes run 0…1 across the close-up (fixed: a move redraws only the picture and the bar).
    """

    def __init__(self, result: KeyResult | None = None, ax=None):
        self.fig, self.ax = plots.new_axes(ax, figsize=(5.6, 5.4))
        self.im = self.ax.imshow(np.zeros((KEY_PX, KEY_PX, 3), np.float32), extent=(0, 1, 0, 1),
                                 interpolation="antialiased")
        self.ax.set_xlim(0, 1)
        self.ax.set_ylim(0, 1)
        self.ax.set_xticks([])
        self.ax.set_yticks([])
        self.ax.set_title("the site on a 1:8000 photo, magnified (north up)")
        self.bar, = self.ax.plot([0.05, 0.25], [0.05, 0.05], color="white", lw=3, solid_capstyle="butt")
        self.bar_text = self.ax.text(0.05, 0.075, "", color="white", fontsize=12)
        self._bar_m = None
        if result is not None:
            self.update(result)

    def update(self, r: KeyResult) -> None:
        from ..i18n.numfmt import fmt_quantity

        self.im.set_data(r.image)
        if r.ground_m > 0:
            bar_m = next(b for b in (500.0, 200.0, 100.0, 50.0, 20.0, 10.0, 5.0) if b <= 0.3 * r.ground_m)
            self.bar.set_data([0.05, 0.05 + bar_m / r.ground_m], [0.05, 0.05])
            if bar_m != self._bar_m:
                self._bar_m = bar_m
                self.bar_text.set_text(fmt_quantity(bar_m, "m", 0))


class KeyDemo(LiveDemo):
    """Table 10 as an interactive key: pick a row, see where it applies on the site."""

    photo_frames = True  # a move changes the photo: its frames go as JPEG (plots.fast_frames; issue 32)
    title = "Table 10 as a key (топографическое дешифрирование)"
    hint = "Pick a row of table 10: the photo shows the site where that key applies, and what to look at."
    params = (
        Param("row", "table 10 row", 1, N_KEY_ROWS, 1, 1, kind="int", group="Key",
              help="the rows of table 10 that the site shows, in the table's order, counted from 1"),
        Param("camera", "film", default="colour film", kind="choice",
              options=(("natural colour", "colour film"), ("colour infrared", "colour-infrared film")), group="Key"),
    )

    def build(self):
        self.view = KeyView()
        self.fig = self.view.fig
        self.animated = (self.view.im,)  # a move swaps the image: only it (and the bar over it) is redrawn
        self._seen = {}  # close-ups already rendered (a row revisited is instant)

    def compute(self, **v):
        k = (int(v["row"]), v["camera"])
        if k in self._seen:
            return self._seen[k]
        row = int(v["row"]) - 1  # the slider counts rows from 1, key_model from 0
        if self._preview:  # a row seen for the first time: a quick preview now, the full close-up when it rests
            return key_model(row, v["camera"], KEY_PREVIEW_PX)
        self._seen[k] = key_model(row=row, camera=v["camera"])
        return self._seen[k]

    def render(self, result):
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="Table 10 (guide §9)")

    def on_slider(self) -> str:
        if (int(self.values["row"]), self.values["camera"]) in self._seen:
            self.update()
            return ""
        return self.preview_then_full(0.2, note="the close-up: full detail when the slider rests")


# =========================================================================== the lab's photo
#: the resolution at which :func:`lab_figure`'s own figure shows the photo's 1024 pixels one for one (dpi)
LAB_DPI = 166


def lab_figure(lab, camera: str = "colour film", ax=None, *, marks: bool = True):
    """The student's photo (:class:`aerophoto.labs.ch08.LabPhoto`) with its numbered marks, in photo mm.

    Saved at :data:`LAB_DPI` (``plots.static(..., dpi=di.LAB_DPI, format="jpeg")``) the photo shows at its full
    resolution, 1024 pixels across.
    """
    if ax is None:  # the photo takes the figure: at LAB_DPI its 1024 pixels are shown one for one
        fig = plots.figure(figsize=(7.0, 7.0), layout="none")
        ax = fig.add_subplot(1, 1, 1)
        fig.subplots_adjust(left=0.105, right=0.985, bottom=0.09, top=0.97)
    fig = ax.figure
    ax.imshow(lab.composite(camera), extent=lab.extent_mm, interpolation="antialiased")
    if marks:
        for name, row in lab.marks.iterrows():
            x, y = row["x, mm"], row["y, mm"]
            colour = "#F0E442" if name.isdigit() else ("#56B4E9" if name in "PQ" else "#D55E00")
            ax.plot([x], [y], "o", ms=5, mfc="none", mec=colour, mew=1.5)
            ax.annotate(name, (x, y), xytext=(5, 5), textcoords="offset points", color=colour, fontsize=12,
                        fontweight="bold")
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.set_xlim(-90, 90)
    ax.set_ylim(-90, 90)
    return fig


def spectra_figure(classes=("deep water", "shallow water", "meadow", "pine forest", "spruce forest",
                            "deciduous forest", "raised bog", "asphalt road", "gravel road"), season: str = "summer",
                   ax=None):
    """The classes' band reflectances (:func:`aerophoto.site.colour.class_band_table`) against the bands' centres."""
    from .. import spectral as sp
    from ..site.colour import class_band_table
    from ..site.cover import CLASS_CODES, CLASS_RU

    fig, ax = plots.new_axes(ax, figsize=(8.6, 4.6))
    fixed, soil = class_band_table(season)
    wl = [sp.BANDS[b].centre_um for b in sp.BAND_NAMES]
    for name in classes:
        if name not in CLASS_CODES:
            raise ValueError(f"classes: {name!r} is not one of the classes {list(CLASS_CODES)}")
        ax.plot(wl, fixed[CLASS_CODES[name]], "o-", lw=1.5, ms=4, label=f"{name} ({CLASS_RU[name]})")
    for b in sp.BAND_NAMES:
        band = sp.BANDS[b]
        ax.axvspan(band.lo_um, band.hi_um, color=band.colour, alpha=0.12, lw=0)
    ax.set_xlabel("wavelength λ, µm (shaded: the six bands)")
    ax.set_ylabel("reflectance ρ (КСЯ)")
    ax.set_title(f"reflectance of the site's classes by band, {season}")
    ax.legend(fontsize=8, ncol=2, loc="upper right")
    return fig


#: sizes on the ground of what the direct keys read (m): the site's own (aerophoto.site.cover, cover_objects)
DETAILS = (
    ("tramlines of a crop, apart", "технологическая колея", 18.0),
    ("a house (its longer side)", "дом", 9.0),
    ("the asphalt road with its shoulders", "дорога с обочинами", 9.0),
    ("a pine's crown, across", "крона сосны", 5.0),
    ("a spruce's crown, across", "крона ели", 3.6),
    ("a plough's pass (its five furrows)", "проход плуга", 1.75),
    ("the two rails, apart", "рельсовые нити", 1.52),
)


def detail_table(m: float, *, power: int = 6) -> pd.DataFrame:
    """What the photo's pixels resolve at scale 1:m: each of :data:`DETAILS` on the ground, on the photo and in
    pixels of the photo (1024 across 180 mm) and of the magnifier at ×``power`` (3…6).  Numbers in the book's
    format (:mod:`aerophoto.i18n.numfmt`)."""
    from .._validate import check_int_range, check_range
    from ..i18n.numfmt import fmt_number
    from ..labs.ch08 import LOUPE_PX, N_PX
    from .loupe import FIELD_MM

    m = check_range("m", m, 500.0, 100000.0)
    k = check_int_range("power", power, 3, 6)
    p_photo = 180.0 / N_PX
    p_glass = FIELD_MM / k / LOUPE_PX
    rows = []
    for en, ru, size in DETAILS:
        mm = size * 1000.0 / m
        digits = 0 if float(size).is_integer() else (2 if size < 2 else 1)
        rows.append({"what": f"{en} ({ru})", "on the ground, m": fmt_number(size, digits),
                     "on the photo, mm": fmt_number(mm, 2), "pixels of the photo": fmt_number(mm / p_photo, 1),
                     f"pixels under the glass ×{k}": fmt_number(mm / p_glass, 0)})
    return pd.DataFrame(rows).set_index("what")

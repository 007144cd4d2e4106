"""Static figures and prints of the stereo chapter (guide §8).

* :func:`stereoscope_figure` — the lens-mirror stereoscope (линзово-зеркальный стереоскоп) in section, with
  the paths of the two lines of sight;
* :func:`stereoscope_view` and :func:`mirror_check_figure` — the check of the mirrors with a 40 cm line:
  what each eye sees when the instrument is set right, turned, or has a tilted mirror;
* :func:`pair_geometry_figure` — the stereo pair in section: two stations, a point and its x-parallax;
* :func:`anaglyph_figure` — a piece of a pair's anaglyph (direct or reverse);
* :func:`profile_figure` — a parallax profile along one epipolar line, matched against the truth;
* :func:`height_model_figure` — the coarse height model of the overlap by correlation against the truth;
* :func:`stereo_print` — a print-ready PDF/PNG at true size: anaglyph, free-viewing pair (eye base) or a
  pair for the lens-mirror stereoscope (its base), with a 50 mm scale bar to check the printer.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import plots
from .. import stereo as st
from .._validate import check_range

__all__ = ["stereoscope_figure", "stereoscope_view", "mirror_check_figure", "pair_geometry_figure",
           "anaglyph_figure", "profile", "profile_figure", "height_model_figure", "stereo_print", "PRINT_MODES"]

C = plots.COLORS
#: the prints :func:`stereo_print` makes: mode → (spacing of conjugate points, mm, or None for an anaglyph; the
#: widest piece, mm)
PRINT_MODES = {"anaglyph": (None, 150.0), "free viewing": (st.EYE_BASE_MM, 60.0),
               "stereoscope": (st.STEREOSCOPE_BASE_MM, 110.0)}


# =========================================================================== the instrument
def stereoscope_figure(ax=None):
    """The lens-mirror stereoscope in section: eyes, lenses, small and large mirrors, the two photos."""
    fig, ax = plots.new_axes(ax, figsize=(8.6, 4.6))
    e, B = st.EYE_BASE_MM, st.STEREOSCOPE_BASE_MM
    y_eye, y_lens, y_mirror, y_photo = 330.0, 300.0, 250.0, 0.0
    for sgn, col, name in ((-1, C["vermillion"], "left"), (1, C["blue"], "right")):
        xe, xb = sgn * e / 2, sgn * B / 2
        ax.add_patch(_circle(xe, y_eye, 9, C["black"]))
        ax.plot([xe - 16, xe + 16], [y_lens, y_lens], color=C["skyblue"], lw=5, solid_capstyle="round")
        ax.plot([xe - 14, xe + 14], [y_mirror - sgn * 14, y_mirror + sgn * 14], color=C["grey"], lw=4)
        ax.plot([xb - 22, xb + 22], [y_mirror - sgn * 22, y_mirror + sgn * 22], color=C["grey"], lw=6)
        ax.plot([xe, xe, xb, xb], [y_eye - 9, y_mirror, y_mirror, y_photo + 4], color=col, lw=1.8)
        ax.plot([xb - 55, xb + 55], [y_photo, y_photo], color=C["black"], lw=4)
        ax.text(xb, y_photo - 22, f"{name} photo", ha="center", fontsize=11)
        ax.plot([xb], [y_photo + 4], "o", color=col, ms=7)
    ax.annotate("", xy=(-B / 2, -45), xytext=(B / 2, -45), arrowprops=dict(arrowstyle="<->", lw=1.2))
    ax.text(0, -60, f"base of the instrument ≈ {B:.0f} mm: conjugate points this far apart", ha="center",
            fontsize=11)
    ax.annotate("", xy=(-e / 2, y_eye + 22), xytext=(e / 2, y_eye + 22), arrowprops=dict(arrowstyle="<->", lw=1.2))
    ax.text(0, y_eye + 30, f"eye base ≈ {e:.0f} mm", ha="center", fontsize=11)
    ax.text(-e / 2 - 30, y_lens, "lenses", ha="right", va="center", fontsize=11)
    ax.text(0, y_mirror - 34, "small mirrors", ha="center", fontsize=11)
    ax.text(B / 2 + 30, y_mirror + 10, "large\nmirrors", ha="left", va="center", fontsize=11)
    ax.set_xlim(-230, 230)
    ax.set_ylim(-80, 380)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title("Lens-mirror stereoscope (линзово-зеркальный стереоскоп), in section")
    return fig


def _circle(x, y, r, color):
    from matplotlib.patches import Circle

    return Circle((x, y), r, fill=False, ec=color, lw=1.5)


def stereoscope_view(turn_deg: float = 0.0, mirror_roll_deg: float = 0.0, *, base_mm: float = st.STEREOSCOPE_BASE_MM,
                     field_mm: float = 120.0) -> tuple:
    """What each eye sees of a straight line drawn on the table (the guide's 40 cm line), in the fused view.

    The stereoscope stands over the line with its base turned ``turn_deg`` from
    it; one pair of mirrors is rolled ``mirror_roll_deg`` about the line of
    sight.  Each eye looks at its own part of the line, ``base_mm`` apart;
    in the fused view their images coincide when the instrument is right.

    Returns ``(left, right)``: the two images of the line as (2, 2) segments
    in the view, mm (x along the base, y across).  Turning the instrument
    moves them apart across by base·sin(turn) — two parallel lines that turning
    back brings together; a rolled mirror pair turns its eye's image by twice
    the roll — lines at an angle that no turning can merge.
    """
    t = math.radians(check_range("turn_deg", turn_deg, -45.0, 45.0, unit="degrees"))
    r = math.radians(check_range("mirror_roll_deg", mirror_roll_deg, -20.0, 20.0, unit="degrees"))
    h = check_range("field_mm", field_mm, 1.0, 1000.0, unit="mm") / 2.0
    B = check_range("base_mm", base_mm, 1.0, 1000.0, unit="mm")
    u = np.array([-h, h])
    # the line in the instrument's frame: direction (cos t, −sin t); each eye's view centred on its end of the base
    out = []
    for sgn, roll in ((-1.0, 0.0), (1.0, 2.0 * r)):
        off = sgn * B / 2.0 * math.sin(t)  # the line passes this far across from the eye's view centre
        d = np.array([math.cos(-t + roll), math.sin(-t + roll)])
        seg = np.column_stack([u * d[0], -off + u * d[1]])
        out.append(seg)
    return out[0], out[1]


def mirror_check_figure(turn_deg: float = 1.5, mirror_roll_deg: float = 1.0):
    """The mirror check of guide §8 in three views: set right, turned by ``turn_deg``, a mirror rolled."""
    fig = plots.figure(figsize=(10.0, 3.4))
    axs = fig.subplots(1, 3)
    cases = ((0.0, 0.0, "set right: one line"), (turn_deg, 0.0, f"turned {turn_deg:g}°: two parallel lines"),
             (0.0, mirror_roll_deg, f"a mirror rolled {mirror_roll_deg:g}°: lines at an angle"))
    for ax, (t, r, title) in zip(axs, cases):
        L, R = stereoscope_view(t, r)
        ax.plot(*L.T, color=C["vermillion"], lw=2.5, label="left eye")
        ax.plot(*R.T, color=C["blue"], lw=2.5, ls="--", label="right eye")
        ax.set_xlim(-60, 60)
        ax.set_ylim(-12, 12)
        ax.set_title(title, fontsize=11)
        ax.set_xlabel("mm in the view")
        ax.grid(False)
    axs[0].legend(loc="lower left", fontsize=9)
    return fig


def pair_geometry_figure(ax=None, *, B_m: float = 864.0, H_m: float = 1200.0, f_mm: float = 100.0,
                         h_m: float = 400.0):
    """The stereo pair in section: S₁, S₂ a base B apart at H, a ground point A and a point C h higher, and the
    images a₁, a₂, c₁, c₂ with their x-parallaxes (the photos drawn 0.2·H below the stations, enlarged)."""
    fig, ax = plots.new_axes(ax, figsize=(8.6, 4.8))
    S1, S2 = np.array([0.0, H_m]), np.array([B_m, H_m])
    A, Cp = np.array([0.45 * B_m, 0.0]), np.array([0.55 * B_m, h_m])
    fz = 0.2 * H_m  # the (positive) photo planes, scaled up so that the images can be seen
    half = fz * 90.0 / f_mm
    for S, lab in ((S1, "S₁"), (S2, "S₂")):
        ax.plot([S[0] - half, S[0] + half], [S[1] - fz] * 2, color=C["black"], lw=3)
        ax.plot(*S, "o", color=C["black"], ms=8)
        ax.text(S[0], S[1] + 40, lab, ha="center", fontsize=12)
    ax.plot([S1[0], S2[0]], [H_m, H_m], color=C["grey"], lw=1, ls=":")
    ax.text(B_m / 2, H_m + 40, "air base B", ha="center", fontsize=11)
    for P, col, name in ((A, C["green"], "a"), (Cp, C["vermillion"], "c")):
        for S, idx in ((S1, 1), (S2, 2)):
            ax.plot([S[0], P[0]], [S[1], P[1]], color=col, lw=1.2)
            t = fz / (S[1] - P[1])
            img = S + t * (P - S)
            ax.plot(*img, "o", color=col, ms=6)
            dy = 25 if name == "c" else -65  # c's images labelled above the photo, a's below
            ax.text(img[0], img[1] + dy, f"{name}{idx}", color=col, fontsize=11, ha="center")
    ax.plot([-0.4 * B_m, 1.4 * B_m], [0, 0], color=C["black"], lw=1.5)
    ax.plot([Cp[0], Cp[0]], [0, Cp[1]], color=C["vermillion"], lw=4)
    ax.text(A[0], -70, "A (ground)", ha="center", color=C["green"], fontsize=11)
    ax.text(Cp[0] + 20, Cp[1] / 2, "C, h above A", color=C["vermillion"], fontsize=11)
    ax.set_xlim(-0.45 * B_m, 1.45 * B_m)
    ax.set_ylim(-120, H_m + 110)
    ax.set_xlabel("along the strip, m")
    ax.set_ylabel("height, m")
    ax.set_title("x-parallax p = x₁ − x₂: C, higher, has the larger one")
    return fig


# =========================================================================== pictures of a pair
def anaglyph_figure(images, *, centre_mm=None, size_mm=(60.0, 40.0), reverse: bool = False, ax=None, title=None):
    """A piece of the pair's overlap as a red–cyan anaglyph (red over the left eye), in left-photo mm."""
    from .stereo import AnaglyphView

    L, R = images.left, images.right
    ex = L.extent_mm
    cx, cy = centre_mm if centre_mm is not None else ((ex[0] + ex[1]) / 2, (ex[2] + ex[3]) / 2)
    w, h = size_mm
    rc0 = np.floor(L.mm_to_pixel(np.array([cx - w / 2, cy + h / 2])) + 0.5).astype(int)
    nr = min(int(round(h / L.pixel_mm)), L.image.shape[0])
    nc = min(int(round(w / L.pixel_mm)), L.image.shape[1])
    r0 = int(np.clip(rc0[0], 0, L.image.shape[0] - nr))
    c0 = int(np.clip(rc0[1], 0, L.image.shape[1] - nc))
    a, b = L.image[r0:r0 + nr, c0:c0 + nc], R.image[r0:r0 + nr, c0:c0 + nc]
    rgb = st.anaglyph(b, a) if reverse else st.anaglyph(a, b)
    left = L.x0_mm + c0 * L.pixel_mm
    top = L.y_top_mm - r0 * L.pixel_mm
    view = AnaglyphView(ax, title=title or ("reverse stereo (photos swapped)" if reverse else
                                            "anaglyph: red filter over the left eye"))
    view.update(rgb, (left, left + nc * L.pixel_mm, top - nr * L.pixel_mm, top))
    return view.fig


def profile(lab, images, y_mm: float, *, step_px: int = 2, half_window: int = 7) -> dict:
    """Parallaxes along the epipolar line y of the normalised pair: matched (NCC) and true, and the heights.

    Returns arrays ``x_mm``, ``p_mm`` (matched), ``peak``, ``p_true_mm`` and ``Z_mm``-free heights
    ``Z_m`` (from the matched parallax), ``Z_true_m`` (what the left photo sees there).  The same for everyone
    on the same pair and line (the guide's example): computed once, then read from the user's disk cache
    (:mod:`aerophoto.cache`).
    """
    from .. import cache

    import hashlib

    pieces = hashlib.sha256()
    for im in (images.left, images.right):
        pieces.update(np.ascontiguousarray(im.image).tobytes())
        pieces.update(repr((im.x0_mm, im.y_top_mm, im.pixel_mm, im.image.shape)).encode())
    inputs = {"f_mm": lab.f_mm, "m": lab.m, "seed": lab.seed, "images": pieces.hexdigest(), "y_mm": float(y_mm),
              "step_px": int(step_px), "half_window": int(half_window)}
    return cache.load_or_build("stereo-profile", inputs, lambda: _profile(lab, images, y_mm, step_px, half_window))


def _profile(lab, images, y_mm: float, step_px: int, half_window: int) -> dict:
    from ..render import trace
    from ..site import get_site

    L, R = images.left, images.right
    px = L.pixel_mm
    row = float(L.mm_to_pixel(np.array([0.0, y_mm]))[0])
    cols = np.arange(half_window + 40, L.image.shape[1] - half_window - 2, step_px)
    rc = np.column_stack([np.full(len(cols), row), cols])
    zlo, zhi = lab.Z_S_m - get_site().z_min_m + 10.0, lab.Z_S_m - get_site().surface_z_max_m - 5.0
    dlo = int(math.floor((lab.B_m * lab.f_mm / zlo - lab.p0_mm) / px)) - 2
    dhi = int(math.ceil((lab.B_m * lab.f_mm / max(zhi, 1.0) - lab.p0_mm) / px)) + 2
    d, peak = st.match_points(L.image, R.image, rc, half_window=half_window, d_min=dlo, d_max=dhi)
    xy = L.pixel_to_mm(np.column_stack([np.full(len(cols), round(row)), cols]))
    p = lab.p0_mm + d * px
    with np.errstate(invalid="ignore"):
        Z = np.where(p > 0, lab.model_to_ground(xy, np.where(p > 0, p, 1.0))[:, 2], np.nan)
    src = st.from_normal(lab.camera, lab.left.pose, lab.R_n, xy)
    P = trace(get_site(), lab.camera, lab.left.pose, src).XYZ_m
    xl, xr = lab.normal_xy(P)
    return {"x_mm": xy[:, 0], "p_mm": p, "peak": peak, "p_true_mm": xl[:, 0] - xr[:, 0], "Z_m": Z,
            "Z_true_m": P[:, 2]}


def profile_figure(lab, images, y_mm: float, *, prof=None):
    """The anaglyph strip along an epipolar line and, under it, the heights from matched parallaxes and the truth."""
    prof = profile(lab, images, y_mm) if prof is None else prof
    fig = plots.figure(figsize=(10.0, 5.4))
    a1, a2 = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [1, 2]})
    L = images.left
    r = int(round(float(L.mm_to_pixel(np.array([0.0, y_mm]))[0])))
    k = int(round(4.0 / L.pixel_mm))
    a, b = L.image[max(r - k, 0):r + k], images.right.image[max(r - k, 0):r + k]
    ex = L.extent_mm
    a1.imshow(st.anaglyph(a, b), extent=(ex[0], ex[1], y_mm - 4, y_mm + 4), aspect="auto", interpolation="nearest")
    a1.axhline(y_mm, color=C["yellow"], lw=1)
    a1.set_ylabel("y, mm")
    a1.grid(False)
    a1.set_title(f"Along the epipolar line y = {y_mm:.1f} mm")
    good = prof["peak"] >= 0.8
    a2.plot(prof["x_mm"], prof["Z_true_m"], color=C["truth"], lw=2.5, label="truth: the surface the left photo sees")
    a2.plot(prof["x_mm"][good], prof["Z_m"][good], ".", color=C["blue"], ms=4, label="from matched parallax (NCC ≥ 0.8)")
    a2.plot(prof["x_mm"][~good], prof["Z_m"][~good], "x", color=C["vermillion"], ms=4, label="weak match (NCC < 0.8)")
    lo = float(np.nanmin(prof["Z_true_m"])) - 10.0
    hi = float(np.nanmax(prof["Z_true_m"])) + 10.0
    a2.set_ylim(lo, hi)
    a2.set_xlabel("x on the left photo, mm")
    a2.set_ylabel("height Z, m")
    a2.legend(loc="upper left", fontsize=9)
    return fig


def height_model_figure(hm):
    """The height model by correlation (reliable pixels), the truth, and the error, over the overlap."""
    from matplotlib.colors import ListedColormap

    fig = plots.figure(figsize=(11.0, 5.2))
    axs = fig.subplots(1, 3)
    ex = hm.extent_mm
    rel = hm.reliable
    zt = hm.Z_true_m
    lo, hi = np.nanpercentile(zt, 1), np.nanpercentile(zt, 99.5)
    m = np.where(rel, hm.Z_m, np.nan)
    for ax, img, title in ((axs[0], m, "matched (reliable pixels)"), (axs[1], zt, "truth (what the left photo sees)")):
        im = ax.imshow(img, extent=ex, vmin=lo, vmax=hi, cmap="terrain", interpolation="nearest")
        ax.set_title(title, fontsize=11)
        ax.grid(False)
    fig.colorbar(im, ax=axs[:2], shrink=0.8, label="Z, m")
    err = np.where(rel, hm.error_m, np.nan)
    cmap = ListedColormap(["#0072B2", "#56B4E9", "#F7F7F7", "#E69F00", "#D55E00"])
    im2 = axs[2].imshow(np.clip(err, -10, 10), extent=ex, vmin=-10, vmax=10, cmap=cmap, interpolation="nearest")
    axs[2].set_title("error, m (white: within ±2 m)", fontsize=11)
    axs[2].grid(False)
    fig.colorbar(im2, ax=axs[2], shrink=0.8, label="matched − true, m")
    for ax in axs:
        ax.set_xlabel("x, mm")
    axs[0].set_ylabel("y, mm")
    return fig


# =========================================================================== printing at true size
def stereo_print(images, path, *, mode: str = "free viewing", centre_mm=None, size_mm=None, dpi: int = 300,
                 reverse: bool = False) -> Path:
    """Write a print-ready PDF or PNG (by ``path``'s suffix) of a piece of the pair at true size.

    Parameters
    ----------
    images : :class:`aerophoto.labs.ch07.PairImages`
    mode : {"anaglyph", "free viewing", "stereoscope"}
        An anaglyph; a pair for free viewing with conjugate points one eye base
        (65 mm) apart; or a pair for the lens-mirror stereoscope, its base
        (:data:`aerophoto.stereo.STEREOSCOPE_BASE_MM`) apart.
    centre_mm, size_mm : the piece of the overlap (left-photo mm); the width is capped per mode
        (:data:`PRINT_MODES`) so the two pieces do not overlap.
    dpi : int
        For PNG (and the images inside a PDF), 100 ≤ dpi ≤ 1200.
    reverse : bool
        Swap the photos (the reverse stereo effect).

    The page is exactly as large as its content plus 10 mm margins; print it at
    100 % ("actual size"): the 50 mm bar at the bottom must measure 50 mm.
    """
    import matplotlib.pyplot as plt

    if mode not in PRINT_MODES:
        raise ValueError(f"mode = {mode!r} is not valid; expected one of {list(PRINT_MODES)}")
    dpi = int(check_range("dpi", dpi, 100, 1200))
    path = Path(path)
    if path.suffix.lower() not in (".pdf", ".png"):
        raise ValueError(f"path = {str(path)!r} must end in .pdf or .png")
    sep, wmax = PRINT_MODES[mode]
    L, R = images.left, images.right
    ex = L.extent_mm
    w, h = size_mm if size_mm is not None else (wmax, 60.0 if mode != "anaglyph" else 100.0)
    w = min(float(w), wmax, ex[1] - ex[0])
    h = min(float(h), ex[3] - ex[2])
    cx, cy = centre_mm if centre_mm is not None else ((ex[0] + ex[1]) / 2, (ex[2] + ex[3]) / 2)
    rc0 = np.floor(L.mm_to_pixel(np.array([cx - w / 2, cy + h / 2])) + 0.5).astype(int)
    nr, nc = int(round(h / L.pixel_mm)), int(round(w / L.pixel_mm))
    r0 = int(np.clip(rc0[0], 0, L.image.shape[0] - nr))
    c0 = int(np.clip(rc0[1], 0, L.image.shape[1] - nc))
    a, b = L.image[r0:r0 + nr, c0:c0 + nc], R.image[r0:r0 + nr, c0:c0 + nc]
    if reverse:
        a, b = b, a
    wmm, hmm = nc * L.pixel_mm, nr * L.pixel_mm  # the pieces' true size
    margin, foot = 10.0, 18.0
    width = (wmm if sep is None else sep + wmm) + 2 * margin
    height = hmm + margin + foot
    fig = plt.figure(figsize=(width / 25.4, height / 25.4), dpi=dpi, layout="none")  # mm-exact axes

    def place(x_mm, img, cmap=None):
        ax = fig.add_axes([x_mm / width, foot / height, wmm / width, hmm / height])
        # "none": the photo's own pixels go into the PDF as they are (no resampling to the dpi: a third of the
        # pixels to write, the same picture)
        ax.imshow(img, cmap=cmap, vmin=0, vmax=1, aspect="auto", interpolation="none")
        ax.set_axis_off()

    if sep is None:
        place(margin, st.anaglyph(a, b))
        note = "red filter over the LEFT eye" + (" (reverse: photos swapped)" if reverse else "")
    else:
        place(margin, np.nan_to_num(a, nan=1.0), "gray")
        place(margin + sep, np.nan_to_num(b, nan=1.0), "gray")
        note = (f"{mode}: conjugate points {sep:g} mm apart — left photo to the left eye"
                + (" (reverse: photos swapped)" if reverse else ""))
    bar = fig.add_axes([margin / width, 4.0 / height, 50.0 / width, 2.0 / height])
    bar.set_xlim(0, 50)
    bar.fill_between([0, 50], 0, 1, color="black")
    bar.set_axis_off()
    fig.text((margin + 55.0) / width, 5.0 / height, f"50 mm — print at 100 %. {note}. Photo at true size "
             f"(1 mm = {images.lab.m / 1000.0:g} m)", fontsize=7, va="center")
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path

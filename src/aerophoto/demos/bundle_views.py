"""Static figures of chapters 14 and 15: a block over the mountain site, the Jacobian's sparsity, error ellipses,
and the accumulation of errors along a strip.

Each builder takes ``ax=None`` (a new figure) or the axes to draw in and returns the figure; notebooks show
them with :func:`aerophoto.plots.static`.
"""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Ellipse

from .. import accuracy as acc
from .. import bundle as B
from .. import plots

__all__ = ["block_figure", "sparsity_figure", "ellipse_figure", "accumulation_figure", "walk_figure"]

_KIND_STYLE = {"tie": ("o", "grey", 3), "check": ("s", "skyblue", 5), "control": ("^", "control", 10),
               "field": ("*", "vermillion", 13)}


def block_figure(survey, ax=None):
    """The block over the site's relief: photo footprints, tie, check, control and gravimetric points."""
    from .. import site as _site

    fig, ax = plots.new_axes(ax, figsize=(8.0, 6.2))
    st = _site.get_site(**survey_site_params(survey))
    x0, x1, y0, y1 = st.extent_m
    im = ax.imshow(st.dem, origin="lower", extent=(x0 / 1000, x1 / 1000, y0 / 1000, y1 / 1000), cmap="terrain",
                   alpha=0.75)
    fig.colorbar(im, ax=ax, fraction=0.035, pad=0.02, label="height, m")
    fp = survey.block.footprints(st.mean_height_m)
    for poly in fp:
        p = np.vstack([poly[:, :2], poly[:1, :2]]) / 1000.0
        ax.plot(p[:, 0], p[:, 1], color=plots.COLORS["blue"], lw=0.6, alpha=0.6)
    m = survey.meas
    for kind, (mk, col, size) in _KIND_STYLE.items():
        sel = m.point_kind == kind
        if not sel.any():
            continue
        xy = survey.truth_m[sel, :2] / 1000.0
        ax.plot(xy[:, 0], xy[:, 1], mk, color=plots.COLORS[col], ms=size, ls="none",
                mec="black" if kind in ("control", "field") else "none", mew=0.5, label=f"{kind} ({int(sel.sum())})")
    c = survey.block.centres_m / 1000.0
    ax.plot(c[:, 0], c[:, 1], "+", color="black", ms=5, ls="none", label="photo centres")
    ax.set_xlabel("X, km")
    ax.set_ylabel("Y, km")
    ax.set_aspect("equal")
    ax.legend(loc="upper left", fontsize=8, ncol=2)
    ax.set_title(survey.name, fontsize=11)
    return fig


def survey_site_params(survey) -> dict:
    """The parameters of the site a survey block was flown over."""
    from ..labs.ch15 import MOUNTAIN_SITE

    return dict(MOUNTAIN_SITE)


def sparsity_figure(meas, ax=None):
    """The Jacobian's non-zero pattern (left) and the reduced camera system's (right)."""
    import scipy.sparse as sp

    if ax is None:
        fig = plots.figure(figsize=(9.0, 4.2))
        a1, a2 = fig.subplots(1, 2)
    else:
        a1, a2 = ax
        fig = a1.figure
    prob = B.solve._Problem(meas)
    J = prob.sparsity()
    a1.spy(J, markersize=0.3, aspect="auto", color=plots.COLORS["blue"])
    a1.axvline(6 * meas.n_photos - 0.5, color=plots.COLORS["vermillion"], lw=1)
    a1.set_title(f"Jacobian {J.shape[0]} × {J.shape[1]}: {J.nnz} non-zeros ({100 * J.nnz / np.prod(J.shape):.2f} %)",
                 fontsize=10)
    a1.set_xlabel("unknowns: photos (6 each) | points (3 each)")
    a1.set_ylabel("equations")
    Jc = J[:, : 6 * meas.n_photos]
    Jp = J[:, 6 * meas.n_photos:]
    S = (Jc.T @ Jc) + (Jc.T @ Jp) @ (Jp.T @ Jc)
    a2.spy(sp.csr_matrix(S), markersize=0.6, color=plots.COLORS["green"])
    a2.set_title(f"reduced system S: {S.shape[0]} × {S.shape[1]}", fontsize=10)
    a2.set_xlabel("photo unknowns")
    return fig


def ellipse_figure(solution, ax=None, *, exaggeration: float = 600.0):
    """The gravimetric points with their standard error ellipses and true errors, both magnified."""
    fig, ax = plots.new_axes(ax, figsize=(7.6, 6.0))
    a = solution.adjustment
    m = a.meas
    sel = np.flatnonzero(m.point_kind == "field")
    cov = a.precision().cov_points[sel]
    A, Bax, th = B.error_ellipse(cov[:, :2, :2])
    for k, i in enumerate(sel):
        t = solution.survey.truth_of(m.point_ids[i])
        c = t[:2] / 1000.0
        e = Ellipse(c, 2 * A[k] * exaggeration / 1000.0, 2 * Bax[k] * exaggeration / 1000.0, angle=th[k],
                    fill=False, color=plots.COLORS["blue"], lw=1.5, label="standard error ellipse" if k == 0 else None)
        ax.add_patch(e)
        d = (a.xyz_m[i, :2] - t[:2]) * exaggeration / 1000.0
        ax.annotate("", xy=c + d, xytext=c, arrowprops=dict(arrowstyle="->", color=plots.COLORS["vermillion"], lw=1.5))
        ax.plot(*c, "*", color=plots.COLORS["vermillion"], ms=11, mec="black", mew=0.5,
                label="gravimetric point (true)" if k == 0 else None)
        ax.annotate(str(m.point_ids[i]), c, textcoords="offset points", xytext=(6, 6), fontsize=9)
    ax.plot([], [], color=plots.COLORS["vermillion"], label="true error of the adjusted point")
    c = solution.survey.block.centres_m / 1000.0
    ax.plot(c[:, 0], c[:, 1], "+", color=plots.COLORS["grey"], ms=5, ls="none", label="photo centres")
    ax.set_aspect("equal")
    ax.set_xlabel("X, km")
    ax.set_ylabel("Y, km")
    ax.set_title(f"ellipses and errors magnified ×{exaggeration:g}", fontsize=11)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2, fontsize=8)
    return fig


def accumulation_figure(mc: acc.StripMonteCarlo, ax=None, *, component: int = 2):
    """RMS errors of the Monte Carlo strips against the laws, log-log: free strip and both ends held."""
    fig, ax = plots.new_axes(ax, figsize=(7.6, 4.8))
    n = mc.free_links()[1:]
    r = mc.rms_free_mm()[1:, component]
    d, slope = acc.fit_accumulation(n, r, acc.free_strip_factor)
    name = "XYZ"[component]
    ax.loglog(n, r * 1000, "o", color=plots.COLORS["blue"], label=f"free strip, simulated (slope {slope:.2f})")
    nn = np.linspace(1, n.max(), 100)
    ax.loglog(nn, d * acc.free_strip_factor(nn) * 1000, "-", color=plots.COLORS["blue"], lw=1.2,
              label=f"(10.20) d·√(Σk²), d = {d * 1000:.1f} µm")
    L = mc.mid_n
    rm = mc.rms_mid_mm()[:, component]
    dm, sm = acc.fit_accumulation(L, rm, lambda k: np.array([acc.middle_factor_exact(int(x)) for x in np.atleast_1d(k)]))
    ax.loglog(L, rm * 1000, "s", color=plots.COLORS["vermillion"], label=f"both ends held, middle (slope {sm:.2f})")
    ax.loglog(L, dm * np.array([acc.middle_factor_exact(int(x)) for x in L]) * 1000, "-",
              color=plots.COLORS["vermillion"], lw=1.2, label="exact middle law √((n³ + 2n)/48)·d′")
    ax.loglog(L, d * acc.middle_factor_article(L) * 1000, "--", color=plots.COLORS["orange"], lw=1.2,
              label="article's recipe: (10.20) with n/2, halved, same d")
    ax.set_xlabel("n, links (bases)")
    ax.set_ylabel(f"RMS error in {name}, µm at the photo scale")
    ax.legend(fontsize=8, loc="upper left")
    return fig


def walk_figure(mc: acc.StripMonteCarlo, ax=None, *, component: int = 2, n_show: int = 12):
    """A few simulated strips' errors along the strip (the walk of a walk) inside the ±RMS envelope."""
    fig, ax = plots.new_axes(ax, figsize=(7.6, 4.4))
    k = np.arange(1, mc.n_bases + 1)
    e = mc.free_m[:, :, component] / mc.scale_m * 1000.0
    for r in range(min(n_show, len(e))):
        ax.plot(k, e[r], color=plots.COLORS["grey"], lw=0.8, alpha=0.8, label="single strips" if r == 0 else None)
    rms = np.sqrt(np.mean(e**2, axis=0))
    ax.plot(k, rms, color=plots.COLORS["blue"], lw=2.2, label="± RMS over all runs")
    ax.plot(k, -rms, color=plots.COLORS["blue"], lw=2.2)
    ax.axhline(0, color="black", lw=0.6)
    ax.set_xlabel("photo k along the strip (control on the first model)")
    ax.set_ylabel(f"error in {'XYZ'[component]}, µm at the photo scale")
    ax.legend(fontsize=9, loc="upper left")
    return fig

"""The live error budget of map updating (chapter 17, article 003).

:class:`BudgetView` draws the budget as bars: each stage's RMS planimetric error on the map (mm), the
root-sum-square total, and the map's tolerance — a mean error of 0.4 mm, i.e. an RMS error of
1.25 × 0.4 = 0.5 mm.  The dominant stage is vermillion; the total is green when the map meets the
tolerance.  :class:`BudgetDemo` binds sliders for the photo scale, the scanning resolution, the map
scale, the DEM stage (the instruction's tolerance, a DEM of given height accuracy, or none at all with
the relief left in) and the relief.  It opens on the article's 1:2000 case.  The model is
:func:`aerophoto.budget.budget`.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .. import budget as bu
from .. import plots
from ..i18n import t
from ..i18n.numfmt import fmt_number
from ..widgets import LiveDemo, Param

__all__ = ["BAR_KEYS", "BudgetView", "BudgetDemo", "budget_figure", "MAP_SCALES", "DTM_OPTIONS"]

#: the bars, top to bottom: the seven stages of formula (10), interior orientation, the total
BAR_KEYS = tuple(k for k, _s, _en, _ru in bu.STAGES) + ("interior", "total")
MAP_SCALES = (("1:500", 500.0), ("1:1000", 1000.0), ("1:2000", 2000.0), ("1:5000", 5000.0), ("1:10 000", 10_000.0),
              ("1:25 000", 25_000.0))
DTM_OPTIONS = (("instruction's tolerance (article)", "instruction"), ("DEM of accuracy m_h", "dem"),
               ("no DEM: mean plane, relief Δh", "plane"))
_C = plots.COLORS
_RMS_TOL = bu.MEAN_TO_RMS * bu.TOLERANCE_MEAN_MM


def _labels() -> list:
    names = {k: f"{en} ({sym})" for k, sym, en, _ru in bu.STAGES}
    names["interior"] = "interior orientation (m_вн.о.)"
    names["total"] = "TOTAL, formula (10)"
    return [names[k] for k in BAR_KEYS]


def _map_values(B: bu.Budget) -> np.ndarray:
    v = {s.key: s.rms_m / B.M_k * 1000.0 for s in B.stages}
    v["total"] = B.map_rms_mm
    return np.array([v.get(k, 0.0) for k in BAR_KEYS])


class BudgetView:
    """Horizontal bars: every stage's RMS error on the map (mm), the total and the 0.5 mm RMS tolerance."""

    def __init__(self, B: bu.Budget | None = None, ax=None):
        if ax is None:
            fig = plots.figure(figsize=(7.6, 5.2), layout="none")
            ax = fig.add_axes([0.42, 0.1, 0.55, 0.76])
        self.fig, self.ax = ax.figure, ax
        y = np.arange(len(BAR_KEYS))[::-1]
        self.bars = ax.barh(y, np.zeros(len(y)), color=_C["blue"], height=0.7)
        ax.set_yticks(y, _labels(), fontsize=10)
        ax.axvline(_RMS_TOL, color=_C["black"], ls="--", lw=1.2)
        self.tol_text = ax.text(_RMS_TOL, -0.75, "tolerance: 0.5 mm RMS = 0.4 mm mean ", fontsize=9,
                                va="center", ha="right")
        ax.set_ylim(-1.2, len(y) - 0.4)
        self.texts = [ax.text(0, yy, "", va="center", fontsize=9) for yy in y]
        ax.set_xlabel("RMS planimetric error on the map, mm")
        ax.grid(axis="y", visible=False)
        self.title = ax.set_title("")
        if B is not None:
            self.update(B)

    def update(self, B: bu.Budget) -> None:
        vals = _map_values(B)
        dom = BAR_KEYS.index(B.dominant.key)
        top = plots.coarse_ceil(max(1.0, 1.15 * float(vals.max())))  # a round limit: the axis seldom changes
        for i, (bar, v) in enumerate(zip(self.bars, vals)):
            bar.set_width(v)
            if BAR_KEYS[i] == "total":
                bar.set_color(_C["green"] if B.meets_tolerance else _C["vermillion"])
            else:
                bar.set_color(_C["vermillion"] if i == dom else _C["blue"])
            self.texts[i].set_position((v + 0.01 * top, self.texts[i].get_position()[1]))
            self.texts[i].set_text(f"{v:.3f}" if (v > 0 or BAR_KEYS[i] != "interior") else t("left out"))
        self.ax.set_xlim(0, top)
        verdict = t("≤ 0.4 mm: meets") if B.meets_tolerance else t("> 0.4 mm: fails")
        mk, mc = (fmt_number(x, 0) for x in (B.M_k, B.M_c))
        self.title.set_text(t("1:{mk} map, 1:{mc} photos\nv_d = {v:.2f} mm {verdict}", mk=mk, mc=mc, v=B.map_mean_mm,
                              verdict=verdict))


def _extra_table(B: bu.Budget, f_mm: float, relief_m: float, frame_mm: float) -> pd.DataFrame:
    r_max, r_rms = bu.working_area_radii_mm(frame_mm)
    h_lim = bu.relief_limit_m(f_mm, B.M_k, r_max)
    rows = [("total on the ground m_D", "m", f"{B.total_m:.3f}"), ("RMS on the map m_d", "mm", f"{B.map_rms_mm:.3f}"),
            ("mean on the map v_d = m_d/1.25", "mm", f"{B.map_mean_mm:.3f}"),
            ("meets v_d ≤ 0.4 mm", "", "yes" if B.meets_tolerance else "no"),
            ("largest stage", "", t("{stage} ({share} % of the variance)", stage=t(B.dominant.name),
                                    share=fmt_number(100 * B.shares()[B.dominant.key], 0))),
            ("relief limit h_пред = 0.3·f·M_k/r_max (2)", "m", f"{h_lim:.2f}"),
            ("relief Δh/2 within it?", "", "yes: a plane would do" if relief_m / 2 <= h_lim else "no: a DEM is needed")]
    return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def _stage_table(B: bu.Budget) -> pd.DataFrame:
    df = B.table()[["symbol", "RMS on the ground, m", "RMS on the map, mm", "share of variance, %"]]
    df.index = [i.split(" (")[0] for i in df.index]
    return df


class BudgetDemo(LiveDemo):
    """Live budget of map updating: photo scale, scanning, map scale, the DEM stage and the relief."""

    title = "The error budget of updating a map (article 003)"
    hint = ("Every bar is one stage's RMS error on the map; the total is their root-sum-square. Find what dominates, "
            "then ask what would have to change to bring the mean error under 0.4 mm.")
    params = (
        Param("M_c", "1:M_c (photo)", 5000, 40000, 500, 10000, group="Photos", help="photo-scale denominator"),
        Param("P_um", "P, µm", 5, 60, 1, 16, group="Photos", help="scanning resolution (pixel size)"),
        Param("f_mm", "f, mm", 70, 310, 1, 153, group="Photos", help="focal length (the article: 153 mm)"),
        Param("M_k", "1:M_k (map)", kind="choice", options=MAP_SCALES, default=2000.0, group="Map"),
        Param("dtm", "DEM stage", kind="choice", options=DTM_OPTIONS, default="instruction", group="Ground"),
        Param("m_h_m", "m_h, m", 0.0, 5.0, 0.05, 1.0, group="Ground", help="RMS height error of the DEM"),
        Param("relief_m", "Δh, m", 0, 200, 5, 30, group="Ground", help="relief within a photo, max − min"),
        Param("extra", "closing paragraph's errors", kind="choice", options=(("left out", "off"), ("in", "on")),
              default="off", group="Map", help="interior orientation and σ = 0.884·P"),
    )

    frame_mm = 230.0

    def build(self):
        self.view = BudgetView()
        self.fig = self.view.fig
        v = self.view
        # a move resizes and recolours the bars and moves their numbers and the title over the cached stage names
        # and mm axis; the axis' limit is a round value (1, 1.25, 1.6, 2 … mm) beyond the longest bar, so only a move
        # that outgrows it or leaves it far behind is a full draw
        self.animated = (*v.bars, *v.texts, v.title)
        plots.steady_limits(v.ax, snap=False)  # the same limits again are no change

    def compute(self, M_c, P_um, f_mm, M_k, dtm, m_h_m, relief_m, extra):
        return bu.budget(M_c, P_um, M_k, f_mm=f_mm, frame_mm=self.frame_mm, dtm=dtm, m_h_m=m_h_m,
                         relief_m=relief_m, extra_stages=(extra == "on"))

    def render(self, B: bu.Budget):
        self.view.update(B)
        v = self.values
        self.table.value = (plots.html_table(_extra_table(B, v["f_mm"], v["relief_m"], self.frame_mm),
                                             caption="The map") +
                            plots.html_table(_stage_table(B), caption="The stages", float_format="{:.3f}"))


def budget_figure(B: bu.Budget, ax=None):
    """The budget's bars as a static figure (the same view as the live demo)."""
    view = BudgetView(B, ax=ax)
    return view.fig

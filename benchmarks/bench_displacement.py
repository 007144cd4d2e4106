"""The displacement explorer (chapters 03–04): live update in place vs the naive re-create-and-render way.

Both are driven through the same cycle of slider changes (f, 1:m, α, λ, relief).

* ``live``: ``demo.set(...)`` (compute, move the artists, refresh the table) followed by a forced Agg draw
  ``demo.draw(force=True)``.  With ipympl, ``draw_idle`` only asks the browser to fetch a new frame and the
  kernel then draws once; headless Agg would draw inside ``draw_idle`` as well, so the benchmark stubs
  ``draw_idle`` on this canvas and counts the one forced draw.
* ``live_png``: the same plus encoding the frame as PNG, as ipympl does before sending it (full frame; ipympl
  usually sends a smaller diff).
* ``naive``: an ``interact``-style callback that builds a new figure, draws the grid and the three quivers and
  renders a PNG into memory each time (what ``ipywidgets.interact`` + ``%matplotlib inline`` does).

The students' lab sheets and the measuring tool (issue 12) are timed too (``lab``): designing the sheets of all
100 variants, rendering one student's photo (1024 px) and plan, building the two tools, and one click (the
reading recorded, the table and the code lines refreshed, the figure drawn: what the kernel does per click).
"""

from __future__ import annotations

import contextlib
import io
import time

from _timing import summarize, time_demo_moves


def _cycle(n: int):
    """n slider changes cycling f, m, α, λ and relief through their ranges."""
    fs = [100, 150, 200, 120, 300, 90]
    ms = [12000, 8000, 20000, 15000, 6000]
    alphas = [3.0, 0.5, 6.0, 10.0, 1.5, 14.0, 2.0]
    lams = [-60, -30, 0, 45, 120, -150, 170]
    reliefs = [60, 0, 120, 200, 30]
    out = []
    for i in range(n):
        k = i % 5
        if k == 0:
            out.append({"f_mm": fs[(i // 5) % len(fs)]})
        elif k == 1:
            out.append({"m": ms[(i // 5) % len(ms)]})
        elif k == 2:
            out.append({"alpha_deg": alphas[(i // 5) % len(alphas)]})
        elif k == 3:
            out.append({"lambda_deg": lams[(i // 5) % len(lams)]})
        else:
            out.append({"relief_m": reliefs[(i // 5) % len(reliefs)]})
    return out


def _naive_render(values: dict) -> int:
    import matplotlib.pyplot as plt
    import numpy as np

    from aerophoto import geometry as g
    from aerophoto import plots
    from aerophoto.demos.displacement import displacement_field, nice_factor

    field = displacement_field(values["f_mm"], values["m"], values["alpha_deg"], values["lambda_deg"],
                                 values["relief_m"], grid_n=9)
    fig = plt.figure(figsize=(6.0, 5.9))
    ax = fig.add_subplot(1, 1, 1)
    rv, tv, av = field.relief_vectors_mm, field.tilt_vectors_mm, field.tilt_approx_vectors_mm
    k = nice_factor(max(np.max(np.hypot(*rv.T)), np.max(np.hypot(*tv.T))))
    grid = field.grid_mm
    plots.photo_frame(ax, g.Camera())
    ax.scatter(grid[:, 0], grid[:, 1], c=field.h_m, s=16, cmap="BrBG_r")
    kw = dict(angles="xy", scale_units="xy", scale=1.0)
    ax.quiver(grid[:, 0], grid[:, 1], k * rv[:, 0], k * rv[:, 1], color=plots.COLORS["relief"], **kw)
    ax.quiver(*(grid - k * tv).T, k * tv[:, 0], k * tv[:, 1], color=plots.COLORS["tilt"], **kw)
    ax.quiver(*(grid - k * av).T, k * av[:, 0], k * av[:, 1], color=plots.COLORS["approx"], **kw)
    plots.mark_points(ax, {"o": field.o_mm, "n": field.n_mm, "c": field.c_mm})
    ax.set_xlim(-100, 100)
    ax.set_ylim(-100, 100)
    ax.set_title(f"arrows ×{k}")
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    plt.close(fig)
    return len(buf.getvalue())


def run(quick: bool = False) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto import plots

    # both ways run under the book's style (aerophoto.setup applies it in every notebook)
    with plots.style_context():
        out = _run(quick)
        out["lab"] = _lab(quick)
        return out


def _lab(quick: bool) -> dict:
    """The lab sheets of chapters 03–04 and the measuring tool: build times and the kernel side of a click."""
    from _timing import measure

    from aerophoto.demos.measure import photo_tool, plan_tool
    from aerophoto.site import get_site
    from aerophoto.labs import displacement as lab

    t0 = time.perf_counter()
    get_site()
    t_site = time.perf_counter() - t0
    lab.relief_sheet.cache_clear()
    lab.tilt_sheet.cache_clear()
    t0 = time.perf_counter()
    for i in range(100):
        lab.relief_sheet(i)
        lab.tilt_sheet(i)
    t_sheets = time.perf_counter() - t0
    sheet = lab.relief_sheet(57)
    t_photo = measure(lambda: (lab.photo_of.cache_clear(), sheet.photo()), 2 if quick else 4, warmup=1)
    t_plan = measure(lambda: (lab.plan_of.cache_clear(), sheet.plan()), 2 if quick else 4, warmup=1)
    t_tool = measure(lambda: photo_tool(sheet).close(), 2 if quick else 4, warmup=1)
    tool = photo_tool(sheet)
    with contextlib.redirect_stdout(io.StringIO()):  # headless (Agg): the widget shows the figure as an Output
        tool.widget()
    canvas = tool.fig.canvas
    canvas.draw_idle = lambda *a, **k: None  # ipympl only schedules; the forced draw below counts
    marks = list(sheet.marks("photo").values())

    def click(k):
        x, y = marks[k % len(marks)]
        tool.select(sheet.names[k % len(marks)])
        tool.click(x + 0.03, y - 0.02)
        canvas.draw()

    clicks = measure(click, 10 if quick else 30, args_for=lambda k: (k,))
    tool.close()
    plan = plan_tool(sheet)
    plan.close()
    return {
        "site_build_s": round(t_site, 2),
        "sheets_all_100_variants_both_kinds_s": round(t_sheets, 2),
        "render_photo_1024px": t_photo,
        "plan_image": t_plan,
        "photo_tool_build": t_tool,
        "click_reading_table_draw": clicks,
        "target": "click p95 ≤ 100 ms (kernel side)",
    }


def _run(quick: bool) -> dict:
    from aerophoto.demos.displacement import DisplacementDemo

    n = 20 if quick else 60
    changes = _cycle(n)
    demo = DisplacementDemo()
    for ch in changes[:3]:  # warm-up
        demo.set(**ch)
    demo.reset()
    moves = time_demo_moves(demo, changes)  # set + forced Agg draw + PNG frame per change (benchmarks/_timing.py)
    n_updates = demo.n_updates

    values = dict(demo.values)
    _naive_render(values)  # warm-up
    naive = []
    for ch in changes:
        values.update(ch)
        t0 = time.perf_counter()
        _naive_render(values)
        naive.append(time.perf_counter() - t0)
    demo.close()

    s_live, s_png, s_naive = moves["live_set_plus_agg_draw"], moves["live_plus_png_encode"], summarize(naive)
    return {
        "slider_changes": n,
        "figure_px": moves["figure_px"],
        "n_updates": n_updates,
        "compute_render_only": moves["compute_render_only"],
        "live_set_plus_agg_draw": s_live,
        "live_plus_png_encode": s_png,
        "naive_new_figure_png": s_naive,
        "speedup_median_naive_over_live": round(s_naive["median_ms"] / s_live["median_ms"], 2),
        "speedup_p95_naive_over_live": round(s_naive["p95_ms"] / s_live["p95_ms"], 2),
        "speedup_median_naive_over_live_png": round(s_naive["median_ms"] / s_png["median_ms"], 2),
        "style": "the book's (plots.STYLE, as after aerophoto.setup)",
        "target": "p95 ≤ 50 ms for live_set_plus_agg_draw and ≥ 3× faster than naive",
    }

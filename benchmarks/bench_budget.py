"""Chapter 17: the live error budget's update (kernel side).

``live_set_plus_agg_draw``: ``demo.set(...)`` (the budget, the bars, the two tables) and one forced Agg draw
(``draw_idle`` stubbed as in ipympl), cycling the photo scale, the scanning resolution, the map scale, the DEM
stage, m_h, the relief and the closing paragraph's errors; ``live_plus_png_encode`` adds the PNG encoding;
``live_cpu_time`` is the process CPU time of set + draw (less sensitive to a shared machine's load).
"""

from __future__ import annotations


from _timing import in_book_style, time_demo_moves


def _cycle(n: int) -> list:
    mcs = [10000, 15000, 25000, 6000, 40000]
    ps = [16, 42, 8, 25, 60]
    mks = [2000.0, 10000.0, 500.0, 25000.0, 5000.0]
    dtms = ["instruction", "dem", "plane"]
    out = []
    for i in range(n):
        k, j = i % 6, i // 6
        out.append([{"M_c": mcs[j % 5]}, {"P_um": ps[j % 5]}, {"M_k": mks[j % 5]}, {"dtm": dtms[j % 3]},
                    {"m_h_m": [0.2, 1.0, 3.0][j % 3], "relief_m": [10, 60, 150][j % 3]},
                    {"extra": "on" if j % 2 else "off"}][k])
    return out


def run(quick: bool = False) -> dict:
    return in_book_style(_run, quick)


def _run(quick: bool) -> dict:

    from aerophoto.demos.error_budget import BudgetDemo

    n = 24 if quick else 72
    demo = BudgetDemo()
    canvas = demo.fig.canvas
    canvas.draw_idle = lambda *a, **k: None
    demo.draw(force=True)
    moves = time_demo_moves(demo, _cycle(n))
    demo.close()
    return {"slider_changes": n, **moves, "target": "p95 ≤ 100 ms for live_set_plus_agg_draw"}

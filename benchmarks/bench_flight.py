"""Survey planning (chapter 01): the calculation, the layout and the live demo's update and draw."""

from __future__ import annotations

import os

os.environ.setdefault("MPLBACKEND", "Agg")

from _timing import measure  # noqa: E402  (registered by benchmarks/run.py)


def run(quick: bool = False) -> dict:
    import matplotlib.pyplot as plt

    from aerophoto import flight
    from aerophoto import guide
    from aerophoto.demos.flight_plan import FlightPlanDemo
    from aerophoto.variants import variant_for_index

    n = 20 if quick else 200
    v0, v99 = variant_for_index(0), variant_for_index(99)
    out = {
        "plan_variant00": measure(lambda: flight.plan(v0), n),
        "plan_and_layout_variant99": measure(lambda: flight.layout(flight.plan(v99)), n),
        "audit": measure(guide.ch01.worked_example, max(5, n // 10)),
    }
    # the demo: recompute + move artists (what a slider callback does before the draw), then one draw
    cases = {
        "variant00": {},
        "variant99": dict(f_mm=1090, m=21900, W_kmh=1190, Lx_km=124, Ly_km=129),
        "largest_plan": dict(f_mm=100, m=5000, px_percent=75, py_percent=60, h_m=250, Lx_km=150, Ly_km=150),
    }
    demo = FlightPlanDemo()
    k = 10 if quick else 60
    for name, values in cases.items():
        demo.reset()
        demo.set(**values)
        base_m = demo.values["m"]
        # alternate the scale by one slider step so every call really changes the plan
        ms = [base_m, base_m + 100 if base_m + 100 <= 30000 else base_m - 100]

        def update(i, ms=ms):
            demo.values["m"] = ms[i % 2]
            demo.render(demo.compute(**demo.values))

        out[f"demo_update_{name}"] = measure(update, k, args_for=lambda i: (i,))
        out[f"demo_update_{name}"]["N"] = demo.result.plan.N
        out[f"demo_draw_{name}"] = measure(lambda: demo.fig.canvas.draw(), max(5, k // 3))
    demo.close()
    plt.close("all")
    return out

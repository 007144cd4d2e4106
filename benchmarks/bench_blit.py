"""Kernel side of a slider move with and without blitting (LiveDemo.animated, blit.Blitter), same run.

    python benchmarks/run.py blit

For each demo that declares animated artists: ``demo.set(...)`` on the headline slider of the benchmark
(alternating two values) on an Agg canvas, where ``draw_idle`` draws at once — so one sample is compute +
render + the draw the demo does (a blit, or a full draw when something static changed).  ``full`` is the
same demo with blitting switched off (``AEROPHOTO_BLIT=0``): every move a full draw, as before.
Medians and p95 in ms; the machine's load is recorded beside them.
"""

from __future__ import annotations

import importlib
import os

from _timing import measure

#: demo → (module, class, parameter, two values a move alternates between)
DEMOS = {
    "footprint": ("footprint", "FootprintDemo", "f_mm", (100, 150)),
    "footprint_alpha": ("footprint", "FootprintDemo", "alpha_deg", (3, 5)),
    "conditions": ("interpretation", "ConditionsDemo", "visibility_km", (30, 20)),
    "spectral": ("spectral_explorer", "SpectralExplorerDemo", "moisture_pct", (18, 28)),
    "reduction": ("reduction", "ReductionDemo", "f_mm", (100, 150)),
    "flight_plan": ("flight_plan", "FlightPlanDemo", "f_mm", (100, 110)),
    "key": ("interpretation", "KeyDemo", "row", (1, 2)),
    "relief": ("displacement", "ReliefDemo", "relief_m", (60, 65)),
    "tilt": ("displacement", "TiltDemo", "alpha_deg", (3, 3.25)),
    "floating_mark": ("stereo", "FloatingMarkDemo", "p_mm", (72.5, 72.8)),
    "base_height": ("stereo", "BaseHeightDemo", "B_m", (864, 874)),
    "plan_correction": ("plan_correction", "PlanCorrectionDemo", "alpha_deg", (3, 3.5)),
    "control_design": ("control", "ControlDesignDemo", "m_eps_arcmin", (4.5, 5)),
    "control_scale": ("control", "ControlDesignDemo", "m", (12000, 12500)),
    "resection": ("control", "ResectionDemo", "north_m", (-150, -140)),
    "transformer": ("rectification", "TransformerDemo", "step", (1, 2)),
    "block_error": ("block_accuracy", "BlockErrorDemo", "sigma_um", (7, 8)),
    "contours": ("dem_contours", "ContourDemo", "mz_m", (0.12, 0.13)),
    "budget": ("error_budget", "BudgetDemo", "M_c", (10000, 10500)),
}


def _one(module, cls, name, values, n, blit: bool) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    old = os.environ.get("AEROPHOTO_BLIT")
    os.environ["AEROPHOTO_BLIT"] = "1" if blit else "0"
    try:
        demo = getattr(importlib.import_module(f"aerophoto.demos.{module}"), cls)()
    finally:
        if old is None:
            os.environ.pop("AEROPHOTO_BLIT")
        else:
            os.environ["AEROPHOTO_BLIT"] = old
    demo.fig.canvas.draw()
    out = measure(lambda v: demo.set(**{name: v}), n, args_for=lambda i: (values[i % 2],))
    if demo.blitter is not None:
        out["blits"], out["full_draws"] = demo.blitter.n_blit, demo.blitter.n_full
    demo.close()
    return out


def run(quick: bool = False) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto import plots

    with plots.style_context():  # as in every notebook (aerophoto.setup)
        return _run(quick)


def _run(quick: bool) -> dict:
    n = 10 if quick else 30
    res = {"load_before": os.getloadavg()}
    for key, (module, cls, name, values) in DEMOS.items():
        if not _declares(module, cls):
            continue
        res[key] = {"blit": _one(module, cls, name, values, n, True), "full": _one(module, cls, name, values, n, False)}
    res["load_after"] = os.getloadavg()
    return res


def _declares(module, cls) -> bool:
    import inspect

    src = inspect.getsource(getattr(importlib.import_module(f"aerophoto.demos.{module}"), cls).build)
    return "animated" in src

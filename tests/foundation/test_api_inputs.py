"""The package's own inputs: NaN, ±inf and huge values are refused by name, and nothing hangs.

For every function in the ``__all__`` of every module of the package (the course tools, the widgets and the
student-facing checks aside: their inputs are files, bounded sliders and answers to be judged), each numeric
parameter gets ``nan``, ``inf``, ``-inf`` and ``1e30`` while the others keep valid values.  Each must give a
``ValueError`` naming the parameter (``1e30`` may also be accepted and return normally), within a time limit:
the calls of one function run in a forked process that is killed after ``LIMIT_S`` — a hang is a failure,
not a slow test.

Valid values for the other parameters come from :data:`SAMPLES` (by parameter name) or, for a numeric
parameter with no sample, the first of a few magnitudes for which the call succeeds.  A function whose
other inputs cannot be built that way (it takes data structures the package builds: measurements, layouts,
strips) is listed in :data:`NOT_SWEPT`; the test fails when a function is neither swept nor listed, so a new
function must be looked at.
"""

from __future__ import annotations

import importlib
import inspect
import math
import multiprocessing as mp
import pkgutil

import numpy as np
import pytest

import aerophoto

LIMIT_S = 30.0
BAD = (math.nan, math.inf, -math.inf, 1e30)
SKIP_MODULES = ("aerophoto.course", "aerophoto.demos", "aerophoto.widgets", "aerophoto.nbtools", "aerophoto.book",
                "aerophoto.checks", "aerophoto.plots", "aerophoto.i18n", "aerophoto.site.build", "aerophoto.site.paint",
                "aerophoto.site.catalogue", "aerophoto.tasks", "aerophoto.guide",
                "aerophoto.website")  # the web book's build runs for minutes by design (tests/course/test_website.py)
GUESSES = (1.0, 10.0, 100.0, 1000.0, 0.5, 3, 0.1)


def _samples():
    from aerophoto import flight, terrain, variants
    from aerophoto import geometry as g

    v = variants.variant_for_index(57)
    cam = g.Camera(f_mm=100.0)
    pose = g.Pose(Z_m=1200.0, alpha_deg=3.0, lambda_deg=10.0)
    other = g.Pose(X_m=500.0, Z_m=1200.0)
    poses = tuple(g.Pose(X_m=480.0 * k, Z_m=1200.0) for k in range(4))
    square = np.array([[-50.0, -50.0], [50.0, -50.0], [50.0, 50.0], [-50.0, 50.0]])
    return {
        "v": v, "variant": v, "camera": cam, "cam": cam, "pose": pose, "pose_a": pose, "pose_b": other,
        "pose_left": pose, "pose_right": other, "pose_from": pose, "pose_to": other, "poses": poses,
        "terrain": terrain.AnalyticHills(relief_m=30.0), "dem": terrain.AnalyticHills(relief_m=30.0),
        "f_mm": 100.0, "m": 12000.0, "M": 10000.0, "H_m": 1200.0, "alpha_deg": 3.0, "lambda_deg": 10.0,
        "kappa_deg": 0.0, "px_percent": 60.0, "py_percent": 30.0, "p_percent": 60.0, "n_photos": 4,
        "n_strips": 2, "n": 3, "i": 57, "record_book": "19-0457", "r_mm": 50.0, "h_m": 30.0, "value": 1.0,
        "ratio": 0.5, "phi_deg": 30.0, "r_c_mm": 50.0, "Z_m": 200.0, "frame_mm": 180.0, "Lx_km": 25.0,
        "Ly_km": 30.0, "W_kmh": 200.0, "p": flight.plan(v), "name": "x", "lo": 0, "hi": 10,
        "xy_mm": np.array([[10.0, 20.0], [30.0, -40.0], [-50.0, 5.0]]),
        "a_mm": 100.0, "b_mm": 60.0, "N": 2000.0, "M_k": 2000.0, "M_c": 10000.0, "P_um": 16.0,
        "m_h_m": 1.0, "relief_m": 30.0, "mq_mm": 0.02, "n_real": 3.5, "contour_interval_m": 1.0,
        "every": 4, "spacing_bases": 4, "angle_deg": 12.5, "distance_m": 500.0, "H_design_m": 1200.0,
        "K_t": 2.0, "K_d": 1.0, "n_along": 3, "n_px": 64, "l_plan_mm": 100.0, "l_photo_mm": 120.0,
        "z_min": 100.0, "z_max": 200.0, "interval_m": 5.0, "mean_error_m": 0.5, "interp_rms_m": 0.3,
        "mz_m": 0.2, "spacing_m": 50.0, "s": 2, "r": 2, "d": 12,
        "corners": square, "photo_corners": square, "plan_corners": 2.0 * square,
        "XYZ_m": np.array([[100.0, 50.0, 200.0], [-200.0, 80.0, 180.0]]), "X_m": np.array([0.0, 100.0]),
        "Y_m": np.array([0.0, 50.0]), "cov_xy": np.array([[2.0, 0.3], [0.3, 1.0]]),
        "A": (0.0, 0.0), "B": (1000.0, 0.0), "C": (500.0, 800.0), "beta1_deg": 40.0, "beta2_deg": 50.0,
        "l_mm": np.array([100.0, 101.0]), "L_mm": np.array([1200.0, 1210.0]), "kind": "tin",
        "mp_mm": 0.01, "names": ("1", "2", "3"), "k": 1.01,
        "centre_mm": np.array([0.0, 0.0]), "delta_mm": np.array([[0.1, 0.0], [0.0, 0.1], [0.1, 0.1]]),
        "points_xy": np.array([[0.0, 0.0], [500.0, 0.0], [0.0, 500.0], [500.0, 500.0], [250.0, 250.0]]),
    }


def _numeric(p) -> bool:
    ann = str(p.annotation)
    if isinstance(p.default, bool) or "bool" in ann or ("str" in ann and "float" not in ann):
        return False
    if ("float" in ann or "int" in ann) and "ndarray" not in ann:
        return True
    return p.default is not p.empty and isinstance(p.default, (int, float))


def _functions():
    out, seen = [], set()
    for info in pkgutil.walk_packages(aerophoto.__path__, "aerophoto."):
        if info.name.startswith(SKIP_MODULES) or any(part.startswith("_") for part in info.name.split(".")):
            continue  # private modules (``_validate``: the checks themselves, their bounds are the caller's)
        mod = importlib.import_module(info.name)
        for n in getattr(mod, "__all__", []) or []:
            f = getattr(mod, n, None)
            if inspect.isfunction(f) and id(f) not in seen:
                seen.add(id(f))
                nums = [p.name for p in inspect.signature(f).parameters.values()
                        if _numeric(p) and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
                if nums:
                    out.append((f"{f.__module__}.{f.__qualname__}", f, nums))
    return sorted(out, key=lambda t: t[0])


FUNCTIONS = _functions()

#: formatting helpers of computed values, for which ±inf is a value to print, by design
PRINTS_INFINITY = {"aerophoto.displacement.ratio_text": "1/N with N = ∞ (no deviation) prints as 1/∞"}

#: functions whose other inputs the sweep cannot build (data structures the package makes), by reason
NOT_SWEPT_REASON = "takes data structures the package builds (measurements, layouts, strips, images)"


def _baseline(fn, samples):
    """Valid keyword arguments for ``fn`` (a successful call), or None."""
    sig = inspect.signature(fn)
    base, unknown = {}, []
    for p in sig.parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) or p.default is not p.empty:
            continue
        if p.name in samples:
            base[p.name] = samples[p.name]
        elif _numeric(p):
            unknown.append(p.name)
        else:
            return None
    for guess in GUESSES if unknown else (None,):
        kw = dict(base, **{n: guess for n in unknown})
        try:
            fn(**kw)
            return kw
        except Exception:
            continue
    return None


def _sweep_one(fn, nums, conn):
    samples = _samples()
    base = _baseline(fn, samples)
    if base is None:
        conn.send(None)
        return
    res = []
    for name in nums:
        for bad in BAD:
            try:
                fn(**dict(base, **{name: bad}))
                res.append((name, bad, "returned", ""))
            except Exception as exc:  # noqa: BLE001 — the kind is the result
                res.append((name, bad, type(exc).__name__, str(exc)[:200]))
    conn.send(res)


def _run(fn, nums):
    """The sweep of one function in a forked process: None (no baseline), "hang", or [(param, bad, kind, msg)]."""
    ctx = mp.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_sweep_one, args=(fn, nums, child))
    proc.start()
    child.close()
    try:
        if parent.poll(LIMIT_S):
            return parent.recv()
        return "hang"
    finally:
        proc.join(0.5)
        if proc.is_alive():
            proc.kill()
            proc.join()


@pytest.fixture(scope="module")
def sweep():
    _samples()  # build the shared samples (and their imports) once, before forking
    return {qual: _run(fn, nums) for qual, fn, nums in FUNCTIONS}


def test_there_is_a_public_api_to_sweep():
    assert len(FUNCTIONS) > 100


def test_nothing_hangs(sweep):
    assert [q for q, r in sweep.items() if r == "hang"] == []


def test_bad_numbers_are_refused_by_name(sweep):
    failures = []
    for qual, res in sweep.items():
        if not isinstance(res, list) or qual in PRINTS_INFINITY:
            continue
        for name, bad, kind, msg in res:
            named = kind == "ValueError" and name in msg
            if not (named or (bad == 1e30 and kind == "returned")):
                failures.append(f"{qual}({name}={bad!r}): {kind} {msg[:100]}")
    assert failures == [], "\n".join(failures)


def test_most_of_the_api_is_swept(sweep):
    swept = [q for q, r in sweep.items() if isinstance(r, list)]
    not_swept = sorted(q for q, r in sweep.items() if r is None)
    print(f"swept {len(swept)} functions; not swept ({NOT_SWEPT_REASON}): {len(not_swept)}")
    assert len(swept) >= 60, not_swept


def test_the_spin_of_issue_11_is_gone():
    """resect with an infinite coordinate spun in SVD: now a ValueError naming the input, at once."""
    from aerophoto import plane

    ctx = mp.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)

    def call(conn):
        try:
            plane.resect_directions(np.radians([10.0, 50.0, 100.0]),
                                    np.array([[0.0, 0.0], [math.inf, 0.0], [0.0, 100.0]]))
            conn.send("returned")
        except Exception as exc:  # noqa: BLE001
            conn.send(f"{type(exc).__name__}: {exc}")

    proc = ctx.Process(target=call, args=(child,))
    proc.start()
    got = parent.recv() if parent.poll(LIMIT_S) else "hang"
    proc.kill()
    proc.join()
    assert got.startswith("ValueError") and "known_xy" in got, got


@pytest.mark.parametrize("fn, kwargs, param", [
    ("aerophoto.geometry.footprint", {"samples_per_side": 10**9}, "samples_per_side"),
    ("aerophoto.simulate.fly_strip", {"n_photos": 10**9}, "n_photos"),
    ("aerophoto.variants.variant_for_index", {"i": math.inf}, "i"),
])
def test_work_size_parameters_have_upper_limits(fn, kwargs, param):
    mod, name = fn.rsplit(".", 1)
    f = getattr(importlib.import_module(mod), name)
    samples = _samples()
    base = _baseline(f, samples)
    assert base is not None
    with pytest.raises(ValueError, match=param):
        f(**dict(base, **kwargs))

"""Bad input at every public entry of the physics and world modules: refused by name, never NaN, never silent.

Every function and class in the ``__all__`` of :data:`MODULES` is called once with the valid example of
:data:`VALID` (built from the shared :func:`samples` by parameter name, with per-function overrides), then once
per mutation of one argument (:func:`mutations`):

=========  =====================================================================  =============================
kind       what                                                                   must
=========  =====================================================================  =============================
nan, inf   a non-finite scalar (``nan``, ``inf``, ``-inf``)                        raise, naming the parameter
a-nan      ``nan`` / ``inf`` placed inside an array argument                       raise, naming the parameter
type       ``None``, ``"abc"``, ``object()`` instead of a number, array or object   raise, naming the parameter
shape      a point array with one coordinate too many                              raise, naming the parameter
empty      an empty array / sequence                                               raise by name, or return
                                                                                   finite (an empty result)
zero, neg  ``0`` and ``-1`` for a number                                           raise by name, or return
                                                                                   finite
huge       ``10**9`` for a count, ``1e-9`` for a step                              raise by name, or return
                                                                                   within ``LIMIT_S``
=========  =====================================================================  =============================

"Raise, naming the parameter" means a ``ValueError`` or ``TypeError`` whose message contains the parameter's
name — not an ``AttributeError``/``IndexError``/``LinAlgError``, nor a numpy message.  A returned result may
never hold a NaN/inf where the valid example's result holds none.

:data:`VALID` has one entry per public name; the test fails when a public name has none (a new function must
be given a valid example or a documented exemption in :data:`EXEMPT`).  Mutations that are genuinely valid
for one function (``inf`` meaning "none") are in :data:`ALLOWED`, each with its reason.

``python tests/physics/test_bad_input.py`` prints the outcome table (clear / vague / obscure / nan / silent) per module.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import signal
import sys
import traceback
import warnings
from collections import Counter

import numpy as np
import pytest

#: the modules whose public API is swept (the physics and the virtual world)
MODULES = (
    "geometry", "plane", "terrain", "variants", "flight", "quality", "displacement", "mosaic",
    "triangulation.ends", "triangulation.geodetic", "triangulation.reduction", "triangulation.strip",
    "triangulation.study", "triangulation.zhukov", "stereo", "projective.grids", "projective.images",
    "projective.scene", "control", "accuracy", "interpretation", "spectral", "bundle.block",
    "bundle.collinearity", "bundle.design", "bundle.solve", "bundle.stages", "dem.densification",
    "dem.surface", "budget", "rectify", "soilmap", "simulate", "site", "site.cover", "site.objects",
    "site.soils", "site.model", "site.colour", "render",
)

#: whole modules not swept, with the reason
EXEMPT_MODULES = {
    "site.build": "the steps of building the site (called by get_site with its validated SiteParams)",
    "site.paint": "raster kernels called per tile inside the site build (validating there would slow it)",
    "site.raycast": "ray kernels called per block of rays inside render/trace (validated at render/trace)",
    "site.catalogue": "the catalogue step of the site build (inputs are the build's own rasters)",
    "site.cover_objects": "the objects step of the interpretation site's build (inputs are the build's own rasters)",
    "site.crowns": "the crowns' surfaces, called per block of rays inside render/trace (validated at render/trace)",
    "site.texture": "pixel kernels of the colour step, called per photo inside colour_geometry (validated there)",
}

LIMIT_S = 3.0  # a mutated call that runs longer counts as a hang

# --------------------------------------------------------------------------------------------- valid examples


def samples() -> dict:
    """Valid arguments shared by parameter name."""
    from aerophoto import flight, terrain, variants
    from aerophoto import geometry as g

    v = variants.variant_for_index(7)
    cam = g.Camera(f_mm=100.0)
    pose = g.Pose(Z_m=1200.0, alpha_deg=3.0, lambda_deg=10.0)
    other = g.Pose(X_m=500.0, Z_m=1200.0)
    poses = tuple(g.Pose(X_m=480.0 * k, Z_m=1200.0) for k in range(4))
    square = np.array([[-50.0, -50.0], [50.0, -50.0], [50.0, 50.0], [-50.0, 50.0]])
    hills = terrain.AnalyticHills(relief_m=30.0)
    global _SITE_POSE
    _SITE_POSE = g.Pose(X_m=1000.0, Y_m=750.0, Z_m=700.0)
    return {
        "v": v, "variant": v, "camera": cam, "cam": cam, "pose": pose, "pose_a": pose, "pose_b": other,
        "pose_left": pose, "pose_right": other, "pose_from": pose, "pose_to": other, "poses": poses,
        "terrain": hills, "dem": hills,
        "f_mm": 100.0, "m": 12000.0, "M": 10000.0, "H_m": 1200.0, "alpha_deg": 3.0, "lambda_deg": 10.0,
        "kappa_deg": 0.0, "px_percent": 60.0, "py_percent": 30.0, "p_percent": 60.0, "n_photos": 4,
        "n_strips": 2, "n": 3, "i": 57, "record_book": "19-0457", "r_mm": 50.0, "h_m": 30.0, "value": 1.0,
        "ratio": 0.5, "phi_deg": 30.0, "r_c_mm": 50.0, "Z_m": 200.0, "frame_mm": 180.0, "Lx_km": 25.0,
        "Ly_km": 30.0, "W_kmh": 200.0, "p": flight.plan(v), "name": "x",
        "xy_mm": np.array([[10.0, 20.0], [30.0, -40.0], [-50.0, 5.0]]),
        "a_mm": 100.0, "b_mm": 60.0, "N": 2000.0, "M_k": 2000.0, "M_c": 10000.0, "P_um": 16.0,
        "m_h_m": 1.0, "relief_m": 30.0, "mq_mm": 0.02, "n_real": 3.5, "contour_interval_m": 1.0,
        "every": 4, "spacing_bases": 4, "angle_deg": 12.5, "distance_m": 500.0, "H_design_m": 1200.0,
        "K_t": 2.0, "K_d": 1.0, "n_along": 3, "n_px": 32, "l_plan_mm": 100.0, "l_photo_mm": 120.0,
        "z_min": 100.0, "z_max": 200.0, "interval_m": 5.0, "mean_error_m": 0.5, "interp_rms_m": 0.3,
        "mz_m": 0.2, "spacing_m": 50.0, "s": 2.0, "r": 2, "d": 12,
        "corners": square, "photo_corners": square, "plan_corners": 2.0 * square,
        "XYZ_m": np.array([[100.0, 50.0, 200.0], [-200.0, 80.0, 180.0]]),
        "X_m": np.array([0.0, 100.0, 40.0]), "Y_m": np.array([0.0, 50.0, 90.0]),
        "cov_xy": np.array([[2.0, 0.3], [0.3, 1.0]]),
        "A": (0.0, 0.0), "B": (1000.0, 0.0), "C": (500.0, 800.0), "beta1_deg": 40.0, "beta2_deg": 50.0,
        "l_mm": np.array([100.0, 101.0]), "L_mm": np.array([1200.0, 1210.0]), "kind": "tin",
        "mp_mm": 0.01, "names": ("1", "2", "3"), "k": 1.01,
        "centre_mm": np.array([0.0, 0.0]), "delta_mm": np.array([0.1, 0.0, 0.1]),
        "points_xy": np.array([[0.0, 0.0], [500.0, 0.0], [0.0, 500.0], [500.0, 500.0], [250.0, 250.0]]),
        "wl_um": np.array([0.45, 0.55, 0.65, 0.85]), "visibility_km": 20.0, "sun_elevation_deg": 40.0,
        "sun_azimuth_deg": 150.0, "speed_kmh": 200.0, "exposure_ms": 2.0, "season": "summer", "band": "red",
        "cover": "wheat", "humus_pct": 3.0, "moisture_pct": 12.0, "particle_mm": 0.1, "roughness": 0.3,
        "B_m": 480.0, "b1_mm": 60.0, "b2_mm": 61.0, "l0_mm": np.array([100.0, 150.0]),
        "li_mm": np.array([100.2, 150.1]), "m_allowed_mm": 0.35,
    }


# --------------------------------------------------------------------------------------------- mutations

SIZE_WORDS = ("n", "n_px", "samples", "samples_per_side", "n_points", "trials", "n_runs", "iterations",
              "max_iter", "cycles", "levels", "n_photos", "n_strips", "strips", "per_strip", "n_along",
              "n_nodes", "max_rejections", "half_window", "band_px", "max_pixels", "n_bases", "k")
STEP_WORDS = ("step_mm", "spacing_m", "cell_m", "pixel", "pixel_mm", "line_spacing_m", "spacing_mm", "cell_mm")


def _is_number(x) -> bool:
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


def _is_numeric_array(x) -> bool:
    if isinstance(x, np.ndarray):
        return x.dtype.kind in "fiu" and x.size > 0
    if isinstance(x, (list, tuple)) and x:
        try:
            a = np.asarray(x, dtype=float)
        except (TypeError, ValueError):
            return False
        return a.size > 0
    return False


def mutations(name: str, value):
    """``(kind, label, bad value)`` for one valid argument."""
    if isinstance(value, (bool, np.bool_)):
        return []
    out = [("type", "None", None), ("type", "obj", object())]
    if _is_number(value):
        out += [("nan", "nan", math.nan), ("inf", "inf", math.inf), ("inf", "-inf", -math.inf),
                ("type", "str", "abc"), ("zero", "0", 0), ("neg", "-1", -1)]
        if name in SIZE_WORDS:
            out.append(("huge", "1e9", 10**9))
        if name in STEP_WORDS:
            out.append(("huge", "1e-9", 1e-9))
    elif _is_numeric_array(value):
        a = np.array(value, dtype=float)
        for label, bad in (("a-nan", math.nan), ("a-inf", math.inf)):
            b = a.copy()
            b.flat[0] = bad
            out.append(("a-nan", label, b))
        out += [("type", "str", "abc"), ("empty", "[]", np.empty((0,) + a.shape[1:]))]
        if a.ndim == 2:
            out.append(("shape", "col+1", np.concatenate([a, a[:, :1]], axis=1)))
        elif a.ndim == 1 and len(a) in (2, 3) and not isinstance(value, np.ndarray):
            out.append(("shape", "len+1", np.append(a, a[0])))
    elif isinstance(value, str):
        out = [("type", "None", None), ("type", "int", 123), ("choice", "str", "abc")]
    elif isinstance(value, (tuple, list)):
        out += [("type", "str", "abc"), ("empty", "()", ())]
    else:
        out += [("type", "str", "abc")]
    return out


MUST_RAISE = {"nan", "inf", "a-nan", "type", "shape", "choice"}

# --------------------------------------------------------------------------------------------- outcomes


def _nonfinite_paths(obj, path="", depth=0, out=None):
    out = set() if out is None else out
    if depth > 3:
        return out
    if _is_number(obj):
        if not math.isfinite(float(obj)):
            out.add(path)
    elif isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fc" and not np.isfinite(obj).all():
            out.add(path)
    elif isinstance(obj, (list, tuple)):
        for k, x in enumerate(obj[:50]):
            _nonfinite_paths(x, f"{path}[{min(k, 1)}]", depth + 1, out)
    elif isinstance(obj, dict):
        for k, x in list(obj.items())[:50]:
            _nonfinite_paths(x, f"{path}.{k}", depth + 1, out)
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        for f in dataclasses.fields(obj):
            _nonfinite_paths(getattr(obj, f.name, None), f"{path}.{f.name}", depth + 1, out)
    elif hasattr(obj, "select_dtypes"):  # a DataFrame
        num = obj.select_dtypes("number").to_numpy(dtype=float)
        if num.size and not np.isfinite(num).all():
            out.add(path)
    return out


class _Hang(Exception):
    pass


def _alarm(signum, frame):
    raise _Hang()


def _call(fn, kwargs, limit_s=LIMIT_S):
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, limit_s)
    try:
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            return fn(**kwargs)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def classify(fn, kwargs, param, kind, base_nonfinite):
    """``(outcome, detail)``: clear, vague, obscure, nan, silent or ok (a valid return of a may-return kind)."""
    try:
        got = _call(fn, kwargs)
        if inspect.isgenerator(got):
            got = list(got)  # a generator checks its arguments when called, not when first iterated
    except _Hang:
        return "obscure", f"no answer within {LIMIT_S} s"
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        if param in msg or any(a in msg for a in ALIASES.get(param, ())):
            return "clear", f"{type(exc).__name__}: {msg[:120]}"
        tb = traceback.extract_tb(exc.__traceback__)
        if tb and "aerophoto" in tb[-1].filename:
            return "vague", f"{type(exc).__name__}: {msg[:160]}"
        return "obscure", f"{type(exc).__name__} from {tb[-1].filename.rsplit('/', 1)[-1]}: {msg[:140]}"
    except Exception as exc:  # noqa: BLE001 — the kind is the result
        return "obscure", f"{type(exc).__name__}: {str(exc)[:160]}"
    new = _nonfinite_paths(got) - base_nonfinite
    if new:
        return "nan", f"non-finite in {sorted(new)[:3]}"
    if kind in MUST_RAISE:
        return "silent", f"returned {type(got).__name__}"
    return "ok", ""


#: parameter names a message may use for a parameter (the guide's symbol or the dataclass the value becomes)
ALIASES: dict = {}

# --------------------------------------------------------------------------------------------- the table


def public_names():
    """``[(qualname, object)]`` of every function and class defined in the swept modules' ``__all__``."""
    out = []
    for m in MODULES:
        mod = importlib.import_module(f"aerophoto.{m}")
        for n in mod.__all__:
            obj = getattr(mod, n)
            is_callable = inspect.isfunction(obj) or inspect.isclass(obj) or hasattr(obj, "__wrapped__")  # lru_cache
            if is_callable and getattr(obj, "__module__", None) == mod.__name__:
                out.append((f"{m}.{n}", obj))
    return out


def _lazy(f):
    f.lazy = True
    return f



def valid_kwargs(qual, obj, S):
    entry = VALID[qual]
    entry = entry(S) if callable(entry) else dict(entry)
    kwargs = {}
    sig = inspect.signature(obj)
    for p in sig.parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        if p.name in entry:
            kwargs[p.name] = entry.pop(p.name)
        elif p.default is not p.empty:
            continue
        elif p.name in S:
            kwargs[p.name] = S[p.name]
        else:
            raise KeyError(f"{qual}: no valid example for parameter {p.name!r}")
    kwargs.update(entry)  # **kwargs entries
    return kwargs, sig


def sweep_one(qual, obj, S):
    """``[(param, label, kind, outcome, detail)]`` for one public name."""
    kwargs, sig = valid_kwargs(qual, obj, S)
    base = _call(obj, kwargs, 60.0)  # the valid call (first imports, caches) may take longer
    base_nonfinite = _nonfinite_paths(base)
    params = dict(kwargs)
    for p in sig.parameters.values():  # optional numbers keep their default unless mutated
        if p.name not in params and _is_number(p.default) and p.kind is not p.VAR_KEYWORD:
            params[p.name] = p.default
    rows = []
    for param, value in params.items():
        for kind, label, bad in mutations(param, value):
            if (qual, param, label) in NOT_RUN:
                continue
            reason = ALLOWED.get((qual, param, label)) or ALLOWED.get((qual, param, kind)) \
                or ALLOWED.get((qual, param, "*"))
            outcome, detail = classify(obj, dict(kwargs, **{param: bad}), param, kind, base_nonfinite)
            if reason and outcome not in ("clear", "ok"):
                outcome = "allowed"
            rows.append((param, label, kind, outcome, detail))
    return rows



# --------------------------------------------------------------------------------------------- the data

#: valid example arguments per public name: a dict (or a function of the shared samples giving one); parameters
#: left out come from :func:`samples` by name
_IMG = np.random.default_rng(0).uniform(0.2, 0.8, (24, 40))
_GRID = {"corners": np.array([[-50.0, -50.0], [50.0, -50.0], [50.0, 50.0], [-50.0, 50.0]])}


def _strip(S):
    from aerophoto import simulate
    return simulate.fly_strip(S["camera"], 12000.0, 60.0, 3, ground_Z_m=0.0)


def _block_poses(S):
    from aerophoto import geometry as g
    return [g.Pose(480.0 * k, 900.0 * s, 1200.0) for s in range(2) for k in range(4)]


def _meas(S):
    from aerophoto import bundle as B
    from aerophoto import geometry as g
    from aerophoto import terrain
    poses = _block_poses(S)
    T = terrain.AnalyticHills(relief_m=20.0, X0_m=720.0, Y0_m=450.0)
    ties = B.standard_points(S["camera"], poses, T, halfway_mm=20.0)
    ctrl = np.array([[0.0, 0.0], [1440.0, 0.0], [1440.0, 900.0], [0.0, 900.0]])
    ctrl = np.column_stack([ctrl, T.height(ctrl[:, 0], ctrl[:, 1])])
    P = np.vstack([ties, ctrl])
    kinds = np.array(["tie"] * len(ties) + ["control"] * len(ctrl), dtype=object)
    eo = B.eo_from_poses(poses)
    m = B.simulate_measurements(100.0, 180.0, eo, list(range(1, 9)), [0] * 4 + [1] * 4, [0, 1, 2, 3] * 2, P,
                                np.arange(1, len(P) + 1), kinds, sigma_mm=0.003, seed=0)
    return m, eo, P[np.searchsorted(np.arange(1, len(P) + 1), m.point_ids)], P, kinds


def _templates(S):
    from aerophoto import triangulation as T
    poses = [S["poses"][0].__class__(480.0 * k, 0.0, 1200.0) for k in range(4)]
    pts = T.design_points(S["camera"], poses, None)
    return T.measure_templates(S["camera"], poses, pts, pricking_mm=0.0)


def _templates_ends(S):
    from aerophoto import triangulation as T
    poses = [S["poses"][0].__class__(480.0 * k, 0.0, 1200.0) for k in range(4)]
    pts = T.design_points(S["camera"], poses, None, control_layout="ends")
    return T.measure_templates(S["camera"], poses, pts, pricking_mm=0.0)


def _small_site(S):
    from aerophoto import site
    return site.get_site(width_m=2000.0, height_m=1500.0)


def _sheet():
    from aerophoto import dem
    return dem.Sheet(0.0, 0.0, 400.0)


def _g(name, S):
    return _CACHE[name] if name in _CACHE else _CACHE.setdefault(name, _BUILD[name](S))


_CACHE: dict = {}
_BUILD = {
    "strip": _strip, "meas": _meas, "templates": _templates, "templates_ends": _templates_ends, "site": _small_site,
    "fs": lambda S: __import__("aerophoto.mosaic").mosaic.assemble(_g("strip", S), S["terrain"]),
    "layout": lambda S: __import__("aerophoto.dem").dem.block_layout(S["terrain"], strips=2, per_strip=3,
                                                                      control_every=2),
    "lines": lambda S: __import__("aerophoto.dem").dem.structural_lines(S["terrain"], _sheet(), cell_m=20.0),
    "gdem": lambda S: __import__("aerophoto.dem").dem.grid_dem(S["terrain"], _sheet(), 100.0),
}


def _rn(S):
    from aerophoto import stereo
    return stereo.normal_rotation(S["pose"], S["pose_right"])


VALID: dict = {
    # geometry
    "geometry.Camera": {"f_mm": 100.0, "frame_mm": 180.0},
    "geometry.Pose": {"X_m": 1.0, "Y_m": 2.0, "Z_m": 1000.0, "alpha_deg": 2.0, "lambda_deg": 3.0, "kappa_deg": 4.0},
    "geometry.FlatTerrain": {"z_m": 5.0},
    "geometry.rotation_matrix": {}, "geometry.principal_vertical": {}, "geometry.principal_point": {},
    "geometry.nadir_point": {}, "geometry.isocentre": {}, "geometry.ground_to_photo": {},
    "geometry.photo_to_plane": {}, "geometry.photo_to_dem": {}, "geometry.transfer_points": {},
    "geometry.photo_axis_towards": {"xy_mm": (71.8, -2.1)}, "geometry.footprint": {"samples_per_side": 2},
    "geometry.tilt_displacement_exact": {}, "geometry.tilt_displacement_vectors": {},
    "geometry.tilt_displacement_approx": {}, "geometry.relief_displacement": {},
    "geometry.photo_scale_denominator": {}, "geometry.as_terrain": {"terrain": None, "ground_Z_m": 5.0},
    "geometry.flying_height_m": {},
    # plane
    "plane.Similarity2D": {"a": 1.0, "b": 0.1, "tx": 2.0, "ty": 3.0},
    "plane.Affine2D": {"M": np.array([[1.0, 0.1, 2.0], [0.0, 1.0, 3.0], [0.0, 0.0, 1.0]])},
    "plane.Projective2D": {"H": np.array([[1.0, 0.1, 2.0], [0.0, 1.0, 3.0], [0.0, 0.001, 1.0]])},
    "plane.fit_similarity": {"src": _GRID["corners"], "dst": 2.0 * _GRID["corners"] + 1.0},
    "plane.fit_affine": {"src": _GRID["corners"], "dst": 2.0 * _GRID["corners"] + 1.0},
    "plane.fit_projective": {"src": _GRID["corners"], "dst": 2.0 * _GRID["corners"] + 1.0},
    "plane.fit": {"kind": "affine", "src": _GRID["corners"], "dst": 2.0 * _GRID["corners"] + 1.0},
    "plane.intersect_rays": {"origins": np.array([[0.0, 0.0], [100.0, 0.0]]), "angles_rad": np.radians([45.0, 135.0])},
    "plane.line_intersection": {"Ca": np.array([0.0, 0.0]), "ua": np.array([1.0, 1.0]), "Cb": np.array([100.0, 0.0]),
                                 "ub": np.array([-1.0, 1.0])},
    "plane.error_triangle": {"origins": np.array([[0.0, 0.0], [100.0, 0.0], [50.0, -50.0]]),
                             "angles_rad": np.radians([45.0, 135.0, 89.0])},
    "plane.resect_directions": {"angles_rad": np.radians([10.0, 50.0, 100.0]),
                                "known_xy": np.array([[0.0, 0.0], [100.0, 0.0], [0.0, 100.0]])},
    # terrain
    "terrain.AnalyticHills": {"relief_m": 30.0, "half_side_m": 1000.0, "X0_m": 1.0, "Y0_m": 2.0, "Z0_m": 3.0},
    "terrain.RescaledRelief": lambda S: {"site": _g("site", S), "relief_m": 10.0},
    # variants
    "variants.variant": {}, "variants.variant_for_index": {}, "variants.index_from_record_book": {},
    "variants.as_variant": lambda S: {"variant": S["v"]},
    # flight
    "flight.plan": lambda S: {"variant": S["v"]}, "flight.count_up": {"ratio": 3.2}, "flight.layout": {}, "flight.overlaps_at": {},
    "flight.guide_example": {}, "flight.exact_allowance_percent": {}, "flight.side_spacing": {},
    # quality
    "quality.overlap_percent": {}, "quality.straightness_percent": {"l_mm": 5.0, "L_mm": 1200.0}, "quality.straightness_limit_percent": {},
    "quality.crab_limit_deg": {}, "quality.level_reading_deg": {}, "quality.scale_difference_percent": {},
    "quality.height_deviation_percent": {}, "quality.measure_overlap": {"samples": 11}, "quality.measure_base": {},
    "quality.measure_crab_deg": {}, "quality.measure_straightness": {},
    "quality.measure_flying_height": {},
    "quality.assess_flight": lambda S: {"flight": _g("strip", S), "dem": S["terrain"]},
    # displacement
    "displacement.base_scale": {}, "displacement.ratio_text": {"N": 2500.0},
    "displacement.Base": {"name": "1-2", "l_plan_mm": 100.0, "l_photo_mm": 99.0},
    "displacement.partial_scales": lambda S: {"bases": (__import__("aerophoto.displacement").displacement.Base(
        "1-2", 100.0, 99.0), __import__("aerophoto.displacement").displacement.Base("2-3", 80.0, 81.0))},
    "displacement.zone_height": {"base_end_heights_m": np.array([[150.0, 160.0], [155.0, 165.0]])},
    "displacement.mean_object_plane": {"zone_heights_m": (150.0, 160.0, 170.0)},
    "displacement.relief_corrections": {"Z_m": np.array([150.0, 160.0, 170.0]), "r_mm": np.array([50.0, 60.0, 70.0])},
    "displacement.relief_displacement_vectors": {}, "displacement.isocentre_offset": {},
    "displacement.nadir_offset": {},
    "displacement.point_from_polar": {}, "displacement.polar_about_isocentre": {},
    "displacement.tilt_corrections": {"r_c_mm": np.array([50.0, 60.0, 70.0]), "phi_deg": np.array([10.0, 100.0, 200.0])},
    "displacement.apply_radial_corrections": {},
    "displacement.base_lengths_mm": {"bases": (("1", "2"), ("2", "3"))},
    "displacement.relief_work": {"photo_xy_mm": np.array([[10.0, 20.0], [30.0, -40.0], [-50.0, 5.0]]),
                                 "l_plan_mm": np.array([60.0, 80.0]), "Z_m": np.array([150.0, 160.0, 170.0]),
                                 "bases": (("1", "2"), ("2", "3")), "n_mm": np.array([0.0, 0.0])},
    "displacement.tilt_work": {"photo_xy_mm": np.array([[10.0, 20.0], [30.0, -40.0], [-50.0, 5.0]]),
                               "l_plan_mm": np.array([60.0, 80.0]), "bases": (("1", "2"), ("2", "3"))},
    # mosaic
    "mosaic.cut_line": {"p_top": (0.0, 80.0), "p_bottom": (2.0, -80.0), "y_range": (-80.0, 80.0)},
    "mosaic.seam_rms": {"dI_mm": np.array([0.1, -0.2, 0.05])},
    "mosaic.partial_scales": {},
    "mosaic.classify_mismatch": {"dI_mm": np.array([0.1, -0.2, 0.05])},
    "mosaic.choose_tie_points": {},
    "mosaic.assemble": lambda S: {"strip": _g("strip", S), "dem": S["terrain"]},
    "mosaic.seam_mismatches": lambda S: {"T_left": _g("fs", S).to_sheet[0], "T_right": _g("fs", S).to_sheet[1],
                                         "points_mm": np.array([[60.0, 0.0], [60.0, 20.0]]),
                                         "direction_m": np.array([1.0, 0.0]), "pose_left": _g("strip", S).poses[0],
                                         "pose_right": _g("strip", S).poses[1]},
    "mosaic.mean_scale": lambda S: {"poses": _g("fs", S).poses, "to_sheet": _g("fs", S).to_sheet,
                                    "cuts": [s.cut_mm for s in _g("fs", S).seams]},
    "mosaic.assign_working_areas": lambda S: {"cuts": [s.cut_mm for s in _g("fs", S).seams]},
    "mosaic.catalogue_points": {"ground": None},
    "mosaic.sheet_raster": lambda S: {"fs": _g("fs", S), "ground": S["terrain"], "px_per_mm": 0.5},
    "mosaic.sheet_raster_bands": lambda S: {"fs": _g("fs", S), "ground": S["terrain"], "px_per_mm": 0.5},
    "mosaic.seam_details": lambda S: {"fs": _g("fs", S), "dem": S["terrain"]},
    # triangulation
    "triangulation.ends.build_from_ends": lambda S: {"templates": _g("templates_ends", S)},
    "triangulation.geodetic.ground_to_geodetic": {"XY_m": np.array([[100.0, 200.0], [300.0, 50.0]])},
    "triangulation.geodetic.geodetic_to_ground": {"XY_geo_m": np.array([[6060100.0, 310200.0]])},
    "triangulation.geodetic.sheet_to_geodetic": {},
    "triangulation.geodetic.direction_to_geodetic_deg": {"theta_rad": np.array([0.1, 1.0])},
    "triangulation.geodetic.geodetic_to_direction_rad": {"alpha_deg": np.array([10.0, 100.0])},
    "triangulation.reduction.reduction_coefficients": {
        "names": ("a", "b", "c"), "base_mm": np.array([[0.0, 0.0], [300.0, 10.0], [600.0, -5.0]]),
        "template_mm": np.array([[0.0, 0.0], [299.0, 10.0], [601.0, -5.0]])},
    "triangulation.reduction.reduction_corrections": {"r_mm": np.array([50.0, 60.0, 70.0])},
    "triangulation.reduction.reduce_strip": lambda S: {
        "strip": __import__("aerophoto.triangulation").triangulation.lay_free_strip(_g("templates", S))},
    "triangulation.strip.design_points": lambda S: {"poses": _g("templates", S).poses, "terrain": None},
    "triangulation.strip.measure_templates": lambda S: {"poses": _g("templates", S).poses,
                                                        "points": _g("templates", S).points},
    "triangulation.strip.lay_free_strip": lambda S: {"templates": _g("templates", S)},
    "triangulation.study.accumulation_study": {"n_bases": (2, 3), "seeds": range(2)},
    "triangulation.zhukov.zhukov_radicand": {}, "triangulation.zhukov.zhukov_error_mm": {},
    "triangulation.zhukov.zhukov_bases_continuous": {}, "triangulation.zhukov.zhukov_max_bases": {},
    "triangulation.zhukov.bridge_variance_factor": {},
    # stereo
    "stereo.StereoPair": {"f_mm": 100.0, "B_m": 480.0, "H_m": 1200.0},
    "stereo.photo_base_mm": {}, "stereo.air_base_m": {}, "stereo.base_height_ratio": {},
    "stereo.x_parallax_mm": {"x_left_mm": np.array([10.0, 20.0]), "x_right_mm": np.array([-30.0, -25.0])},
    "stereo.y_parallax_mm": {"y_left_mm": np.array([10.0, 20.0]), "y_right_mm": np.array([10.1, 19.9])},
    "stereo.parallax_mm": {},
    "stereo.model_point": {"x_left_mm": 10.0, "y_left_mm": 20.0, "p_mm": 40.0, "H_m": 1200.0},
    "stereo.height_difference_m": {"dp_mm": 0.5, "b_mm": 72.0},
    "stereo.parallax_difference_mm": {"dh_m": 10.0, "b_mm": 72.0},
    "stereo.flying_height_from_point": {"p_mm": 40.0}, "stereo.air_base_from_point": {"p_mm": 40.0},
    "stereo.vertical_exaggeration": {},
    "stereo.normal_rotation": {},
    "stereo.to_normal": lambda S: {"R_n": _rn(S)}, "stereo.from_normal": lambda S: {"R_n": _rn(S)},
    "stereo.normalise_image": lambda S: {"image": _IMG[:, :24], "R_n": _rn(S), "window_mm": (-20.0, 20.0, -10.0, 10.0),
                                         "pixel_mm": 2.0},
    "stereo.anaglyph": {"left": _IMG, "right": _IMG[:, ::-1]},
    "stereo.side_by_side": {"left": _IMG, "right": _IMG[:, ::-1], "separation_px": 40},
    "stereo.match_points": {"left": _IMG, "right": np.roll(_IMG, -3, axis=1), "rc": np.array([[12.0, 20.0]]),
                            "half_window": 3, "d_max": 8},
    "stereo.dense_parallax": {"left": _IMG, "right": np.roll(_IMG, -3, axis=1), "half_window": 2, "d_max": 6},
    # projective
    "projective.grids.check_quadrilateral": dict(_GRID, name="corners"), "projective.grids.unit_square_map": dict(_GRID),
    "projective.grids.vanishing_points": {"corners": np.array([[-50.0, -50.0], [50.0, -40.0], [45.0, 45.0],
                                                               [-50.0, 50.0]])},
    "projective.grids.proportional_grid": dict(_GRID), "projective.grids.projective_grid": dict(_GRID),
    "projective.grids.diagonal_grid": dict(_GRID, levels=2), "projective.grids.grid": dict(_GRID),
    "projective.grids.bilinear": dict(_GRID, u=np.array([0.2, 0.5]), v=np.array([0.3, 0.5])),
    "projective.grids.locate": lambda S: {"nodes": __import__("aerophoto.projective").projective.grid(
        _GRID["corners"], 4), "xy": np.array([[0.0, 0.0], [10.0, 20.0]])},
    "projective.grids.transfer": lambda S: {
        "nodes_from": __import__("aerophoto.projective").projective.grid(_GRID["corners"], 4),
        "nodes_to": __import__("aerophoto.projective").projective.grid(2.0 * _GRID["corners"], 4),
        "xy": np.array([[0.0, 0.0], [10.0, 20.0]])},
    "projective.grids.place": lambda S: {
        "nodes": __import__("aerophoto.projective").projective.grid(_GRID["corners"], 4),
        "loc": __import__("aerophoto.projective").projective.locate(
            __import__("aerophoto.projective").projective.grid(_GRID["corners"], 4), np.array([[0.0, 0.0]]))},
    "projective.grids.grid_pair": {},
    "projective.grids.transfer_study": {"ns": (1, 2), "n_points": 20},
    "projective.images.photo_pixel_matrix": {},
    "projective.images.raster_pixel_matrix": {"extent": (0.0, 100.0, 0.0, 80.0), "pixel": 2.0},
    "projective.images.as_matrix": lambda S: {"transform": __import__("aerophoto.plane").plane.Similarity2D(1.0, 0.1)},
    "projective.images.warp_photo": lambda S: {"image": _IMG[:, :24], "transform": __import__(
        "aerophoto.plane").plane.Similarity2D(1.0, 0.1), "extent": (-90.0, 90.0, -90.0, 90.0), "pixel": 10.0},
    "projective.images.warp_raster": lambda S: {
        "image": _IMG, "to_plane_of_pixels": __import__("aerophoto.projective").projective.raster_pixel_matrix(
            (0.0, 40.0, 0.0, 24.0), 1.0),
        "transform": __import__("aerophoto.plane").plane.Similarity2D(1.0, 0.1), "extent": (0.0, 40.0, 0.0, 24.0),
        "pixel": 2.0},
    "projective.scene.land_use_scene": {},
    # control
    "control.identification_tolerance_m": {}, "control.marking_circles_ground_m": {},
    "control.geodetic_from_site": {"xy_m": np.array([[100.0, 200.0]])},
    "control.site_from_geodetic": {"xy_m": np.array([[100.0, 200.0]])},
    "control.dms": {}, "control.from_dms": {"d": 12, "m": 30, "s": 15.0}, "control.format_dms": {},
    "control.direction_angle_deg": {"from_xy": (0.0, 0.0), "to_xy": (100.0, 50.0)},
    "control.horizontal_angle_deg": {"station_xy": (0.0, 0.0), "from_xy": (100.0, 0.0), "to_xy": (0.0, 100.0)},
    "control.danger_circle": {}, "control.resect": {}, "control.resect_many": {},
    "control.check_tolerance_arcsec": {},
    "control.check_resection": lambda S: {"res": __import__("aerophoto.control").control.resect(
        S["A"], S["B"], S["C"], 40.0, 50.0), "D": (900.0, 900.0), "measured_deg": 30.0},
    "control.control_rows": {"n_photos": 12},
    "control.design_control": {"centres_m": np.array([[[480.0 * k, 900.0 * s] for k in range(8)] for s in range(2)])},
    "control.control_spacing_bases": {},
    # accuracy
    "accuracy.squares_sum": {}, "accuracy.free_strip_factor": {}, "accuracy.middle_factor_article": {},
    "accuracy.middle_factor_exact": {"n": 4}, "accuracy.strip_errors_mm": {},
    "accuracy.allowed_height_error_m": {}, "accuracy.plan_bases": {}, "accuracy.height_bases": {},
    "accuracy.whole_bases": {},
    "accuracy.strip_monte_carlo": {"terrain": 0.0, "n_runs": 3},
    "accuracy.fit_accumulation": lambda S: {"n": np.array([2.0, 4.0, 6.0]), "rms": np.array([0.1, 0.3, 0.6]),
                                            "law": __import__("aerophoto.accuracy").accuracy.free_strip_factor},
    "accuracy.control_rows": {"n_photos": 12},
    "accuracy.block_precision": lambda S: {"poses": _block_poses(S), "photo_strip": [0] * 4 + [1] * 4,
                                           "photo_order": [0, 1, 2, 3] * 2, "terrain": 0.0, "every": 2},
    "accuracy.block_vs_strip": lambda S: {
        "strip_precision": __import__("aerophoto.accuracy").accuracy.block_precision(
            S["camera"], _block_poses(S)[:4], [0] * 4, [0, 1, 2, 3], 0.0, every=2),
        "block_precision_": __import__("aerophoto.accuracy").accuracy.block_precision(
            S["camera"], _block_poses(S), [0] * 4 + [1] * 4, [0, 1, 2, 3] * 2, 0.0, every=2)},
    "accuracy.block_monte_carlo": lambda S: {"poses": _block_poses(S), "photo_strip": [0] * 4 + [1] * 4,
                                             "photo_order": [0, 1, 2, 3] * 2, "terrain": 0.0, "every": 2,
                                             "n_runs": 2},
    # interpretation
    "interpretation.Conditions": {"sun_elevation_deg": 40.0, "visibility_km": 20.0},
    "interpretation.shadow_length_m": {"h_m": 10.0}, "interpretation.shadow_azimuth_deg": {},
    "interpretation.slope_illumination": {"slope_deg": 10.0, "aspect_deg": 90.0},
    "interpretation.image_motion_mm": {},
    "interpretation.motion_blur": {"image": _IMG, "length_px": 3.0},
    "interpretation.haze": {"rho": np.array([0.1, 0.2])},
    "interpretation.contrast": {"image": _IMG},
    "interpretation.conditions_table": {},
    # spectral
    "spectral.band_mean": lambda S: {"curve": __import__("aerophoto.spectral").spectral.soil_reflectance()},
    "spectral.bands_of": lambda S: {"curve": __import__("aerophoto.spectral").spectral.soil_reflectance()},
    "spectral.water_absorption_per_cm": {}, "spectral.dry_shape": {}, "spectral.humus_g": {},
    "spectral.humus_sensitivity": {}, "spectral.particle_factor": {}, "spectral.clod_factor": {},
    "spectral.moisture_factor": {}, "spectral.soil_reflectance": {"wl_um": np.array([0.45, 0.55, 0.65, 0.85])},
    "spectral.soil_bands": {"humus_pct": 3.0, "moisture_pct": 12.0},
    "spectral.soil_band_table": {}, "spectral.mixture": {"cover": "crop"}, "spectral.cover_bands": {"cover": "deep water"},
    "spectral.rayleigh_optical_depth": {}, "spectral.aerosol_optical_depth": {},
    "spectral.path_optical_depth": {},
    "spectral.haze_layer": {"tau_aerosol": np.array([0.2, 0.1]), "tau_rayleigh": np.array([0.1, 0.05])},
    "spectral.apparent_reflectance": {"rho": np.array([0.1, 0.2]), "R": np.array([0.02, 0.01]),
                                      "T": np.array([0.8, 0.9])},
    # bundle
    "bundle.block.simulate_measurements": lambda S: {
        "f_mm": 100.0, "frame_mm": 180.0, "eo_true": _g("meas", S)[1], "photo_ids": list(range(1, 9)),
        "photo_strip": [0] * 4 + [1] * 4, "photo_order": [0, 1, 2, 3] * 2, "XYZ_true_m": _g("meas", S)[3],
        "point_ids": np.arange(1, len(_g("meas", S)[3]) + 1), "point_kind": _g("meas", S)[4]},
    "bundle.collinearity.rotation_opk": {"omega": 0.01, "phi": 0.02, "kappa": 0.3},
    "bundle.collinearity.opk_from_matrix": {"R": np.eye(3)},
    "bundle.collinearity.eo_from_pose": {}, "bundle.collinearity.eo_from_poses": {},
    "bundle.collinearity.project": {"eo": np.array([[0.0, 0.0, 1200.0, 0.01, 0.0, 0.1]]),
                                    "XYZ_m": np.array([[100.0, 50.0, 20.0]])},
    "bundle.collinearity.project_jacobian": {"eo": np.array([[0.0, 0.0, 1200.0, 0.01, 0.0, 0.1]]),
                                             "XYZ_m": np.array([[100.0, 50.0, 20.0]])},
    "bundle.design.standard_points": lambda S: {"poses": _block_poses(S), "halfway_mm": 20.0},
    "bundle.solve.adjust": lambda S: {"meas": _g("meas", S)[0], "eo0": _g("meas", S)[1], "xyz0_m": _g("meas", S)[2],
                                      "max_iter": 3},
    "bundle.solve.precision": lambda S: {"meas": _g("meas", S)[0], "eo": _g("meas", S)[1], "xyz_m": _g("meas", S)[2]},
    "bundle.solve.data_snooping": lambda S: {"meas": _g("meas", S)[0], "eo0": _g("meas", S)[1],
                                             "xyz0_m": _g("meas", S)[2], "max_rejections": 1, "max_iter": 3},
    "bundle.solve.image_critical": {},
    "bundle.solve.error_ellipse": {},
    "bundle.solve.point_covariance": lambda S: {"meas": _g("meas", S)[0], "eo": _g("meas", S)[1],
                                                "xyz_m": _g("meas", S)[2], "point_index": 0},
    "bundle.solve.rms_expectation": {"cov": np.diag([1.0, 2.0, 3.0]), "components": [0, 1]},
    "bundle.stages.similarity_fit": {"A": np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
                                     "B": np.array([[1.0, 1.0, 0.0], [3.0, 1.0, 0.0], [1.0, 3.0, 0.0]])},
    "bundle.stages.relative_orientation": lambda S: {
        "xy_left": __import__("aerophoto.geometry").geometry.ground_to_photo(S["camera"], S["poses"][0], _RO_P),
        "xy_right": __import__("aerophoto.geometry").geometry.ground_to_photo(S["camera"], S["poses"][1], _RO_P)},
    "bundle.stages.intersect": {"S1": np.array([0.0, 0.0, 1000.0]), "r1": np.array([[0.1, 0.0, -1.0]]),
                                "S2": np.array([200.0, 0.0, 1000.0]), "r2": np.array([[-0.1, 0.0, -1.0]])},
    "bundle.stages.form_strip": lambda S: {"meas": _g("meas", S)[0], "photos": [0, 1, 2, 3]},
    "bundle.stages.join_strips": lambda S: {"strips": [
        __import__("aerophoto.bundle").bundle.form_strip(_g("meas", S)[0], [0, 1, 2, 3]),
        __import__("aerophoto.bundle").bundle.form_strip(_g("meas", S)[0], [4, 5, 6, 7])]},
    "bundle.stages.three_stage": lambda S: {"meas": _g("meas", S)[0]},
    # dem
    "dem.densification.bundle_counts": {"m": 4500.0}, "dem.densification.lysenko_ratio": {"m": 4500.0},
    "dem.densification.lysenko_mz_m": {"m": 4500.0},
    "dem.densification.block_layout": {"strips": 2, "per_strip": 3, "control_every": 2},
    "dem.densification.block_precision": lambda S: {"layout": _g("layout", S), "trials": 2},
    "dem.densification.lysenko_study": {"cases": (("small", {"strips": 2, "per_strip": 3, "control": "spread",
                                                             "control_every": 2}),), "trials": 2},
    "dem.surface.Sheet": {"X0_m": 0.0, "Y0_m": 0.0, "size_m": 400.0},
    "dem.surface.grid_nodes": {"sheet": _sheet(), "spacing_m": 100.0},
    "dem.surface.correlated_noise_factor": {"spacing_m": 30.0, "corr_length_m": 300.0, "samples": 8},
    "dem.surface.structural_lines": {"sheet": _sheet(), "cell_m": 20.0},
    "dem.surface.grid_dem": {"sheet": _sheet(), "spacing_m": 100.0},
    "dem.surface.tin_dem": {},
    "dem.surface.grid_with_lines": lambda S: {"sheet": _sheet(), "spacing_m": 100.0, "lines": _g("lines", S)},
    "dem.surface.structural_dem": lambda S: {"sheet": _sheet(), "spacing_m": 100.0, "lines": _g("lines", S)},
    "dem.surface.contour_levels": {},
    "dem.surface.contour_lines": {"x": np.linspace(0.0, 100.0, 11), "y": np.linspace(0.0, 50.0, 6),
                                  "Z": np.add.outer(np.linspace(0.0, 5.0, 6), np.linspace(0.0, 10.0, 11)),
                                  "levels": np.array([2.0, 4.0])},
    "dem.surface.contour_accuracy": lambda S: {"lines": __import__("aerophoto.dem").dem.contour_lines(
        np.linspace(0.0, 100.0, 11), np.linspace(0.0, 50.0, 6),
        np.add.outer(np.linspace(0.0, 5.0, 6), np.linspace(0.0, 10.0, 11)), np.array([2.0, 4.0]))},
    "dem.surface.dem_accuracy": lambda S: {"dem": _g("gdem", S), "points_xy": np.array([[100.0, 100.0], [50.0, 300.0]])},
    "dem.surface.predicted_rms": {}, "dem.surface.standard_interval": {},
    "dem.surface.evaluate": lambda S: {"sheet": _sheet(), "dem": _g("gdem", S), "cell_m": 20.0},
    "dem.surface.spacing_study": {"sheet": _sheet(), "spacings_m": (100.0, 200.0), "cell_m": 20.0},
    # budget
    "budget.rms_from_mean": {"v": 0.8}, "budget.mean_from_rms": {"m": 1.0},
    "budget.mean_abs_deviation": {"values": np.array([0.1, -0.2, 0.3])},
    "budget.plan_error": {"v_x": 0.3, "v_y": 0.4},
    "budget.transfer_from_mean_mm": {"d_mean_mm": 0.5, "n": 50},
    "budget.vectorising_error": {}, "budget.sigma_um": {}, "budget.triangulation_rms_m": {},
    "budget.transfer_rms_mm": {}, "budget.relief_limit_m": {}, "budget.working_area_radii_mm": {},
    "budget.dtm_displacement_m": {}, "budget.plane_rectification_m": {}, "budget.budget": {},
    "budget.scenarios": {},
    # rectify
    "rectify.paper_deformation": {}, "rectify.control_grid_length_mm": {}, "rectify.enlargement": {},
    "rectify.projection_distance_mm": {}, "rectify.substrate_thickness_mm": {"K_d": 0.01},
    "rectify.rectify_points": {"photo_control_mm": _GRID["corners"], "plan_control_mm": 2.0 * _GRID["corners"] + 1.0},
    "rectify.TransformerState": {"eps_deg": 2.0, "tilt_dir_deg": 30.0, "theta_deg": 5.0, "scale": 1.5,
                                 "tx_mm": 1.0, "ty_mm": 2.0},
    "rectify.screen_image": lambda S: {"state": __import__("aerophoto.rectify").rectify.TransformerState(2.0, 30.0),
                                       "xy_photo_mm": _GRID["corners"]},
    "rectify.true_state": {},
    "rectify.principal_horizontal": {"images_mm": _GRID["corners"], "plan_mm": 1.1 * _GRID["corners"] + [[0.0, 0.0],
                                     [0.0, 0.0], [2.0, 2.0], [-2.0, 2.0]]},
    "rectify.transformer_sequence": lambda S: {
        "photo_mm": _GRID["corners"], "plan_mm": __import__("aerophoto.rectify").rectify.screen_image(
            __import__("aerophoto.rectify").rectify.TransformerState(2.0, 30.0, 5.0, 1.5), _GRID["corners"], 100.0)},
    # soilmap
    "soilmap.segment_tones": {"image": _IMG, "k": 3, "iterations": 5},
    "soilmap.contingency": {"labels": np.array([0, 1, 2, 1]), "truth": np.array([0, 1, 1, 1])},
    "soilmap.overlay": {"sheets": [np.array([[0, 0, 1], [0, 1, 1]]), np.array([[0, 1, 1], [0, 1, 1]])]},
    # simulate
    "simulate.Imperfections": {"max_tilt_deg": 1.0, "crab_deg": 1.0, "max_crab_jitter_deg": 1.0,
                               "max_height_percent": 1.0, "curvature_percent": 1.0, "max_base_percent": 1.0},
    "simulate.photo_base_m": {}, "simulate.strip_spacing_m": {}, "simulate.fly_strip": {},
    "simulate.fly_block": {},
    "simulate.strip_over_site": lambda S: {"site": _g("site", S), "m": 5000.0, "n_photos": 3},
    "simulate.block_over_site": lambda S: {"site": _g("site", S), "m": 3000.0, "n_photos": 2},
    "simulate.variant_strip": {"n_photos": 2},
    "simulate.variant_block": {"n_photos": 2, "n_strips": 2},
    "simulate.required_site_size": {},
    # site
    "site.get_site": lambda S: {"width_m": 2000.0, "height_m": 1500.0},
    "site.cache_entry": lambda S: {"params": __import__("aerophoto.site").site.SiteParams(width_m=2000.0,
                                                                                          height_m=1500.0)},
    "site.cover.default_soil": {},
    "site.soils.soil_layer": lambda S: {"site": _g("site", S), "spacing_m": 50.0},
    "site.soils.key_sheets": lambda S: {"layer": __import__("aerophoto.site.soils").site.soils.soil_layer(
        _g("site", S), spacing_m=50.0), "site": _g("site", S)},
    "site.model.SiteParams": {"width_m": 2000.0, "height_m": 1500.0},
    "site.colour.class_band_table": {},
    "site.colour.to_display": {"rho": np.random.default_rng(1).uniform(0.0, 0.5, (8, 8, 3))},
    # render
    "render.Sun": {"azimuth_deg": 200.0, "elevation_deg": 40.0},
    "render.render": lambda S: {"site": _g("site", S), "pose": _SITE_POSE, "n_px": 32},
    "render.render_shot": lambda S: {"site": _g("site", S), "shot": __import__("aerophoto.simulate").simulate.
                                     strip_over_site(_g("site", S), S["camera"], 5000.0, 60.0, 2).shots[0], "n_px": 32},
    "render.render_strip": lambda S: {"site": _g("site", S), "strip": __import__("aerophoto.simulate").simulate.
                                      strip_over_site(_g("site", S), S["camera"], 5000.0, 60.0, 2), "n_px": 32},
    "render.trace": lambda S: {"site": _g("site", S), "pose": _SITE_POSE},
}

_RO_P = np.array([[x, y, 10.0 * ((x + y) % 3)] for x in (0.0, 240.0, 480.0) for y in (-300.0, 0.0, 300.0)])
_SITE_POSE = None  # set in samples(): a pose over the middle of the small site

_RESULT = "a result record built by the package from validated inputs (its fields are the computation's output)"
EXEMPT: dict = {
    "geometry.Terrain": "a typing.Protocol (the interface of a terrain), not a constructor",
    **{q: _RESULT for q in (
        "plane.Fit", "flight.FlightPlan", "flight.FlightLayout", "quality.PhotoCheck", "quality.PairCheck",
        "quality.StripCheck", "quality.QualityReport", "displacement.ScaleTable", "displacement.ReliefCorrections",
        "displacement.TiltCorrections", "displacement.ReliefWork", "displacement.TiltWork", "mosaic.TiePoints",
        "mosaic.Seam", "mosaic.ScaleCheck", "mosaic.Fotoschema", "mosaic.SeamDetails", "triangulation.ends.EndsStrip",
        "triangulation.reduction.ReductionCoefficients", "triangulation.reduction.ReductionCorrections",
        "triangulation.reduction.Reduction", "triangulation.strip.StripPoints", "triangulation.strip.Templates",
        "triangulation.strip.FreeStrip", "stereo.NormalImage", "stereo.DenseParallax", "projective.grids.GridPair",
        "projective.images.Raster", "projective.scene.Feature", "projective.scene.LandUseScene", "control.Resection",
        "control.ResectionCheck", "control.ControlDesign", "accuracy.StripMonteCarlo", "accuracy.BlockPrecision",
        "spectral.Band", "spectral.SoilBandTable", "bundle.block.Measurements", "bundle.solve.Adjustment",
        "bundle.solve.Precision", "bundle.solve.Snooping", "bundle.stages.Similarity",
        "bundle.stages.RelativeOrientation", "bundle.stages.StripModel", "bundle.stages.ThreeStage",
        "dem.densification.BlockLayout", "dem.densification.BlockPrecision", "dem.surface.StructuralLines",
        "dem.surface.DEM", "dem.surface.ContourAccuracy", "dem.surface.SheetResult", "budget.Vectorising",
        "budget.Stage", "budget.Budget", "rectify.PaperDeformation", "rectify.Rectification",
        "rectify.TransformerStep", "rectify.TransformerRun", "simulate.Shot", "simulate.Strip", "simulate.Block",
        "site.cover.InterpretationSite", "site.objects.SiteObjects", "site.soils.SoilClass", "site.soils.SoilLayer",
        "site.model.Site", "site.colour.ColourGeometry", "site.colour.ColourPhoto", "render.Photo", "render.Hits",
        "variants.Variant")},
    "site.cover.interpretation_site": "builds the 17 s interpretation site (seed only; validated by check_int_range)",
    "site.cover.build_interpretation_site": "builds the 17 s interpretation site (seed only)",
    "site.objects.build_objects": "a step of the site build (its inputs are the build's own rasters)",
    "site.objects.object_points": "a step of the site build (its inputs are the build's own rasters)",
    "site.colour.colour_geometry": "renders from the 17 s interpretation site (too slow for the sweep)",
    "site.colour.colour_photo": "renders from the 17 s interpretation site (too slow for the sweep)",
    "site.colour.render_colour": "renders from the 17 s interpretation site (too slow for the sweep)",
    "site.colour.vertical_pose": "needs the 17 s interpretation site (too slow for the sweep)",
}

#: (name, parameter, mutation label) not run, with the reason (valid, and too slow for the sweep)
NOT_RUN: dict = {
    ("site.soils.soil_layer", "site", "None"): "None is the default site (documented); building it takes ~7 s",
    ("site.soils.key_sheets", "site", "None"): "None is the default site (documented); building it takes ~7 s",
}

#: (name, parameter, mutation label or kind or '*') → why that bad-looking input is valid there
ALLOWED: dict = {
    ("geometry.as_terrain", "terrain", "None"): "None is flat ground at ground_Z_m (documented)",
    ("variants.variant", "record_book", "int"): "a record-book number may be given as an integer (documented)",
    ("variants.index_from_record_book", "record_book", "int"): "a record-book number may be an integer (documented)",
    ("variants.as_variant", "variant", "None"): "None is the guide's worked example where a caller allows it",
    ("flight.plan", "variant", "None"): "None is the guide's worked example (documented)",
    **{(f"quality.{f}", "dem", "None"): "None is flat ground (geometry.as_terrain, documented)"
       for f in ("measure_overlap", "measure_base", "measure_crab_deg", "assess_flight")},
    ("displacement.ratio_text", "N", "inf"): "N = ∞ (no deviation, Δm = 0) prints as the guide's 0",
    ("displacement.Base", "name", "str"): "any text is a base name",
    **{(f"mosaic.{f}", p, "None"): "None is flat ground / no texture (documented)"
       for f, p in (("assemble", "dem"), ("seam_details", "dem"), ("sheet_raster", "ground"),
                    ("sheet_raster_bands", "ground"), ("catalogue_points", "ground"))},
    ("triangulation.strip.design_points", "terrain", "None"): "None is flat ground at Z = 0 (documented)",
    ("triangulation.study.accumulation_study", "n_bases", "len+1"): "any number of strip lengths",
    **{(f"stereo.{f}", p, "a-nan"): "NaN pixels mark no data in an image (documented); it stays no data"
       for f, ps in (("normalise_image", ("image",)), ("anaglyph", ("left", "right")),
                     ("side_by_side", ("left", "right")), ("match_points", ("left", "right")),
                     ("dense_parallax", ("left", "right"))) for p in ps},
    ("projective.grids.check_quadrilateral", "name", "str"): "the name is any label for the messages",
    ("projective.grids.transfer_study", "ns", "len+1"): "any number of grid sizes",
    ("projective.images.warp_raster", "image", "col+1"): "a raster of any size",
    **{(f"projective.images.{f}", "cval", "nan"): "NaN marks pixels with no data (the default)"
       for f in ("warp_photo", "warp_raster")},
    **{(f"accuracy.{f}", "terrain", "None"): "None is flat ground (geometry.as_terrain, documented)"
       for f in ("strip_monte_carlo", "block_precision", "block_monte_carlo")},
    ("interpretation.Conditions", "visibility_km", "None"): "None is a clear sky, no haze (documented)",
    ("interpretation.haze", "visibility_km", "None"): "None is a clear sky, no haze (documented)",
    **{(f"interpretation.{f}", p, "a-nan"): "NaN pixels mark no data in an image (documented); they stay no data"
       for f, p in (("motion_blur", "image"), ("haze", "rho"), ("contrast", "image"))},
    **{(f"interpretation.{f}", "image", "col+1"): "an image of any size" for f in ("motion_blur", "contrast")},
    ("spectral.apparent_reflectance", "rho", "a-nan"): "NaN pixels mark no data in an image; they stay no data",
    ("spectral.soil_reflectance", "wl_um", "None"): "None is the model's own wavelength grid (documented)",
    ("bundle.design.standard_points", "terrain", "None"): "None is flat ground (documented)",
    ("bundle.design.standard_points", "halfway_mm", "None"): "None places the points half a base apart (default)",
    ("bundle.solve.rms_expectation", "components", "len+1"): "any number of components",
    **{(f"dem.{f}", "terrain", "None"): "None is flat ground (geometry.as_terrain, documented)"
       for f in ("densification.block_layout", "densification.lysenko_study", "surface.structural_lines",
                 "surface.grid_dem", "surface.tin_dem", "surface.grid_with_lines", "surface.structural_dem",
                 "surface.contour_accuracy", "surface.dem_accuracy", "surface.evaluate")},
    ("dem.surface.contour_accuracy", "lines", "()"): "no contours: the accuracy is undefined — NaN with n_lines = 0",
    ("dem.surface.spacing_study", "spacings_m", "len+1"): "any number of spacings",
    ("soilmap.segment_tones", "image", "col+1"): "an image of any size",
    ("site.soils.soil_layer", "spacing_m", "None"): "None is the site's own spacing (documented)",
    ("site.colour.to_display", "rho", "a-nan"): "NaN pixels mark no data in an image; they stay no data",
    ("stereo.model_point", "H_m", "None"): "without H the model is in photo units (documented)",
    ("mosaic.sheet_raster_bands", "band_px", "None"): "None is the whole sheet in one band (documented)",
    ("displacement.mean_object_plane", "zone_heights_m", "len+1"): "any number of zones",
}

# --------------------------------------------------------------------------------------------- the tests

PUBLIC = public_names()


def test_every_public_name_has_a_valid_example_or_an_exemption():
    missing = [q for q, _ in PUBLIC if q not in VALID and q not in EXEMPT]
    stale = [q for q in list(VALID) + list(EXEMPT) if q not in dict(PUBLIC)]
    assert missing == [] and stale == [], f"missing: {missing}\nstale: {stale}"


def test_the_exempt_modules_are_the_only_ones_left_out():
    import pkgutil

    import aerophoto

    owned = ("geometry", "plane", "terrain", "variants", "flight", "quality", "displacement", "mosaic",
             "triangulation", "stereo", "projective", "control", "accuracy", "interpretation", "spectral",
             "bundle", "dem", "budget", "rectify", "soilmap", "simulate", "site", "render")
    mods = set()
    for info in pkgutil.walk_packages(aerophoto.__path__, "aerophoto."):
        m = info.name.removeprefix("aerophoto.")
        if m.split(".")[0] in owned and not info.ispkg or m in ("site",):
            mods.add(m)
    assert mods - set(MODULES) - set(EXEMPT_MODULES) == set()


@pytest.fixture(scope="module")
def results():
    S = samples()
    out = {}
    for qual, obj in PUBLIC:
        if qual in VALID:
            out[qual] = sweep_one(qual, obj, S)
    return out


def test_bad_input_is_refused_by_name(results):
    bad = [f"{q}({p}={label}): {outcome} — {detail}" for q, rows in results.items()
           for p, label, kind, outcome, detail in rows if outcome not in ("clear", "ok", "allowed")]
    assert bad == [], f"{len(bad)} bad outcomes:\n" + "\n".join(bad)


def test_the_sweep_is_broad(results):
    n = sum(len(rows) for rows in results.values())
    assert len(results) >= 200 and n >= 2500, (len(results), n)


def test_every_allowance_is_used(results):
    """An allowance that no mutation needs any more (the function now refuses it by name) is removed."""
    used = {(q, p, x) for q, rows in results.items() for p, label, kind, outcome, _ in rows for x in (label, kind, "*")
            if outcome == "allowed"}
    assert [k for k in ALLOWED if k not in used] == []


def report(results) -> str:
    by_module = {}
    for q, rows in results.items():
        c = by_module.setdefault(q.rsplit(".", 1)[0], Counter())
        c.update(outcome for *_, outcome, _ in rows)
    total = Counter()
    lines = []
    for m, c in by_module.items():
        total.update(c)
        lines.append(f"{m:24s} " + " ".join(f"{k}={c[k]}" for k in sorted(c)))
    lines.append(f"{'TOTAL':24s} " + " ".join(f"{k}={total[k]}" for k in sorted(total)))
    return "\n".join(lines)


if __name__ == "__main__":
    import time

    t0 = time.perf_counter()
    S = samples()
    res = {}
    only = [a for a in sys.argv[1:] if not a.startswith("-")]
    for qual, obj in PUBLIC:
        if qual in VALID and (not only or any(qual.startswith(o + ".") for o in only)):
            try:
                res[qual] = sweep_one(qual, obj, S)
            except Exception as exc:  # noqa: BLE001
                print(f"BASELINE FAILS {qual}: {type(exc).__name__}: {exc}")
    print(report(res))
    print(f"{len(res)} names, {sum(len(r) for r in res.values())} calls, {time.perf_counter() - t0:.1f} s")
    if "-v" in sys.argv:
        for q, rows in res.items():
            for p, label, kind, outcome, detail in rows:
                if outcome not in ("clear", "ok", "allowed"):
                    print(f"{outcome:8s} {q}({p}={label}) {detail}")


# --------------------------------------------------------------------------------------------- the issue's examples
def _raises(exc, match, fn, *args, **kwargs):
    with pytest.raises(exc, match=match):
        fn(*args, **kwargs)


def test_the_examples_of_the_issue_are_refused_by_name():
    from aerophoto import budget, control, displacement, flight, geometry, mosaic, plane, projective, rectify, spectral
    from aerophoto import bundle as B
    from aerophoto import stereo, terrain

    cam, pose = geometry.Camera(100.0), geometry.Pose(Z_m=1200.0, alpha_deg=3.0)
    bad_xy = np.array([[10.0, 20.0], [np.nan, 0.0]])
    # constructors that checked nothing
    _raises(ValueError, "eps_deg", rectify.TransformerState, eps_deg=95.0)
    _raises(ValueError, "scale", rectify.TransformerState, scale=0.0)
    _raises(ValueError, "tx", plane.Similarity2D, tx=math.nan)
    _raises(ValueError, "X0_m", terrain.AnalyticHills, X0_m=math.inf)
    _raises(ValueError, "z_m", geometry.FlatTerrain, "abc")
    # NaN/inf no longer returned
    _raises(ValueError, "omega", B.rotation_opk, math.nan, 0.0, 0.0)
    _raises(ValueError, "f_mm", B.project, np.zeros((1, 6)) + [0, 0, 1000, 0, 0, 0], np.zeros((1, 3)), math.nan)
    _raises(ValueError, "r_mm", geometry.relief_displacement, math.nan, 10.0, 1200.0)
    _raises(ValueError, "u", projective.bilinear, _GRID["corners"], math.nan, 0.5)
    _raises(ValueError, "v", budget.rms_from_mean, math.nan)
    _raises(ValueError, "wl_um", spectral.path_optical_depth, 0.0, 20.0, 1200.0)
    _raises(ValueError, "XYZ_m", geometry.ground_to_photo, cam, pose, [[0.0, 0.0, np.nan]])
    _raises(ValueError, "xy_mm", geometry.photo_to_plane, cam, pose, bad_xy)
    _raises(ValueError, "xy_mm", geometry.photo_to_dem, cam, pose, bad_xy, geometry.FlatTerrain())
    # silent plausible values
    _raises(ValueError, "variant", flight.plan, variant="abc")
    _raises(ValueError, "dI_mm", mosaic.classify_mismatch, [math.nan])
    _raises(ValueError, "N", displacement.ratio_text, math.nan)
    _raises(ValueError, "N", displacement.ratio_text, -71.0)
    _raises(ValueError, "dp_mm", stereo.height_difference_m, dp_mm=1e300, b_mm=72.0, H_m=1200.0)
    _raises(ValueError, "from_xy", control.direction_angle_deg, from_xy=[math.inf, 0.0], to_xy=[1.0, 1.0])
    # obscure errors
    _raises(TypeError, "camera", geometry.nadir_point, None, pose)
    _raises(TypeError, "pose", geometry.rotation_matrix, "abc")
    _raises(TypeError, "A", control.resect, None, (1000.0, 0.0), (500.0, 800.0), 40.0, 50.0)
    _raises(ValueError, "p_top", mosaic.cut_line, [], (2.0, -80.0), (-80.0, 80.0))
    _raises(ValueError, "A", B.similarity_fit, np.array([[0.0, 0, 0], [1, 0, 0], [np.nan, 1, 0]]), np.eye(3))
    _raises(ValueError, "d_max", stereo.match_points, _IMG, _IMG, [[12.0, 20.0]], d_max=math.inf)
    _raises(ValueError, "step_mm", mosaic.cut_line, (0.0, 80.0), (2.0, -80.0), (-80.0, 80.0), shape="curved",
            step_mm=1e-9)
    _raises(ValueError, "ns", projective.transfer_study, _GRID["corners"], 2.0 * _GRID["corners"], ns=())


def test_a_variant_argument_is_resolved_in_one_place():
    from aerophoto import flight, simulate, variants

    v = variants.variant("19-0457")
    assert variants.as_variant(v) is v and variants.as_variant(None) is None
    assert variants.as_variant("19-0457") == v and variants.as_variant(190457).i == v.i
    assert flight.plan("19-0457") == flight.plan(v)  # a record-book number is a valid form
    for bad in ("abc", "7", object(), 3.5):
        with pytest.raises((ValueError, TypeError), match="variant") as info:
            flight.plan(bad)
        assert "record-book" in str(info.value)  # the message lists the valid forms
        with pytest.raises((ValueError, TypeError), match="variant"):
            simulate.variant_strip(bad)
    with pytest.raises(TypeError, match="variant"):
        variants.as_variant(None, none=False)


def test_the_entry_checks_are_cheap():
    """The decorator costs microseconds per call: far below the work of any public function it guards."""
    import time

    from aerophoto import geometry

    cam, pose = geometry.Camera(100.0), geometry.Pose(Z_m=1200.0, alpha_deg=3.0)
    xy = np.random.default_rng(0).uniform(-80.0, 80.0, (1000, 2))
    geometry.photo_to_plane(cam, pose, xy)
    t0 = time.perf_counter()
    for _ in range(200):
        geometry.photo_to_plane(cam, pose, xy)
    per_call = (time.perf_counter() - t0) / 200
    assert per_call < 2e-3, per_call

"""aerophoto.plane: 2-D similarity, affine and projective fits from point pairs (with their residuals), rays,
their intersection and error triangle, resection from directions (guide §7, §10, §12 use them; re-exported by
aerophoto.projective)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import plane


# --------------------------------------------------------------------------- transformations on known points
def test_similarity_on_known_points_and_its_round_trip():
    # a quarter turn, twice as large, then a shift of (10, −5): (1, 0) → (10, −3), (0, 1) → (8, −5)
    S = plane.Similarity2D.from_angle(90.0, (10.0, -5.0), scale=2.0)
    np.testing.assert_allclose(S.apply([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]), [[10.0, -3.0], [8.0, -5.0], [10.0, -5.0]],
                               atol=1e-12)
    assert S.scale == pytest.approx(2.0) and S.rotation_deg == pytest.approx(90.0)
    P = np.array([[0.0, 0.0], [100.0, 0.0], [100.0, 50.0], [0.0, 50.0]])
    fit = plane.fit_similarity(P, S.apply(P), scale=True)
    assert (fit.a, fit.b, fit.tx, fit.ty) == pytest.approx((S.a, S.b, 10.0, -5.0), abs=1e-9)
    np.testing.assert_allclose(S.inverse().apply(S.apply(P)), P, atol=1e-12)
    np.testing.assert_allclose(S.compose(S.inverse()).matrix(), np.eye(3), atol=1e-12)
    with pytest.raises(ValueError, match="scale 0"):
        plane.Similarity2D(0.0, 0.0).inverse()


# --------------------------------------------------------------------------- fits (moved from test_projective.py)
def test_fits_recover_known_transformations_exactly():
    rng = np.random.default_rng(1)
    P = rng.uniform(-80, 80, size=(7, 2))
    S = plane.Similarity2D.from_angle(23.0, (5.0, -7.0), scale=1.7)
    A = plane.Affine2D(np.array([[1.2, 0.3, 4.0], [-0.2, 0.9, -3.0], [0, 0, 1.0]]))
    H = plane.Projective2D(np.array([[1.1, 0.05, 3.0], [-0.04, 0.95, -2.0], [2e-4, -1e-4, 1.0]]))
    for kind, T in (("similarity", S), ("affine", A), ("projective", H)):
        fit = plane.fit(kind, P, T.apply(P))
        assert fit.rms < 1e-9
        Q = rng.uniform(-80, 80, size=(5, 2))
        np.testing.assert_allclose(fit.transform.apply(Q), T.apply(Q), atol=1e-8)


def test_fit_residuals_grow_with_the_noise_as_expected():
    rng = np.random.default_rng(3)
    photo = rng.uniform(-80, 80, size=(40, 2))
    T = plane.Projective2D(np.array([[1.2, 0.1, 3.0], [-0.05, 1.1, -2.0], [3e-4, -2e-4, 1.0]]))
    exact = T.apply(photo)
    rms = []
    for sigma in (0.01, 0.04, 0.16):
        noisy = exact + rng.normal(0, sigma, size=exact.shape)
        rms.append(plane.fit("projective", photo, noisy).rms)
    # least squares over 40 pairs with 8 parameters: the residual RMS ≈ σ·√2·√(1 − 8/80)
    for r, sigma in zip(rms, (0.01, 0.04, 0.16)):
        assert r == pytest.approx(sigma * math.sqrt(2) * math.sqrt(1 - 8 / 80), rel=0.3)
    assert rms[0] < rms[1] < rms[2]


@pytest.mark.parametrize("src, match", [
    ([[0, 0], [1, 0], [2, 0], [0, 1]], "on one line"),
    ([[0, 0], [1, 0], [1, 1]], "needs at least 4"),
    ([[0, 0], [1, 0], [1, 1], [1, 1]], "coincide"),
])
def test_degenerate_input_to_the_projective_fit_is_named(src, match):
    src = np.asarray(src, float)
    with pytest.raises(ValueError, match=match):
        plane.fit_projective(src, src * 2.0)


def test_degenerate_input_to_the_affine_fit_is_named():
    with pytest.raises(ValueError, match="one line"):
        plane.fit_affine([[0, 0], [1, 1], [2, 2]], [[0, 0], [1, 0], [0, 1]])
    with pytest.raises(ValueError, match="at least 3"):
        plane.fit_affine([[0, 0], [1, 1]], [[0, 0], [1, 0]])


# --------------------------------------------------------------------------- rays and resection (moved from test_triangulation.py)
@settings(max_examples=40, deadline=None)
@given(cx=st.floats(-500, 500), cy=st.floats(-500, 500), th=st.floats(-3.1, 3.1), seed=st.integers(0, 1000))
def test_resection_recovers_a_template(cx, cy, th, seed):
    rng = np.random.default_rng(seed)
    K = rng.uniform(-300, 300, size=(4, 2)) + [cx, cy]
    if np.min(np.hypot(*(K - [cx, cy]).T)) < 20:
        K += 50.0
    d = K - [cx, cy]
    phi = np.arctan2(d[:, 1], d[:, 0]) - th  # directions measured on the template
    C, theta, r = plane.resect_directions(phi, K)
    assert np.hypot(*(C - [cx, cy])) < 1e-6
    assert math.remainder(theta - th, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)
    assert np.max(np.abs(r)) < 1e-6


def test_resection_with_an_initial_direction_line():
    C0 = np.array([10.0, 5.0])
    K = np.array([[100.0, 80.0], [120.0, -60.0], [-40.0, 0.0]])
    phi = np.arctan2(*(K - C0).T[::-1]) - 0.3
    C, th, r = plane.resect_directions(phi, K, line=(np.array([-40.0, 0.0]), math.atan2(5.0, 50.0)))
    assert np.allclose(C, C0) and th == pytest.approx(0.3) and len(r) == 4
    with pytest.raises(ValueError, match="at least 3"):
        plane.resect_directions(phi[:2], K[:2])


def test_error_triangle_and_ray_intersection():
    O = np.array([[0.0, 0.0], [100.0, 0.0], [50.0, -80.0]])
    P = np.array([50.0, 60.0])
    ang = np.arctan2(*(P - O).T[::-1])
    V, sides = plane.error_triangle(O, ang)
    assert np.max(sides) < 1e-9 and np.allclose(V, P)
    np.testing.assert_allclose(plane.intersect_rays(O, ang), P)
    # shift the third ray sideways by 0.3 mm: a triangle appears, its side on ray 1 is 0.3/sin of the angle
    O2 = O.copy()
    n = np.array([-math.sin(ang[2]), math.cos(ang[2])])
    O2[2] += 0.3 * n
    V, sides = plane.error_triangle(O2, ang)
    assert np.max(sides) > 0.3
    gamma = abs(math.remainder(ang[2] - ang[1], math.pi))
    assert sides[0] == pytest.approx(0.3 / math.sin(gamma), rel=1e-9)


@settings(max_examples=30, deadline=None)
@given(a=st.floats(-3.1, 3.1), tx=st.floats(-1e3, 1e3), ty=st.floats(-1e3, 1e3), s=st.floats(0.2, 5.0))
def test_rigid_and_similarity_fits(a, tx, ty, s):
    rng = np.random.default_rng(0)
    A = rng.uniform(-100, 100, size=(5, 2))
    R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    Bp = A @ R.T + [tx, ty]
    T2 = plane.fit_similarity(A, Bp).matrix()  # rigid: rotation + shift (what reduce_strip lays the strip with)
    R2, t2 = T2[:2, :2], T2[:2, 2]
    np.testing.assert_allclose(A @ R2.T + t2, Bp, atol=1e-8)
    S3 = plane.fit_similarity(A, s * Bp, scale=True)  # with a free scale (FreeStrip.similarity_to_truth)
    s3, R3, t3 = S3.scale, S3.matrix()[:2, :2] / S3.scale, S3.matrix()[:2, 2]
    assert s3 == pytest.approx(s, rel=1e-9)
    np.testing.assert_allclose(s3 * A @ R3.T + t3, s * Bp, atol=1e-7)

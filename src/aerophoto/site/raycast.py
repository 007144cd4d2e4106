"""Ray casting against the site's objects with height: the intersections the renderer and the DSM use.

Rays are ``S + u·D`` (S, D in ground metres, u ≥ 0).  :func:`hit_polyhedra`
(Cyrus–Beck clipping of convex polyhedra), :func:`hit_ellipsoids` (crowns) and
:func:`march_canopy` (the forest canopy's height field of 2 m columns, sampled
and refined by bisection) return entry depths; :func:`first_hits` finds, for
many rays at once, the nearest of the ground, the objects and the canopy, and
:func:`in_shadow` whether a surface point sees the sun.  A photo's rays and
the pairs (object, pixel) worth testing come from the camera model
(:func:`box_pixel_pairs`, :func:`box_point_pairs`: each object's bounding box
projected onto the photo).  Used by :mod:`aerophoto.render` and
:meth:`aerophoto.site.objects.SiteObjects.surface_height`; geometry only (layer 3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import geometry as g

__all__ = ["AMBIENT", "hit_polyhedra", "hit_ellipsoids", "march_canopy", "shading", "light_factor", "RayHits",
           "project_boxes", "box_pixel_pairs", "box_point_pairs", "ray_dirs", "first_hits", "canopy_hits",
           "in_shadow"]

#: brightness of a face turned away from the sun or in shadow, as a share of level ground in full sun
AMBIENT = 0.35


def hit_polyhedra(planes, k, S, D, *, min_u: float = 0.0):
    """Where rays ``S + u·D`` enter convex polyhedra (Cyrus–Beck clipping against every plane).

    Parameters
    ----------
    planes : (K, P, 4) planes ``n·x ≤ d`` of the polyhedra
    k : (N,) which polyhedron each ray is tested against
    S, D : (N, 3) or (3,) ray origins and directions, metres
    min_u : only entries beyond this depth count (a shadow ray leaving a surface)

    Returns
    -------
    u : (N,) entry depth (np.inf where the ray misses); a ray starting inside enters at u = 0
    plane : (N,) index of the entering plane (its face), −1 where missed
    """
    k = np.asarray(k, np.int64)
    out_u = np.full(len(k), np.inf)
    out_p = np.full(len(k), -1, np.int64)
    if len(k) == 0:
        return out_u, out_p
    S = np.broadcast_to(np.asarray(S, float), (len(k), 3))
    D = np.broadcast_to(np.asarray(D, float), (len(k), 3))
    used = np.any(planes[..., :3] != 0.0, axis=2).sum(axis=1)  # planes in use, per polyhedron
    for lo, hi in ((0, 8), (8, planes.shape[1])):  # small polyhedra (boxes) apart from the 12-sided prisms
        sel = np.flatnonzero((used[k] > lo) & (used[k] <= hi)) if lo else np.flatnonzero(used[k] <= hi)
        for c0 in range(0, len(sel), 65536):
            s = sel[c0:c0 + 65536]
            P = planes[k[s], :hi]  # (n, p, 4)
            num = P[..., 3] - np.einsum("npj,nj->np", P[..., :3], S[s])
            den = np.einsum("npj,nj->np", P[..., :3], D[s])
            with np.errstate(divide="ignore", invalid="ignore"):
                t = num / den
            enter = den < 0
            t_in = np.where(enter, t, -np.inf)
            p_in = np.argmax(t_in, axis=1)
            t_in = t_in[np.arange(len(s)), p_in]
            t_out = np.where(den > 0, t, np.inf).min(axis=1)
            never = np.any((den == 0) & (num < 0), axis=1)
            t0 = np.maximum(t_in, 0.0)
            hit = ~never & (t0 <= t_out) & (t_out > min_u) & (t0 >= min_u) & np.isfinite(t_in)
            out_u[s[hit]] = t0[hit]
            out_p[s[hit]] = p_in[hit]
    return out_u, out_p


def hit_ellipsoids(centre, radii, S, D, *, min_u: float = 0.0):
    """Where rays ``S + u·D`` enter ellipsoids with semi-axes (r, r, c) about ``centre``.

    ``centre`` (N, 3), ``radii`` (N, 2) per ray; S, D (N, 3) or (3,).  Returns
    ``(u, normal)``: the entry depth (np.inf where missed) and the unit outward
    normal there, (N, 3).
    """
    centre = np.asarray(centre, float).reshape(-1, 3)
    radii = np.asarray(radii, float).reshape(-1, 2)
    n = len(centre)
    S = np.broadcast_to(np.asarray(S, float), (n, 3))
    D = np.broadcast_to(np.asarray(D, float), (n, 3))
    sc = np.column_stack([radii[:, 0], radii[:, 0], radii[:, 1]])
    o = (S - centre) / sc
    d = D / sc
    a = np.einsum("ij,ij->i", d, d)
    b = np.einsum("ij,ij->i", o, d)
    c = np.einsum("ij,ij->i", o, o) - 1.0
    disc = b * b - a * c
    ok = disc >= 0
    root = np.sqrt(np.where(ok, disc, 0.0))
    u0 = (-b - root) / a
    u1 = (-b + root) / a
    u = np.where(u0 >= min_u, u0, np.where(c < 0, np.maximum(min_u, 0.0), np.inf))  # inside: at once
    u = np.where(ok & (u1 >= min_u) & (u >= min_u), u, np.inf)
    q = (S + np.where(np.isfinite(u), u, 0.0)[:, None] * D - centre) / (sc * sc)
    nrm = q / np.maximum(np.linalg.norm(q, axis=1, keepdims=True), 1e-12)
    return u, nrm


def march_canopy(objects, ground, S, D, u_start, u_end, *, step_m: float = 6.0, refine: int = 5):
    """Where rays ``S + u·D`` first meet the forest canopy (ground + canopy) between ``u_start`` and ``u_end``.

    ``ground`` is the bare earth: a callable ``height(X, Y)``, or a pair of
    arrays (Z at ``u_start``, Z at ``u_end``) between which the ground along
    each short piece of ray is taken as linear.  The surface is sampled at
    steps of at most ``step_m`` along the ray; the first sample under it is
    refined by bisection (``refine`` halvings) and then, within the last
    bracket, the ray is cut with the top of the column it ends in (exact on a
    column's top; on a column's wall within step/2^refine).  Returns u
    (np.inf where the ray stays above the canopy).
    """
    D = np.asarray(D, float)
    n = len(u_start)
    S = np.broadcast_to(np.asarray(S, float), (n, 3))
    D = np.broadcast_to(D, (n, 3))
    u_start = np.asarray(u_start, float)
    u_end = np.asarray(u_end, float)
    out = np.full(n, np.inf)
    if n == 0:
        return out
    seg = (u_end - u_start) * np.sqrt(np.einsum("ij,ij->i", D, D))  # length of each ray's piece, m
    n_steps = np.clip(np.ceil(seg / step_m).astype(np.int64), 1, 256)
    linear = not callable(ground)
    S32 = S.astype(np.float32)
    D32 = D.astype(np.float32)
    if linear:
        z0, z1 = (np.asarray(z, float) for z in ground)
        dz = (z1 - z0).astype(np.float32)
        z0 = z0.astype(np.float32)

    def below(u, frac, rows):
        """Whether the ray points at depths u (rows of rays) are under the surface (float32: cm at 10 km)."""
        u = u.astype(np.float32)
        frac = frac.astype(np.float32)
        Sr = S32[rows]
        Dr = D32[rows]
        X = Sr[:, 0, None] + u * Dr[:, 0, None]
        Y = Sr[:, 1, None] + u * Dr[:, 1, None]
        Z = Sr[:, 2, None] + u * Dr[:, 2, None]
        if linear:
            zg = z0[rows, None] + frac * dz[rows, None]
        else:
            zg = np.asarray(ground(X.ravel(), Y.ravel()), np.float32).reshape(X.shape)
        Z -= zg
        Z -= objects.canopy_at(X, Y)
        return Z <= -1e-3  # a millimetre under the surface (not the ground the piece of ray ends on)

    # every step of every ray at once, the longest pieces in blocks of rays with as many steps
    order = np.argsort(n_steps, kind="stable")
    for a in range(0, n, 16384):
        rows = order[a:a + 16384]
        k = int(n_steps[rows].max())
        frac = np.minimum(np.arange(1, k + 1)[None, :] / n_steps[rows, None], 1.0)
        du = (u_end - u_start)[rows, None]
        u = u_start[rows, None] + frac * du
        inside = below(u, frac, rows)
        hit = inside.any(axis=1)
        if not hit.any():
            continue
        first = np.argmax(inside, axis=1)[hit]
        r = rows[hit]
        hi = u[hit, first]
        f_hi = frac[hit, first]
        f_lo = np.where(first > 0, frac[hit, np.maximum(first - 1, 0)], 0.0)
        lo = u_start[r] + f_lo * (u_end - u_start)[r]
        for _ in range(refine):
            mid = 0.5 * (lo + hi)
            fm = 0.5 * (f_lo + f_hi)
            b = below(mid[:, None], fm[:, None], r)[:, 0]
            hi = np.where(b, mid, hi)
            f_hi = np.where(b, fm, f_hi)
            lo = np.where(b, lo, mid)
            f_lo = np.where(b, f_lo, fm)
        # the top of the column under ``hi``: where the ray's height equals ground + that canopy, if inside [lo, hi]
        Ph = S[r] + hi[:, None] * D[r]
        c = objects.canopy_at(Ph[:, 0], Ph[:, 1])
        span_u = np.where(u_end[r] > u_start[r], u_end[r] - u_start[r], 1.0)
        if linear:
            slope_g = dz[r].astype(float) / span_u  # ground height per unit u along the piece
            g_hi = z0[r].astype(float) + f_hi * dz[r].astype(float)
        else:
            slope_g = np.zeros(len(r))
            g_hi = np.asarray(ground(Ph[:, 0], Ph[:, 1]), float)
        # Z(u) = Ph_z + (u − hi)·D_z  and  top(u) = g_hi + c + (u − hi)·slope_g
        den = D[r, 2] - slope_g
        with np.errstate(divide="ignore", invalid="ignore"):
            u_top = hi + (g_hi + c - Ph[:, 2]) / den
        ok = np.isfinite(u_top) & (u_top >= lo) & (u_top <= hi)
        Pt = S[r] + np.where(ok, u_top, hi)[:, None] * D[r]  # … and still over that column (else: its wall)
        inv = 1.0 / objects.texel_m
        same = (np.floor(Pt[:, 0] * inv) == np.floor(Ph[:, 0] * inv)) & (np.floor(Pt[:, 1] * inv) == np.floor(Ph[:, 1] * inv))
        out[r] = np.where(ok & same & (c > 0), u_top, hi)
    return out


def shading(normal, light, ambient: float = 0.35) -> np.ndarray:
    """Brightness factor of a surface: ``ambient + (1 − ambient)·max(n·L, 0)/L_z`` (1 for level ground in sun).

    ``normal`` (N, 3) unit normals, ``light`` (3,) unit vector towards the sun.
    """
    L = np.asarray(light, float)
    cos = np.clip(np.asarray(normal, float) @ L, 0.0, None)
    return (ambient + (1.0 - ambient) * cos / max(L[2], 1e-6)).astype(np.float32)



@dataclass(frozen=True, eq=False)
class RayHits:
    """What the rays hit: full ``surface``/``object_id`` arrays; the rest for the rays that hit something (``idx``)."""

    surface: np.ndarray  # SURFACES code, every ray
    object_id: np.ndarray  # −1 for ground and canopy, every ray
    idx: np.ndarray  # the rays that hit an object or the canopy (sorted)
    u: np.ndarray  # their depth below S (Z = Z_S − u)
    normal: np.ndarray  # (len(idx), 3) unit normals
    albedo: np.ndarray  # a face's own brightness, NaN where the texture shows (canopy, textured faces)


def light_factor(normal, light) -> np.ndarray:
    """:func:`shading` with the book's ambient light, capped at 1.6 (a face turned right into the sun)."""
    return np.minimum(shading(normal, light, AMBIENT), np.float32(1.6))


def project_boxes(boxes, camera, pose) -> np.ndarray:
    """Photo-mm rectangles (x0, x1, y0, y1) of 3-D boxes (X0, X1, Y0, Y1, Z0, Z1); NaN for boxes behind S."""
    b = np.asarray(boxes, float)
    corners = np.stack([np.stack([b[:, i], b[:, j], b[:, k]], axis=1)
                        for i in (0, 1) for j in (2, 3) for k in (4, 5)], axis=1)  # (K, 8, 3)
    R = g.rotation_matrix(pose)
    front = np.all((corners - pose.centre) @ R[:, 2] < 0, axis=1)
    out = np.full((len(b), 4), np.nan)
    if front.any():
        xy = g.ground_to_photo(camera, pose, corners[front])
        out[front] = np.column_stack([xy[..., 0].min(1), xy[..., 0].max(1), xy[..., 1].min(1), xy[..., 1].max(1)])
    return out


def box_pixel_pairs(boxes, camera, pose, n, raster=None) -> tuple:
    """(box, pixel) pairs: the pixel centres of an n×n photo inside each box's projected rectangle.

    ``raster`` ``(x_left, y_top, p)`` mm: the pixel grid of a window of the frame (:func:`aerophoto.render.render`'s
    ``window_mm``); None: the whole frame.
    """
    rect = project_boxes(boxes, camera, pose)
    if raster is None:
        h, p = camera.half_mm, camera.frame_mm / n
        x0, y0 = -h, h
    else:
        x0, y0, p = raster
    ok = np.all(np.isfinite(rect), axis=1)
    c0 = np.ceil((rect[:, 0] - x0) / p - 0.5)
    c1 = np.floor((rect[:, 1] - x0) / p - 0.5)
    r0 = np.ceil((y0 - rect[:, 3]) / p - 0.5)
    r1 = np.floor((y0 - rect[:, 2]) / p - 0.5)
    c0, r0 = np.clip(np.nan_to_num(c0, nan=n), 0, n), np.clip(np.nan_to_num(r0, nan=n), 0, n)
    c1, r1 = np.clip(np.nan_to_num(c1, nan=-1), -1, n - 1), np.clip(np.nan_to_num(r1, nan=-1), -1, n - 1)
    nc = np.where(ok, c1 - c0 + 1, 0).clip(0).astype(np.int64)
    nr = np.where(ok, r1 - r0 + 1, 0).clip(0).astype(np.int64)
    # repeat counts in the platform's index type: numpy refuses int64 counts where intp is int32 (wasm32, the
    # browser book)
    cnt = (nr * nc).astype(np.intp)
    k = np.repeat(np.arange(len(rect)), cnt)
    local = np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    ncr = np.repeat(nc, cnt)
    rows = np.repeat(r0.astype(np.int64), cnt) + local // np.maximum(ncr, 1)
    cols = np.repeat(c0.astype(np.int64), cnt) + local % np.maximum(ncr, 1)
    return k, rows * n + cols


def box_point_pairs(boxes, camera, pose, xy_mm) -> tuple:
    """(box, point) pairs: the photo points inside each box's projected rectangle."""
    rect = project_boxes(boxes, camera, pose)
    xy = np.asarray(xy_mm, float).reshape(-1, 2)
    ks, ps = [], []
    step = max(1, int(4e6 // max(len(rect), 1)))
    for a in range(0, len(xy), step):
        q = xy[a:a + step]
        inside = ((q[:, None, 0] >= rect[None, :, 0]) & (q[:, None, 0] <= rect[None, :, 1])
                  & (q[:, None, 1] >= rect[None, :, 2]) & (q[:, None, 1] <= rect[None, :, 3]))
        pi, ki = np.nonzero(inside)
        ks.append(ki)
        ps.append(pi + a)
    return (np.concatenate(ks) if ks else np.zeros(0, np.int64)), (np.concatenate(ps) if ps else np.zeros(0, np.int64))


def ray_dirs(ax, ay, idx) -> np.ndarray:
    """Ray directions (len(idx), 3) per unit depth: (−a_x, −a_y, −1)."""
    out = np.empty((len(idx), 3))
    out[:, 0] = -ax[idx]
    out[:, 1] = -ay[idx]
    out[:, 2] = -1.0
    return out


def first_hits(site, objs, S, ax, ay, u_ground, k, ray, Xg=None, Yg=None) -> RayHits:
    """The nearest of the ground (depth ``u_ground``), the objects (pairs ``k``–``ray``) and the canopy, per ray.

    Ray i is ``S + u·(−ax[i], −ay[i], −1)``; ``Xg``, ``Yg`` (optional) are its ground hit's X, Y.
    """
    S = np.asarray(S, float)
    ug = np.asarray(u_ground, float)
    N = len(ug)
    surface = np.zeros(N, np.uint8)
    obj = np.full(N, -1, np.int32)
    n_poly = objs.n_polyhedra
    cand = []
    if len(k):
        poly = k < n_poly
        if poly.any():
            kp, rp = k[poly], ray[poly]
            uu, pl = hit_polyhedra(objs.planes, kp, S, ray_dirs(ax, ay, rp))
            ok = uu < ug[rp]
            cand.append((rp[ok], uu[ok], kp[ok], pl[ok], np.zeros((int(ok.sum()), 3))))
        if (~poly).any():
            ke, re = k[~poly], ray[~poly]
            e = ke - n_poly
            uu, nrm = hit_ellipsoids(objs.ell_centre[e], objs.ell_radii[e], S, ray_dirs(ax, ay, re))
            ok = uu < ug[re]
            cand.append((re[ok], uu[ok], ke[ok], np.full(int(ok.sum()), -1), nrm[ok]))
    r_ = np.zeros(0, np.int64)
    u_ = np.zeros(0)
    nrm_ = np.zeros((0, 3))
    alb_ = np.zeros(0, np.float32)
    if cand:
        r_ = np.concatenate([c[0] for c in cand])
        u_ = np.concatenate([c[1] for c in cand])
        k_ = np.concatenate([c[2] for c in cand])
        p_ = np.concatenate([c[3] for c in cand])
        n_ = np.concatenate([c[4] for c in cand])
        order = np.lexsort((u_, r_))
        r_, u_, k_, p_, n_ = r_[order], u_[order], k_[order], p_[order], n_[order]
        first = np.ones(len(r_), bool)
        first[1:] = r_[1:] != r_[:-1]
        r_, u_, k_, p_, n_ = r_[first], u_[first], k_[first], p_[first], n_[first]
        obj[r_] = k_
        isp = p_ >= 0
        kp, pp = k_[isp], p_[isp]
        nrm_ = n_.copy()
        nrm_[isp] = objs.planes[kp, pp, :3]
        surf = np.full(len(r_), 3, np.uint8)
        surf[isp] = objs.face[kp, pp]
        surface[r_] = surf
        alb_ = np.empty(len(r_), np.float32)
        top = objs.planes[kp, pp, 2] > 0.5
        alb_[isp] = np.where(objs.textured[kp, pp], np.nan, np.where(top, objs.albedo[kp, 0], objs.albedo[kp, 1]))
        alb_[~isp] = objs.ell_albedo[k_[~isp] - n_poly]
    if objs.canopy_dm.size and objs.canopy_max_m > 0:
        u_near = ug.copy()
        u_near[r_] = u_
        c_idx, c_u, c_n = canopy_hits(site, objs, S, ax, ay, u_near, ug, march_canopy, Xg, Yg)
        if len(c_idx):
            surface[c_idx] = 4
            obj[c_idx] = -1
            keep = ~np.isin(r_, c_idx)
            r_ = np.r_[r_[keep], c_idx]
            u_ = np.r_[u_[keep], c_u]
            nrm_ = np.vstack([nrm_[keep], c_n])
            alb_ = np.r_[alb_[keep], np.full(len(c_idx), np.nan, np.float32)]
            order = np.argsort(r_, kind="stable")
            r_, u_, nrm_, alb_ = r_[order], u_[order], nrm_[order], alb_[order]
    return RayHits(surface, obj, r_, u_, nrm_, alb_)


def canopy_hits(site, objs, S, ax, ay, u_near, u_ground, march, Xg=None, Yg=None) -> tuple:
    """Where the rays passing over the forest meet the canopy before ``u_near``: (rays, depths, normals)."""
    top = objs.canopy_max_m + 1.0
    ug = np.asarray(u_ground)
    # the ray's piece from ``top`` above its ground hit down to it is top·tg θ long horizontally: look for forest
    # that near its ground hit (rays grouped by that reach, in whole 8 m cells)
    Gx = S[0] - ug * ax if Xg is None else Xg
    Gy = S[1] - ug * ay if Yg is None else Yg
    tg = float(np.sqrt(np.max(ax * ax + ay * ay, initial=0.0)))
    cand = np.flatnonzero(objs.near_canopy(Gx, Gy, reach_m=top * tg + 2.0))
    empty = (np.zeros(0, np.int64), np.zeros(0), np.zeros((0, 3)))
    if not len(cand):
        return empty
    cells = np.ceil((top * np.hypot(ax[cand], ay[cand]) + 2.0) / 8.0).astype(np.int64)
    near = np.zeros(len(cand), bool)
    for c in np.unique(cells):
        sel = np.flatnonzero(cells == c)
        near[sel] = objs.near_canopy(Gx[cand[sel]], Gy[cand[sel]], reach_m=8.0 * c)
    cand = cand[near]
    if not len(cand):
        return empty
    D = ray_dirs(ax, ay, cand)
    G = np.column_stack([Gx[cand], Gy[cand], S[2] - ug[cand]])
    T = G - top * D  # where the ray is ``top`` above its ground hit
    zT = site.height(T[:, 0], T[:, 1])  # the ground may rise under the ray's upper part
    z_start = np.maximum(G[:, 2], zT) + top
    u0 = np.maximum(S[2] - z_start, 0.0)
    # the ground along the short piece of ray: linear from the point under its start to its ground hit
    P0 = S + u0[:, None] * D
    z0 = site.height(P0[:, 0], P0[:, 1])
    uc = march(objs, (z0, G[:, 2]), S, D, u0, ug[cand])
    hit = uc < np.asarray(u_near)[cand]
    if not hit.any():
        return empty
    idx = cand[hit]
    u = uc[hit]
    P = S + u[:, None] * D[hit]
    if getattr(objs, "crowns", None) is not None:  # the crowns' own surfaces (aerophoto.site.crowns)
        return idx, u, objs.crowns.normal_at(P[:, 0], P[:, 1], P[:, 2] - site.height(P[:, 0], P[:, 1]))
    d = objs.texel_m  # the canopy's normal from its slope over ± one texel (the gentle ground's slope left out)
    c = objs.canopy_at
    gx = (c(P[:, 0] + d, P[:, 1]) - c(P[:, 0] - d, P[:, 1])) / (2 * d)
    gy = (c(P[:, 0], P[:, 1] + d) - c(P[:, 0], P[:, 1] - d)) / (2 * d)
    nrm = np.column_stack([-gx, -gy, np.ones(len(idx))])
    return idx, u, nrm / np.linalg.norm(nrm, axis=1, keepdims=True)


def in_shadow(objs, site, Xs, Ys, Zs, obj, light, camera, pose, n, raster=None) -> np.ndarray:
    """Which pixels' surface points lie in the shadow of an object or of the canopy (the sun along ``light``).

    The pixels are those of an n×n photo of the frame, or of a window's ``raster`` (:func:`box_pixel_pairs`).
    """
    N = len(Zs)

    def P_at(i):
        return np.column_stack([Xs[i], Ys[i], Zs[i]])

    out = np.zeros(N, bool)
    L = np.asarray(light, float)
    # shadow volumes: each object's box swept away from the sun down to 5 m below its lowest ground
    b = objs.bbox
    drop = (b[:, 5] - (b[:, 4] - 5.0)) / L[2]
    sx, sy = -L[0] * drop, -L[1] * drop
    vol = np.column_stack([b[:, 0] + np.minimum(sx, 0), b[:, 1] + np.maximum(sx, 0), b[:, 2] + np.minimum(sy, 0),
                           b[:, 3] + np.maximum(sy, 0), b[:, 4] - 5.0, b[:, 5]])
    k, pix = box_pixel_pairs(vol, camera, pose, n, raster)
    keep = obj[pix] != k  # a face's own object shades it through the face's turn, not as a cast shadow
    k, pix = k[keep], pix[keep]
    eps = 0.05
    n_poly = objs.n_polyhedra
    poly = k < n_poly
    if poly.any():
        uu, _ = hit_polyhedra(objs.planes, k[poly], P_at(pix[poly]), L, min_u=eps)
        out[pix[poly][np.isfinite(uu)]] = True
    if (~poly).any():
        e = k[~poly] - n_poly
        uu, _ = hit_ellipsoids(objs.ell_centre[e], objs.ell_radii[e], P_at(pix[~poly]), L, min_u=eps)
        out[pix[~poly][np.isfinite(uu)]] = True
    if objs.canopy_dm.size and objs.canopy_max_m > 0:
        reach = (objs.canopy_max_m + 3.0) / max(math.tan(math.asin(min(L[2], 1.0))), 1e-3)
        cand = np.flatnonzero(~out & objs.near_canopy(Xs, Ys, reach_m=reach + 2.0))
        if len(cand):
            Pc = P_at(cand)
            u_end = np.full(len(cand), (objs.canopy_max_m + 3.0) / L[2])
            u0 = np.full(len(cand), 0.5 / L[2])
            E = Pc + u_end[:, None] * L
            ground = (site.height(Pc[:, 0], Pc[:, 1]), site.height(E[:, 0], E[:, 1]))  # linear under the ray
            uc = march_canopy(objs, ground, Pc, np.broadcast_to(L, (len(cand), 3)), u0, u_end)
            out[cand[np.isfinite(uc)]] = True
    return out

"""Contour soil interpretation (контурное почвенное дешифрирование, guide §14) done by a computer.

The guide's office interpretation begins by dividing the image into areas homogeneous in tone (colour) and
texture, and says that on photos taken from higher up "quantising the range of optical densities" can pick
out the areas of one soil type.  Here that step is an unsupervised classification: k-means clustering of the
pixels' band values (Lloyd, 1982; MacQueen, 1967), seeded with k-means++ (Arthur & Vassilvitskii, 2007) from a
fixed random seed, so the same image gives the same areas on every machine.  The areas are then compared
with a soil map (the field survey's truth) through their cross-table.

Layer 2: pure functions on arrays.

Public API
----------
``segment_tones(image, k, *, seed=0, iterations=30) -> ndarray`` — (ny, nx) labels 0…k−1 of an (ny, nx, b)
image, ordered by the areas' mean brightness (0 the darkest);
``contingency(labels, truth, n_classes=None) -> ndarray`` — (k, n) counts of cells with label i and class j;
``overlay(sheets, *, sure_share=0.7) -> (areas, sure)`` — the overlay technique (guide §14, the Delft method):
transparent sheets of keys laid together cut the image into areas of one combination of keys.
"""

from __future__ import annotations

import numpy as np

from . import _validate as V
from ._validate import check_int_range

__all__ = ["segment_tones", "contingency", "overlay"]


@V.checked(image=V.image(2, 3))
def segment_tones(image, k: int, *, seed: int = 0, iterations: int = 30) -> np.ndarray:
    """Divide an image into ``k`` tone-homogeneous areas by k-means on its band values.

    Parameters
    ----------
    image : array (ny, nx, b) or (ny, nx): band values (any units, finite)
    k : number of areas, 1 ≤ k ≤ 20
    seed : the k-means++ start's seed, 0 ≤ seed < 2**32
    iterations : at most this many Lloyd steps, 1…200 (it stops earlier when no cell changes area)

    Returns
    -------
    int64 array (ny, nx): the area of each cell, 0…k−1, numbered by increasing mean brightness (the mean of
    the bands), so the numbering does not depend on the start.
    """
    a = np.asarray(image, dtype=np.float64)
    if a.ndim == 2:
        a = a[..., None]
    if a.ndim != 3 or a.shape[0] * a.shape[1] == 0:
        raise ValueError(f"image has shape {np.shape(image)}; expected (ny, nx) or (ny, nx, bands), not empty")
    if not np.all(np.isfinite(a)):
        raise ValueError("image holds NaN or ±inf; every band value must be finite")
    k = check_int_range("k", k, 1, 20)
    seed = check_int_range("seed", seed, 0, 2**32 - 1)
    iterations = check_int_range("iterations", iterations, 1, 200)
    ny, nx, nb = a.shape
    X = a.reshape(-1, nb)
    n = len(X)
    if k > n:
        raise ValueError(f"k = {k} is more than the image's {n} cells; the valid range is 1 ≤ k ≤ {n}")
    rng = np.random.default_rng(seed)
    # k-means++ start
    centres = np.empty((k, nb))
    centres[0] = X[rng.integers(n)]
    d2 = ((X - centres[0]) ** 2).sum(axis=1)
    for j in range(1, k):
        total = d2.sum()
        i = int(rng.integers(n)) if total <= 0 else int(np.searchsorted(np.cumsum(d2), rng.random() * total))
        centres[j] = X[min(i, n - 1)]
        d2 = np.minimum(d2, ((X - centres[j]) ** 2).sum(axis=1))
    labels = np.full(n, -1, np.int64)
    for _ in range(iterations):
        dist = ((X[:, None, :] - centres[None, :, :]) ** 2).sum(axis=2)
        new = np.argmin(dist, axis=1)
        if np.array_equal(new, labels):
            break
        labels = new
        for j in range(k):
            members = labels == j
            if members.any():
                centres[j] = X[members].mean(axis=0)
    order = np.argsort(centres.mean(axis=1), kind="stable")
    rank = np.empty(k, np.int64)
    rank[order] = np.arange(k)
    return rank[labels].reshape(ny, nx)


def contingency(labels, truth, n_classes: int | None = None) -> np.ndarray:
    """The cross-table of two maps: entry (i, j) counts the cells with label ``i`` and true class ``j``.

    ``labels`` and ``truth``: whole-number arrays of one shape (values ≥ 0); ``n_classes``: the number of
    columns (None: the largest class + 1).  Shape (labels.max() + 1, n_classes).
    """
    a = np.asarray(labels)
    b = np.asarray(truth)
    if a.shape != b.shape or a.size == 0:
        raise ValueError(f"labels has shape {a.shape} and truth {b.shape}; they must be one (non-empty) shape")
    for name, x in (("labels", a), ("truth", b)):
        if not np.issubdtype(x.dtype, np.integer) or x.min() < 0:
            raise ValueError(f"{name} must hold whole numbers ≥ 0 (got dtype {x.dtype}, minimum {x.min()})")
    nc = int(b.max()) + 1 if n_classes is None else check_int_range("n_classes", n_classes, int(b.max()) + 1, 255)
    out = np.zeros((int(a.max()) + 1, nc), np.int64)
    np.add.at(out, (a.ravel(), b.ravel()), 1)
    return out


def overlay(sheets, *, sure_share: float = 0.7) -> tuple:
    """Lay transparent sheets of keys together (guide §14's overlay technique): the areas of one combination.

    Each sheet is a whole-number map (ny, nx) of the areas an interpreter outlined by one group of keys — tone
    on the first, relief on the second, vegetation or land use on the third.  Laid together, every cell belongs
    to the combination of its areas on all the sheets; the connected pieces of one combination are the candidate
    soil contours (контурное почвенное дешифрирование).

    A piece is **sure** (drawn solid) when its combination is the usual one within the first sheet's area it lies
    in — at least ``sure_share`` (0.5…1) of that area's cells have it: its keys agree.  The others are **doubtful**
    (drawn dashed): the tone says one thing, the relief or the cover another, and the field routes go through
    them.

    Returns ``(areas, sure)``: ``areas`` int64 (ny, nx), the piece of each cell (0, 1, … in the order of the
    pieces' first cells, row by row), and ``sure`` bool (n_pieces,).
    """
    from scipy.ndimage import label

    from ._validate import check_range

    share = check_range("sure_share", sure_share, 0.5, 1.0)
    if sheets is None or isinstance(sheets, (str, bytes)) or not hasattr(sheets, "__len__"):
        raise TypeError(f"sheets = {sheets!r:.40} is not a list of maps; expected (ny, nx) arrays of whole numbers")
    maps = [np.asarray(a) for a in sheets]
    if not maps:
        raise ValueError("sheets is empty; give at least one map of areas")
    shape = maps[0].shape
    for k, a in enumerate(maps):
        if a.shape != shape or a.ndim != 2 or a.size == 0:
            raise ValueError(f"sheets[{k}] has shape {a.shape}; every sheet must be one (ny, nx) shape, not empty")
        if not np.issubdtype(a.dtype, np.integer) or a.min() < 0:
            raise ValueError(f"sheets[{k}] must hold whole numbers ≥ 0 (got dtype {a.dtype})")
    combo = np.zeros(shape, np.int64)
    for a in maps:
        combo = combo * (int(a.max()) + 1) + a.astype(np.int64)
    pieces = np.zeros(shape, np.int64)
    n = 0
    for c in np.unique(combo):
        lab, k = label(combo == c)
        pieces[lab > 0] = lab[lab > 0] + n - 1
        n += k
    # renumber the pieces in the order of their first cells, row by row
    _, first = np.unique(pieces.ravel(), return_index=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty(n, np.int64)
    rank[order] = np.arange(n)
    pieces = rank[pieces]
    sure = np.zeros(n, bool)
    tone = maps[0]
    for t in np.unique(tone):
        in_t = tone == t
        combos, counts = np.unique(combo[in_t], return_counts=True)
        usual = combos[counts >= share * in_t.sum()]
        if len(usual):
            sure[np.unique(pieces[in_t & np.isin(combo, usual)])] = True
    return pieces, sure

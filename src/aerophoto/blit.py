"""Blitting: a live figure redraws only the artists that change, over a cached picture of the rest.

:class:`Blitter` replaces the figure's ``draw`` while it is active, so that a full draw keeps a background
without the animated artists; a slider move then restores that background, draws the animated set and blits.
:class:`aerophoto.widgets.LiveDemo` uses it for the artists a demo names in ``animated``.  The figure
builders and the book's style are :mod:`aerophoto.plots`; tests/presentation/test_blit.py and tests/presentation/test_blit_mosaic.py
compare blitted moves with full draws pixel by pixel.

:func:`nearest_pixels` makes an image that is enlarged by repeating its pixels (``interpolation="nearest"``) draw
by gathering them, instead of matplotlib's general resampling (2–9 ms a frame on a photo demo, 0.5–1 ms so).
"""

from __future__ import annotations

import contextlib

import numpy as np
from matplotlib.image import AxesImage

__all__ = ["Blitter", "NearestImage", "nearest_pixels"]


class NearestImage(AxesImage):
    """An :class:`~matplotlib.image.AxesImage` that draws ``interpolation="nearest"`` by gathering pixels.

    Whenever the image is nearest-interpolated, axis-aligned (linear axes, no rotation), unmasked and without an
    alpha of its own, each screen pixel's centre is carried back into the array and the pixel it falls in is
    copied, without the resampler's float conversion, premultiplication and filter.  The picture is matplotlib's
    but on a screen column or row whose pixel centres fall on a boundary between two array pixels, where agg's
    fixed-point rounding may take the other neighbour (tests/presentation/test_blit.py compares the two pixel by
    pixel: under 1 % of the pixels, each a neighbour's colour).  Anything else is drawn by matplotlib.
    Use :func:`nearest_pixels` on an image made by ``ax.imshow``.
    """

    _gather = None  # (key, rows, cols) of the last gather: the same screen layout reuses its index vectors

    def _make_image(self, A, in_bbox, out_bbox, clip_bbox, magnification=1.0, unsampled=False,
                    round_to_pixel_border=True):
        from matplotlib.transforms import Affine2D, Bbox, IdentityTransform

        fast = (not unsampled and round_to_pixel_border and self.get_interpolation() == "nearest"
                and self.get_alpha() is None and not np.ma.is_masked(A) and self.get_transform().is_affine
                and (A.ndim == 2 or (A.ndim == 3 and A.shape[2] in (3, 4))))
        clipped = Bbox.intersection(out_bbox, clip_bbox) if fast else None
        if clipped is None:
            return super()._make_image(A, in_bbox, out_bbox, clip_bbox, magnification, unsampled,
                                       round_to_pixel_border)
        e = clipped.extents * magnification  # rounded to whole screen pixels as matplotlib rounds them
        x0, y0 = np.floor(e[0] + 0.5), np.ceil(e[1] - 0.5 - 1e-8)
        x1, y1 = np.floor(e[2] + 0.5 + 1e-8), np.ceil(e[3] - 0.5)
        w, h = int(x1 - x0), int(y1 - y0)
        if w <= 0 or h <= 0:
            return None, 0, 0, None
        t0 = Affine2D().translate(0, -A.shape[0]).scale(1, -1) if self.origin == "upper" else IdentityTransform()
        t = (t0 + Affine2D().scale(in_bbox.width / A.shape[1], in_bbox.height / A.shape[0])
             .translate(in_bbox.x0, in_bbox.y0) + self.get_transform()
             + Affine2D().scale(magnification).translate(-x0, -y0))
        m = t.get_matrix()
        if m[0, 1] != 0 or m[1, 0] != 0 or abs(m[0, 0]) < 1 or abs(m[1, 1]) < 1:  # rotated, sheared or shrunk
            return super()._make_image(A, in_bbox, out_bbox, clip_bbox, magnification, unsampled,
                                       round_to_pixel_border)
        key = (tuple(m.ravel()), w, h, A.shape[:2])
        if self._gather is None or self._gather[0] != key:
            inv = np.linalg.inv(m)  # screen pixel centre → array (column, row) coordinates
            cols = np.floor(inv[0, 0] * (np.arange(w) + 0.5) + inv[0, 2]).astype(np.intp)
            rows = np.floor(inv[1, 1] * (np.arange(h) + 0.5) + inv[1, 2]).astype(np.intp)
            self._gather = (key, np.clip(rows, 0, A.shape[0] - 1), np.clip(cols, 0, A.shape[1] - 1))
        _, rows, cols = self._gather
        if self._imcache is None:  # the colours first, on the array's own pixels (matplotlib's norm, colormap and
            # byte conversion, kept until set_data or a new norm/colormap, as matplotlib keeps them), then the gather
            self._imcache = A if A.dtype == np.uint8 and A.ndim == 3 and A.shape[2] == 4 else \
                self.to_rgba(A, bytes=True, norm=(A.ndim == 2))
        out = self._imcache.take(rows, axis=0).take(cols, axis=1)  # row 0 at the bottom, as the resampler's
        return out, x0 / magnification, y0 / magnification, t


def nearest_pixels(image: AxesImage) -> AxesImage:
    """Turn an image made by ``ax.imshow`` into a :class:`NearestImage` (same data, norm, extent; drawn by
    gathering pixels whenever it is nearest-interpolated).  Returns the same artist."""
    if not isinstance(image, AxesImage):
        raise TypeError(f"image = {image!r:.60} is a {type(image).__name__}; expected an AxesImage (ax.imshow)")
    image.__class__ = NearestImage  # no state of its own beyond the gather's cache: a class change is enough
    return image


def _overlapping_axes_labels(fig, top: list, ids: set) -> set:
    """The axes (ticks and labels) of later Axes that reach over an Axes with animated artists.

    Figure order draws a later Axes' labels over an earlier Axes' data (e.g. one panel's y label crossing
    its neighbour's spine); such an axis is animated too, so it is drawn after the animated data, as before.
    """
    from matplotlib.axes import Axes

    try:
        renderer = fig.canvas.get_renderer()
    except Exception:  # a canvas without an Agg renderer: keep the declared set
        return set()
    extra = set()
    axes = [a for a in top if isinstance(a, Axes)]
    for i, A in enumerate(axes):
        if id(A) not in ids and not any(id(c) in ids for c in A.get_children()):
            continue
        region = A.get_tightbbox(renderer)
        if region is None:
            continue
        for B in axes[i + 1:]:
            if id(B) in ids:
                continue
            for axis in B._axis_map.values():
                box = axis.get_tightbbox(renderer) if axis.get_visible() else None
                if box is not None and box.overlaps(region):
                    extra.add(id(axis))
    return extra


def _axes_draw_order(ax) -> list:
    """The children of ``ax`` in the order ``Axes.draw`` draws them (patch first, left out here)."""
    kids = [a for a in ax.get_children() if a is not ax.patch]
    if not (ax.axison and ax._frameon):
        kids = [a for a in kids if a not in ax.spines.values()]
    if not ax.axison:
        kids = [a for a in kids if a not in ax._axis_map.values()]
    return sorted(kids, key=lambda a: a.get_zorder())  # stable, as matplotlib's sort


def _outside_data_area(ax, artist) -> bool:
    """Whether ``artist`` of ``ax`` never paints inside the axes box (its titles, placed above it)."""
    return artist in (ax.title, ax._left_title, ax._right_title)


def _ticks_out(axis) -> bool:
    """Whether all of ``axis``'s tick marks point out of the axes box (labels are outside it anyway)."""
    return all(t._tickdir == "out" for t in axis.get_major_ticks() + axis.get_minor_ticks())


def _grid_on(axis) -> bool:
    return any(t.gridline.get_visible() for t in axis.get_major_ticks() + axis.get_minor_ticks())


class _GridLines:
    """Stand-in for an Axis in the animated set: its grid lines (the only part of it inside the axes box).

    While active, the Axis draws without its grid in a normal (non-saving) draw, so the background holds its
    ticks and labels but no grid; the grid is drawn here, in the Axis' turn, over the animated artists.
    """

    def __init__(self, axis):
        self.axis = axis
        self.axes = axis.axes
        self.active = False

    def _gridlines(self):
        return [t.gridline for t in self.axis.get_major_ticks() + self.axis.get_minor_ticks()]

    def _draw_axis(self, renderer, *args, **kwargs):
        axis = self.axis
        if not self.active or axis.figure.canvas.is_saving():
            return type(axis).draw(axis, renderer, *args, **kwargs)
        axis._update_ticks()  # creates the ticks this draw will use (a new tick copies the grid setting)
        hidden = [(g, g._visible) for g in self._gridlines()]
        for g, _ in hidden:
            g._visible = False  # not set_visible: that would mark the figure stale
        try:
            return type(axis).draw(axis, renderer, *args, **kwargs)
        finally:
            for g, v in hidden:
                g._visible = v

    def set_animated(self, value) -> None:
        self.active = bool(value)
        if self.active:
            self.axis.draw = self._draw_axis
        else:
            self.axis.__dict__.pop("draw", None)

    def get_zorder(self):
        return self.axis.get_zorder()

    def draw(self, renderer) -> None:
        if not self.axis.get_visible():
            return
        for tick in self.axis._update_ticks():
            if tick.get_visible():
                tick.gridline.draw(renderer)


class Blitter:
    """Draw only the artists of a figure that change, over a cached picture of the rest (blitting).

    ``Blitter(fig, artists)`` marks ``artists`` as animated: a full draw of the
    figure paints everything else, keeps that picture (the *background*) and
    then paints the animated artists on top — so every full draw (``canvas.draw()``,
    ipympl's own redraws, ``savefig``) still shows the whole figure.  An artist
    may be a whole Axes (e.g. one whose limits and ticks change on every move).

    :meth:`update` restores the background, draws only the animated artists and
    blits (ipympl sends the changed pixels as one PNG diff, at once, without
    the browser round trip of ``draw_idle``).  It declines — returns False, the
    caller then draws in full — when there is no background yet, when the
    figure's size or dpi changed, or when anything *not* animated changed since
    the background was taken (matplotlib marks the figure ``stale``; animated
    artists do not).

    The picture equals a full draw's because the animated set is closed
    upwards: within an Axes, every artist drawn after the first animated one
    (higher zorder: spines, later lines, texts) is animated as well and redrawn
    in matplotlib's order — except those that never paint inside the axes box:
    its titles, and an axis with outward ticks, which stays in the background
    with only its grid lines redrawn (:class:`_GridLines`).  The axis of a later
    Axes whose labels reach over animated artists is animated too, so it is
    drawn over them as before.  The set is recomputed before every full draw
    (artists added meanwhile join it).  ``savefig`` (and so the inline
    backend) draws the figure as if nothing were animated.  tests/presentation/test_blit.py
    compares blitted moves with full draws pixel by pixel.
    """

    def __init__(self, fig, artists):
        self.fig = fig
        self.declared = list(artists)
        self._grids = {}  # Axis → its _GridLines stand-in (one per Axis, kept across refreshes)
        self.artists = []
        self._refresh()
        self.background = None
        self._key = None
        self._fresh_for = None  # the layout key the animated set was last computed for by update()
        self.n_full = 0  # full draws that took a background
        self.n_blit = 0  # moves drawn by blitting
        self._cid = fig.canvas.mpl_connect("draw_event", self._on_draw)
        fig.draw = self._draw_figure

    def _refresh(self) -> None:
        """(Re)compute the animated set: artists added since (e.g. more labels) take their place in it."""
        new = self._closure(self.fig, self.declared, self._grids)
        keep = {id(a) for a in new}
        for a in self.artists:
            if id(a) not in keep:
                a.set_animated(False)
        for a in new:
            a.set_animated(True)
        self.artists = new

    @staticmethod
    def _closure(fig, declared: list, grids: dict) -> list:
        from matplotlib.axes import Axes
        from matplotlib.axis import Axis

        ids = {id(a) for a in declared}
        out = []
        top = sorted((a for a in fig.get_children() if a is not fig.patch), key=lambda a: a.get_zorder())
        ids |= _overlapping_axes_labels(fig, top, ids)
        for a in top:
            if id(a) in ids:
                out.append(a)
            elif isinstance(a, Axes):
                order = _axes_draw_order(a)
                first = next((i for i, c in enumerate(order) if id(c) in ids), None)
                if first is not None:
                    for c in order[first:]:
                        if id(c) in ids:
                            out.append(c)
                        elif isinstance(c, Axis) and _ticks_out(c):
                            if _grid_on(c):  # only its grid lies over the data: the grid is redrawn, not the labels
                                out.append(grids.setdefault(c, _GridLines(c)))
                        elif not _outside_data_area(a, c):
                            out.append(c)
        missing = ids - {id(a) for a in out if not isinstance(a, _GridLines)}
        if missing:
            raise ValueError("some animated artists are neither Axes of the figure nor children of its Axes")
        return out

    def _layout_key(self):
        canvas = self.fig.canvas
        return (canvas.get_width_height(physical=True), float(self.fig.dpi), tuple(self.fig.bbox.bounds))

    def _draw_figure(self, renderer, *args, **kwargs):
        """``fig.draw`` while blitting: a saved figure (``savefig``, the inline backend) is drawn as if nothing
        were animated — exactly the picture without blitting; an on-screen draw leaves the animated set out."""
        fig = self.fig
        if not fig.canvas.is_saving():
            return type(fig).draw(fig, renderer, *args, **kwargs)
        for a in self.artists:
            a.set_animated(False)
        try:
            return type(fig).draw(fig, renderer, *args, **kwargs)
        finally:
            for a in self.artists:
                a.set_animated(True)

    def _quiet(self):
        """While the animated set is drawn or measured: no ``draw_idle`` from stale artists (pyplot's interactive
        mode asks for one whenever an artist is marked stale — here that would be another full draw per move)."""
        cntx = getattr(self.fig.canvas, "_idle_draw_cntx", None)
        return cntx() if cntx is not None else contextlib.nullcontext()

    def _on_draw(self, event) -> None:
        with self._quiet():
            self._after_full_draw(event)

    def _after_full_draw(self, event) -> None:
        canvas = self.fig.canvas
        renderer = event.renderer
        if canvas.is_saving():  # drawn whole by _draw_figure
            return
        take = hasattr(canvas, "copy_from_bbox") and renderer is getattr(canvas, "renderer", None)
        if take:
            self.background = canvas.copy_from_bbox(self.fig.bbox)
            self._key = self._layout_key()
            self.n_full += 1
        for a in self.artists:
            a.draw(renderer)
        fresh, self._fresh_for = self._fresh_for, None
        if take and fresh != self._key:
            # this draw laid the figure out (its first, or a new size): if that changed which labels overlap
            # the animated artists, the set is recomputed and the next move draws in full once more.  (Not
            # after a move's full draw at the same size: update() has just computed the set for it.)
            if [id(a) for a in self._closure(self.fig, self.declared, self._grids)] != [id(a) for a in self.artists]:
                self._refresh()
                self.background = None
        # drawing an axis (or measuring it) re-places its label, marking it, its Axes and the figure stale:
        # the picture is current
        self.fig.stale = False

    def update(self) -> bool:
        """Redraw the animated artists over the background and blit; False if a full draw is needed instead."""
        fig, canvas = self.fig, self.fig.canvas
        if self.background is None or fig.stale or self._key != self._layout_key():
            self._refresh()  # the full draw that follows takes the background without the animated set
            # the set is current for this layout: the full draw need not compute it again (_after_full_draw)
            same_size = self.background is not None and self._key == self._layout_key()
            self._fresh_for = self._key if same_size else None
            return False
        with self._quiet():
            canvas.restore_region(self.background)
            renderer = canvas.get_renderer()
            for a in self.artists:
                a.draw(renderer)
            fig.stale = False  # as after a full draw (see _on_draw)
        canvas.blit(fig.bbox)
        self.n_blit += 1
        return True

    def disconnect(self) -> None:
        """Stop blitting: the artists are ordinary again (a full draw shows them as before)."""
        self.fig.canvas.mpl_disconnect(self._cid)
        self.fig.__dict__.pop("draw", None)
        for a in [*self.artists, *self._grids.values()]:
            a.set_animated(False)
        self.background = None
        self.fig.stale = True

"""Views of the virtual world: the site as a map and a rendered photo, with the guide's point symbols.

Presentation for :mod:`aerophoto.site` and :mod:`aerophoto.render` (which are
data only).  Ground points are drawn as the guide draws them: control points
(опознаки) as open triangles, other points as open circles.

* :func:`plot_site` — the site's texture as a map in ground metres, its
  catalogue points and, optionally, photo footprints;
* :func:`plot_points` — catalogue points on any axes (ground X, Y or photo x, y);
* :class:`PhotoView` — a photo in photo millimetres whose ``update(photo)``
  replaces the image and moves the points in place (for live demos);
  :func:`show_photo` builds one for a photo.
"""

from __future__ import annotations

import numpy as np

from .. import plots

__all__ = ["plot_site", "plot_points", "PhotoView", "show_photo"]


def plot_site(site, ax=None, *, points: bool = True, labels: bool = False, level: int | None = None,
              footprints=None, cmap="gray"):
    """Show the site as a map: texture (greyscale), catalogue points with the guide's symbols.

    Parameters
    ----------
    site : aerophoto.site.Site
    ax : matplotlib Axes or None (a new figure)
    points : bool
        Draw the catalogue (control points as triangles, others as circles).
    labels : bool
        Write the control points' ids beside them.
    level : int or None
        Pyramid level to show (default: one that gives at most ~2000 pixels across).
    footprints : array_like, shape (n, k, 2 or 3), optional
        Photo footprints (ground polygons, metres) to outline, e.g. ``strip.footprints()``.

    Returns
    -------
    dict with the artists: ``"image"``, ``"points"`` (see :func:`plot_points`), ``"footprints"``.
    """
    fig, ax = plots.new_axes(ax)
    if level is None:
        level = 0
        while level < site.n_levels - 1 and site.texture_level(level).shape[1] > 2000:
            level += 1
    img = ax.imshow(site.texture_level(level), cmap=cmap, vmin=0, vmax=255, origin="lower",
                    extent=site.extent_m, interpolation="antialiased")
    ax.set_xlabel("X, m")
    ax.set_ylabel("Y, m")
    ax.set_aspect("equal")
    ax.grid(False)
    out = {"image": img, "points": None, "footprints": []}
    if footprints is not None:
        for fp in np.asarray(footprints, dtype=float):
            p = np.vstack([fp[:, :2], fp[:1, :2]])
            (ln,) = ax.plot(p[:, 0], p[:, 1], color=plots.COLORS["footprint"], lw=1.2)
            out["footprints"].append(ln)
    if points:
        out["points"] = plot_points(ax, site.catalogue, x="X_m", y="Y_m", labels=labels)
    ax.set_xlim(site.extent_m[0], site.extent_m[1])
    ax.set_ylim(site.extent_m[2], site.extent_m[3])
    return out


def plot_points(ax, points, *, x: str = "X_m", y: str = "Y_m", labels: bool = False, size: float = 7.0,
                control_color=None, other_color=None):
    """Draw catalogue points with the guide's symbols on ``ax``.

    Control points (опознаки, ``control`` True) are open triangles, the other
    points open circles.  ``points`` is a DataFrame with the columns ``x``,
    ``y`` (ground ``X_m``/``Y_m`` by default; photo ``x_mm``/``y_mm`` work too),
    ``control`` and ``id``.  With ``labels`` the control points' ids are written.

    Returns a dict ``{"control": Line2D, "other": Line2D, "labels": [Text]}``;
    move them with ``set_data`` on update.
    """
    if ax is None:
        _, ax = plots.new_axes(None)
    df = points
    ctrl = df["control"].to_numpy(dtype=bool) if len(df) else np.zeros(0, bool)
    cc = control_color or plots.COLORS["control"]
    oc = other_color or plots.COLORS["yellow"]
    (lo,) = ax.plot(df[x].to_numpy()[~ctrl], df[y].to_numpy()[~ctrl], linestyle="none", marker="o", ms=size * 0.8,
                    mfc="none", mec=oc, mew=1.5, label="ground points", zorder=5)
    (lc,) = ax.plot(df[x].to_numpy()[ctrl], df[y].to_numpy()[ctrl], linestyle="none", marker="^", ms=size * 1.3,
                    mfc="none", mec=cc, mew=2.0, label="control points (опознаки)", zorder=6)
    texts = []
    if labels:
        for _, r in df[ctrl].iterrows():
            texts.append(ax.annotate(str(r["id"]), (r[x], r[y]), xytext=(5, 5), textcoords="offset points",
                                     color=cc, fontsize=10, fontweight="bold", zorder=7))
    return {"control": lc, "other": lo, "labels": texts}


class PhotoView:
    """A photo in photo millimetres, with points marked by the guide's symbols.

    ``view = PhotoView(ax=None)`` builds the artists once; ``view.update(photo)``
    (a :class:`aerophoto.render.Photo`) replaces the image data and moves the
    points in place (for live demos).
    """

    def __init__(self, ax=None, *, points: bool = True, labels: bool = False, cmap: str = "gray"):
        self.fig, self.ax = plots.new_axes(ax)
        self.show_points = points
        self.labels = labels
        self.image = self.ax.imshow(np.zeros((2, 2), np.float32), cmap=cmap, vmin=0.0, vmax=1.0,
                                    extent=(-90, 90, -90, 90), interpolation="antialiased")
        (self.control,) = self.ax.plot([], [], linestyle="none", marker="^", ms=9, mfc="none",
                                       mec=plots.COLORS["control"], mew=2.0, label="control points (опознаки)")
        (self.other,) = self.ax.plot([], [], linestyle="none", marker="o", ms=6, mfc="none",
                                     mec=plots.COLORS["yellow"], mew=1.5, label="ground points")
        self.texts = []
        self.ax.set_xlabel("x, mm")
        self.ax.set_ylabel("y, mm")
        self.ax.set_aspect("equal")
        self.ax.grid(False)

    def update(self, photo):
        self.image.set_data(photo.image)
        self.image.set_extent(photo.extent_mm)
        h = photo.camera.half_mm
        self.ax.set_xlim(-h, h)
        self.ax.set_ylim(-h, h)
        for t in self.texts:
            t.remove()
        self.texts = []
        if self.show_points:
            df = photo.points()
            df = df[df["visible"]]
            c = df["control"].to_numpy(dtype=bool)
            self.control.set_data(df["x_mm"].to_numpy()[c], df["y_mm"].to_numpy()[c])
            self.other.set_data(df["x_mm"].to_numpy()[~c], df["y_mm"].to_numpy()[~c])
            if self.labels:
                for _, r in df[c].iterrows():
                    self.texts.append(self.ax.annotate(str(r["id"]), (r["x_mm"], r["y_mm"]), xytext=(5, 5),
                                                       textcoords="offset points", color=plots.COLORS["control"],
                                                       fontsize=10, fontweight="bold"))
        else:
            self.control.set_data([], [])
            self.other.set_data([], [])
        return self


def show_photo(photo, ax=None, *, points: bool = True, labels: bool = False, title: str | None = None) -> PhotoView:
    """Show a photo in photo mm with its visible catalogue points; returns the :class:`PhotoView`.

    The title is ``title``, else "photo <number>" when the photo has a number.
    """
    view = PhotoView(ax, points=points, labels=labels)
    view.update(photo)
    if title is not None:
        view.ax.set_title(title)
    elif photo.number is not None:
        view.ax.set_title(f"photo {photo.number}")
    return view

"""plots.PointLabels: photo numbers as one collection of glyph outlines — where they land, their size, errors."""

from __future__ import annotations

import numpy as np
import pytest

from aerophoto import plots


def _figure(dpi=100):
    fig = plots.figure(figsize=(4, 3), dpi=dpi)
    ax = fig.add_axes([0, 0, 1, 1])
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 10)
    ax.set_axis_off()
    return fig, ax


def _ink(fig):
    """Pixels darker than mid-grey: where the black glyphs are."""
    fig.canvas.draw()
    rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    return rgb.sum(axis=-1) < 3 * 100


def test_the_labels_sit_right_and_up_of_their_points_and_follow_a_move():
    fig, ax = _figure()
    labels = plots.PointLabels(ax, offset_pt=(4.0, 4.0), fontsize=12)
    labels.set([(2.0, 2.0)], ["7"])
    ink = _ink(fig)
    rows, cols = np.nonzero(ink)
    px, py = ax.transData.transform((2.0, 2.0))
    H = fig.canvas.get_width_height()[1]
    # right of and above the point (image rows grow downwards), within a glyph's size of it
    assert cols.min() > px and cols.min() - px < 12
    assert (H - rows.max()) > py and (H - rows.max()) - py < 12
    labels.set([(8.0, 8.0)], ["7"])
    rows2, cols2 = np.nonzero(_ink(fig))
    dx = ax.transData.transform((8.0, 8.0))[0] - px
    assert cols2.min() - cols.min() == pytest.approx(dx, abs=1.5)


def test_the_labels_scale_with_the_dpi_as_text_does():
    sizes = []
    for dpi in (100, 200):
        fig, ax = _figure(dpi)
        plots.PointLabels(ax, fontsize=12).set([(5.0, 5.0)], ["10"])
        rows, cols = np.nonzero(_ink(fig))
        sizes.append((cols.max() - cols.min(), rows.max() - rows.min()))
    assert sizes[1][0] == pytest.approx(2 * sizes[0][0], rel=0.15)
    assert sizes[1][1] == pytest.approx(2 * sizes[0][1], rel=0.15)


def test_colours_per_label_and_a_text_for_every_point():
    fig, ax = _figure()
    labels = plots.PointLabels(ax)
    labels.set([(1, 1), (5, 5)], [1, 2], ["#D55E00", "#000000"])
    assert np.allclose(labels.glyphs.get_facecolors()[0][:3], (0xD5 / 255, 0x5E / 255, 0))
    assert len(labels.glyphs.get_paths()) == 2 and len(labels.halo.get_paths()) == 2
    with pytest.raises(ValueError, match="2 texts for 3 points"):
        labels.set([(1, 1), (2, 2), (3, 3)], ["1", "2"])

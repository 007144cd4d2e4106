"""The browser benchmark's floor (chapter 00's ray, :class:`aerophoto.demos.ray.RayDemo`) in a real browser.

``benchmarks/bench_browser.py`` reports every demo's latency as a multiple of this demo's, measured beside it; so
the floor must stay what it claims to be — one line moved per key press — on the page, in Voilà, as a lecturer
shows it: every key press paints exactly one new frame, the picture changes only along the ray (a thin wedge
inside the axes, well under 3 % of the figure), the readout and the table follow.  (Speed itself is measured by
the benchmark, never asserted here.)
"""

from __future__ import annotations

import pytest

from . import harness as h
from .chapters import CHAPTERS
from .test_voila import voila_demo_root

pytestmark = [pytest.mark.browser, pytest.mark.timeout(900)]


def _floor():
    ch = next(c for c in CHAPTERS if c.number == "00")
    return ch, next(d for d in ch.demos if d.cell == "demo-ray")


def test_the_floor_paints_one_frame_of_one_line_per_key_press(voila, tab):
    from aerophoto.book import lecture_page

    chapter, demo = _floor()
    page = tab.page
    h.open_voila(page, voila, lecture_page(chapter))
    root = voila_demo_root(page, demo)
    probe = h.DemoProbe(page, root)
    probe.wait_rendered()
    label = demo.timed_slider
    for key in ("ArrowRight", "ArrowRight", "ArrowLeft", "PageDown"):
        draws0 = probe.draws()
        r = probe.move(label, key)
        tab.add(f"floor-{key}-after", r["png_after"])
        assert r["value_after"] != r["value_before"], f"{key} did not move {label!r}"
        assert probe.draws() == draws0 + 1, f"{key}: {probe.draws() - draws0} frames painted for one move"
        change = h.pixel_change(r["png_before"], r["png_after"])
        assert 0.0005 <= change < 0.03, f"{key}: {change:.2%} of the figure changed; the floor moves one line"
        assert r["table_after"] != r["table_before"], f"{key}: the table did not follow"
    assert not probe.status_text()

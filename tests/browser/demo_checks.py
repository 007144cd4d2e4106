"""What every live demo must do in a real browser (shared by the JupyterLab and Voilà tests)."""

from __future__ import annotations

from . import harness as h

#: a slider move must change at least this fraction of the figure's pixels
MIN_PIXEL_CHANGE = 0.0001  # 0.01 % of the pixels: the one-ray demo (chapter 00) moves one thin line (0.026 %)


def exercise_demo(tab, root, demo, where: str, *, after_move=None) -> dict:
    """Move each headline slider of ``demo`` with the keyboard, then press Reset.

    Asserts for every move: the slider's readout changed, the figure's pixels
    changed, the numbers in the table changed, no ⚠ status; Reset always
    returns the readouts and the table to the same (default) state.  ``after_move``
    (e.g. waiting for the kernel to be idle) runs after each move.  Returns the
    measured pixel changes, label → fraction.
    """
    page = tab.page
    probe = h.DemoProbe(page, root)
    probe.wait_rendered()
    labels = probe.slider_labels()
    missing = [label for label, _key in demo.sliders if label not in labels]
    assert not missing, f"{where}: sliders {missing} not found; the demo has {labels}"
    png0 = probe.canvas_png()
    assert h.figure_is_drawn(png0), f"{where}: the figure's canvas is blank"
    tab.add(f"{demo.cell}-0-start-viewport", page.screenshot())
    tab.add(f"{demo.cell}-0-start-figure", png0)
    changes = {}
    for i, (label, key) in enumerate(demo.sliders, start=1):
        r = probe.move(label, key)
        if after_move:
            after_move()
        slug = "".join(ch if ch.isalnum() else "_" for ch in label)
        tab.add(f"{demo.cell}-{i}-{slug}-before", r["png_before"])
        tab.add(f"{demo.cell}-{i}-{slug}-after", r["png_after"])
        assert r["value_after"] != r["value_before"], f"{where}: {key} did not move slider {label!r}"
        change = h.pixel_change(r["png_before"], r["png_after"])
        changes[label] = change
        assert change >= MIN_PIXEL_CHANGE, (
            f"{where}: moving {label!r} {r['value_before']} → {r['value_after']} changed only "
            f"{change:.4%} of the figure's pixels")
        assert r["table_after"] != r["table_before"], f"{where}: moving {label!r} left the table unchanged"
        assert not probe.status_text(), f"{where}: the demo reports {probe.status_text()!r}"
    tab.add(f"{demo.cell}-9-after-moves-viewport", page.screenshot())

    # Reset returns to the demo's defaults (which need not be the chapter's starting values): press it,
    # note where it lands, move a slider away again, press it again, and it must land at the same place
    moved_table = probe.table_text()
    labels_only = [label for label, _key in demo.sliders]

    def reset_and_wait(table_before):
        root.locator("button", has_text="Reset").first.click()
        page.wait_for_function(
            "([el, t0]) => { const t = el.querySelector('.aerophoto-table'); return !!t && t.innerText !== t0; }",
            arg=[root.element_handle(), table_before], timeout=h.T_MOVE, polling=50,
        )
        # the Reset's picture, and a full-resolution one the page may still be owed (a demo's settle delay is
        # 0.25–0.35 s): wait for no scheduled work and a figure quiet for longer than that delay
        probe.wait_idle(quiet_ms=800)
        if after_move:
            after_move()
        return probe.table_text(), {label: probe.readout(label) for label in labels_only}

    reset_table, reset_values = reset_and_wait(moved_table)
    label, key = demo.sliders[0]
    probe.move(label, key)
    if after_move:
        after_move()
    again_table, again_values = reset_and_wait(probe.table_text())
    assert again_values == reset_values, f"{where}: Reset gave {again_values}, then {reset_values}"
    assert again_table == reset_table, f"{where}: Reset did not restore the table"
    return changes


def assert_clean(tab, where: str) -> None:
    """No error or stderr output on the page and no console error from our code."""
    errors = h.error_outputs(tab.page)
    assert not errors, f"{where}: error output on the page: {errors}"
    console = tab.log.relevant()
    assert not console, f"{where}: browser console errors: {console}"

"""Calm while sliding: the table follows the picture within TABLE_DELAY_S even while moves keep coming, a discrete
step is drawn at full resolution at once, and the status line keeps its height."""

from __future__ import annotations

import asyncio

import matplotlib

matplotlib.use("Agg")


def test_a_table_is_never_frozen_on_an_old_move():
    """Moves faster than TABLE_DELAY_S: the pending table keeps its time and shows the newest move (chapter 16's
    table said 1225 nodes while the figure said 196)."""
    from aerophoto.demos.displacement import ReliefDemo
    from aerophoto.widgets import TABLE_DELAY_S

    async def drive():
        demo = ReliefDemo()
        ctl = demo.controls()["relief_m"]
        seen = []
        for k, relief in enumerate((85.0, 90.0, 95.0, 100.0, 105.0, 110.0)):
            ctl.value = relief
            await asyncio.sleep(TABLE_DELAY_S / 3)  # moves three times faster than the table's delay
        await asyncio.sleep(TABLE_DELAY_S + 0.05)
        seen.append(demo.table.value)
        demo.set(relief_m=110.0)  # the same state, set from code: the table as it must be
        seen.append(demo.table.value)
        demo.close()
        return seen

    moved, expected = asyncio.run(drive())
    assert moved == expected


def test_the_table_shows_up_while_moves_keep_coming():
    from aerophoto.demos.displacement import ReliefDemo
    from aerophoto.widgets import TABLE_DELAY_S

    async def drive():
        demo = ReliefDemo()
        start = demo.table.value
        ctl = demo.controls()["relief_m"]
        changed_during = False
        for relief in (85.0, 90.0, 95.0, 100.0, 105.0, 110.0, 115.0, 120.0):
            ctl.value = relief
            await asyncio.sleep(TABLE_DELAY_S / 2)
            changed_during |= demo.table.value != start
        demo.close()
        return changed_during

    assert asyncio.run(drive()), "the table stayed on the first state during a stream of moves"


def test_the_transformers_step_is_drawn_in_full_at_once():
    from aerophoto.demos.rectification import TransformerDemo

    async def drive():
        demo = TransformerDemo()
        demo.controls()["step"].value = 3
        out = (demo.result.preview, demo._later is None, "aerophoto-pending" not in demo.status.value, demo.result.step)
        demo.controls()["alpha_deg"].value = 4.0  # a photo slider: a preview now, the full picture later
        out += (demo.result.preview,)
        demo.close()
        return out

    assert asyncio.run(drive()) == (False, True, True, 3, True)


def test_the_status_line_keeps_its_height():
    from aerophoto.demos.footprint import FootprintDemo

    demo = FootprintDemo()
    try:
        assert demo.status.layout.min_height == "26px"
    finally:
        demo.close()

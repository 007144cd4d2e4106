"""Graded tasks of chapter 08 (guide §9): interpreting the student's own colour photo of the interpretation site.

Each variant photographs :mod:`aerophoto.site.cover`'s site with its own crop and conditions (:func:`aerophoto.labs.ch08.lab_setup`,
seeded by the variant number i): a frame camera f = 100 mm, 18×18 cm, at a scale 1:m between 1:8 000 and
1:9 500, the photo's x axis turned by κ = 0°, 90°, 180° or 270° from east, a small tilt (α ≤ 1.5°), a summer day
with the sun 35–60° high in the south-east to south-west, visibility 20–50 km, a little motion blur.

The student gets :class:`aerophoto.labs.ch08.LabPhoto` (``tasks.inputs("task-08-1", v)``): the photo itself (six bands, shown as
natural colour and colour infrared), the photo coordinates of the numbered marks as read on it, the scale, and the
names to choose from — what the photo shows, never what is there: no class map, no site.  The truth is the site's
(:func:`aerophoto.labs.ch08.truth`: the land cover under each mark, the river's flow, the stands, the river's width).

* 08.1 (:class:`NameObjects`): name the six numbered objects, one of :data:`OBJECT_NAMES` each; graded in
  proportion (one check per object).
* 08.2 (:class:`FlowAndForest`): the river's flow direction on the photo (one of :data:`FLOW_OPTIONS`) and which
  of the stands P and Q is spruce.
* 08.3 (:class:`RiverWidth`): the river's width at the section A–B by the photo's scale, m (tolerance 5 %: the
  scale varies over a tilted photo of relief by up to 4 % here).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..labs.ch08 import FLOW_OPTIONS, N_OBJECTS, OBJECT_NAMES, STAND_OPTIONS, LabPhoto, lab_photo, setup_for, truth
from .base import Answer, Method, Task

__all__ = ["WIDTH_TOL_REL", "NameObjects", "FlowAndForest", "RiverWidth", "TASKS"]

#: the river's width is graded to 5 % (the scale varies over a tilted photo of relief by up to 4 % here)
WIDTH_TOL_REL = 0.05
# =========================================================================== the tasks
def _obj(k: int) -> Answer:
    return Answer(f"obj{k}", f"name of object {k}: one of OBJECT_NAMES", kind="choice", options=OBJECT_NAMES,
                  hint="compare its tone, texture, shape and surroundings with table 10's keys.")


@dataclass(frozen=True)
class NameObjects(Task):
    id = "task-08-1"
    title = "Name the numbered objects on your photo"
    points = 3
    partial = True
    cross_variant = False
    spec = tuple(_obj(k) for k in range(1, N_OBJECTS + 1))
    tools = ("aerophoto.labs.ch08.OBJECT_NAMES",)
    methods = (Method("tone, texture, shape, size and surroundings against table 10's direct and indirect keys",
                      "guide §9, table 10"),)

    def inputs(self, v) -> LabPhoto:
        return lab_photo(v)

    def answers(self, v) -> dict:
        objs = truth(int(v.i))["objects"]
        return {f"obj{k + 1}": name for k, (name, _, _) in enumerate(objs)}


@dataclass(frozen=True)
class FlowAndForest(Task):
    id = "task-08-2"
    title = "The river's flow and the spruce stand"
    points = 2
    partial = True
    cross_variant = False
    spec = (
        Answer("flow", "the river's flow direction on your photo: one of FLOW_OPTIONS", kind="choice",
               options=FLOW_OPTIONS, hint="look at the islands' ends and at how the tributary meets the river."),
        Answer("spruce", "which stand is spruce: 'P' or 'Q'", kind="choice", options=STAND_OPTIONS,
               hint="compare the stands' tone, its evenness, and the crowns' shape and shadows."),
    )
    tools = ("aerophoto.labs.ch08.FLOW_OPTIONS",)
    methods = (Method("the islands' ends and the tributary's angle for the flow; tone and crowns for spruce",
                      "guide §9, table 10"),)

    def inputs(self, v) -> LabPhoto:
        return lab_photo(v)

    def answers(self, v) -> dict:
        t = truth(int(v.i))
        return {"flow": t["flow"], "spruce": t["spruce"]}


#: slip hint of task 08.3: the variant's flight scale (setup's banner) instead of this photo's own scale
BANNER_SCALE = ("that is the scale of your variant's flight (the 1:m of the banner); this photo has its own scale, "
                "lab.m, printed with the photo — use that one")


@dataclass(frozen=True)
class RiverWidth(Task):
    id = "task-08-3"
    title = "The river's width by the photo's scale"
    points = 1
    cross_variant = False
    spec = (Answer("width_m", "the river's width at A–B on the ground, m", unit="m", tol_rel=WIDTH_TOL_REL, printed=0.1),)
    methods = (Method("|AB| on the photo times this photo's own m", "guide §9; chapter 08, task 08.3"),)

    def inputs(self, v) -> LabPhoto:
        return lab_photo(v)

    def answers(self, v) -> dict:
        return {"width_m": truth(int(v.i))["width_m"]}

    def slips(self, v) -> dict:
        su = setup_for(int(v.i))
        w = truth(int(v.i))["width_m"]
        vm = float(v.m)
        return {"width_m": {"the photo distance is in mm: multiply by m and divide by 1000 for metres": w * 1000.0,
                            "use the photo's scale 1:m — the ground distance is the photo distance times m": w / su.m,
                            BANNER_SCALE: (w * vm / su.m) if abs(vm / su.m - 1.0) > 2 * WIDTH_TOL_REL else None}}


TASKS = (NameObjects(), FlowAndForest(), RiverWidth())

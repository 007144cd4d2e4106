"""Which chapters have live demos, and which sliders the browser tests move.

To add a chapter: append a :class:`Chapter` with the notebook's file name and,
for each demo cell (id ``demo-…``), its headline sliders — the exact slider
labels (``"f, mm"``, ``"α, °"``) with the key that moves them by a visible
amount (``ArrowRight``/``ArrowLeft`` = one step, ``PageUp``/``PageDown`` =
five steps).  Pick a key that moves away from the demo's default without
leaving the slider's range.  ``tests/browser/test_registry.py`` fails while a
notebook with a ``demo-`` cell is missing here or from the lecture index.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Demo:
    cell: str  #: id of the notebook cell that displays the demo
    sliders: tuple  #: ((label, key), ...): the headline sliders and the key that moves each
    nth: int = 0  #: in Voilà (no cell ids): which of the demos carrying these sliders
    timed: str = ""  #: the slider benchmarks/bench_browser.py times (default: the first headline slider)
    cls: str = ""  #: the LiveDemo class (module.Class) — the benchmark's naive re-implementation rebuilds it

    @property
    def timed_slider(self) -> str:
        return self.timed or self.sliders[0][0]


@dataclass(frozen=True)
class Chapter:
    notebook: str  #: file name in notebooks/
    demos: tuple  #: the chapter's live demos

    @property
    def name(self) -> str:
        return self.notebook.removesuffix(".ipynb")


F = ("f, mm", "PageUp")  # focal length: five steps up from the chapter's start
M = ("m (scale 1:m)", "PageUp")  # scale denominator: five steps up

CHAPTERS = (
    Chapter("00_start_here.ipynb", (
        Demo("demo-footprint", (F, M, ("α, °", "ArrowRight")), timed="α, °",
             cls="aerophoto.demos.footprint.FootprintDemo"),
    )),
    Chapter("01_flight_planning.ipynb", (
        Demo("demo-flight-plan", (F, M, ("px, %", "ArrowRight")), timed="f, mm",
             cls="aerophoto.demos.flight_plan.FlightPlanDemo"),
    )),
    Chapter("02_photo_quality.ipynb", (
        Demo("demo-quality", (F, ("α max, °", "ArrowRight"), ("crab φ, °", "ArrowRight")),
             timed="α max, °", cls="aerophoto.demos.quality.QualityDemo"),
    )),
    Chapter("03_relief_displacement.ipynb", (
        Demo("demo-relief", (F, M, ("α, °", "ArrowRight"), ("relief ±h, m", "ArrowRight")),
             timed="relief ±h, m", cls="aerophoto.demos.displacement.ReliefDemo"),
    )),
    Chapter("04_tilt_displacement.ipynb", (
        # m is no headline here: over flat ground the tilt displacement on the photo does not depend on m
        Demo("demo-tilt", (F, ("α, °", "ArrowRight"), ("λ, °", "ArrowRight")), timed="α, °",
             cls="aerophoto.demos.displacement.TiltDemo"),
    )),
    Chapter("05_fotoschema.ipynb", (
        Demo("demo-fotoschema", (F, M, ("α max, °", "ArrowRight")), timed="α max, °",
             cls="aerophoto.demos.fotoschema.FotoschemaDemo"),
    )),
    Chapter("06_strip_triangulation.ipynb", (
        Demo("demo-reduction", (F, ("m (photo 1:m)", "PageUp"), ("α max, °", "ArrowRight")), timed="α max, °",
             cls="aerophoto.demos.reduction.ReductionDemo"),
    )),
    Chapter("12_phototriangulation.ipynb", (
        Demo("demo-reduction", (F, ("m (photo 1:m)", "PageUp"), ("α max, °", "ArrowRight")), timed="α max, °",
             cls="aerophoto.demos.reduction.ReductionDemo"),
    )),
)

#: the notebook that lists the demos for lecturers
LECTURE_INDEX = "lectures.ipynb"

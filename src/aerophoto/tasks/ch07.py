"""Graded tasks of chapter 07 (guide §8): the student's own stereo pair — its base, and heights from parallaxes.

Each variant flies its own pair over the virtual site (:func:`aerophoto.labs.ch07.stereo_lab`):
two photos with the variant's camera f and scale 1:m, p_x = 60 %, centred on
the site, with the small departures of a real flight seeded by i (tilts up to
0.7°, crab jitter ±1°, base jitter ±2 %; both stations at one height).  The
student works from what a photogrammetrist measures on such a pair:

* the principal points transferred to the neighbour photo (pricked by eye,
  σ = 0.02 mm, read to 0.01 mm) — the photo base;
* on the pair normalised along its base (the parallax bar's setting), the
  coordinates of a control point A of known height and of four objects of the
  site — a roof corner, a tree top, the chimney top, the mast top — with a
  ground point beside each (read to 0.01 mm, σ = 0.007 mm a coordinate);
* the air base B of the navigation record (to 0.1 m).

The truth comes from geometry (the objects' points projected through the
true orientations), never from image analysis.  Tasks:

* 07.1 (:class:`PairBase`): the photo base b, the parallax of A and the
  height of the projection centres from A;
* 07.2 (:class:`ObjectHeights`): the parallax differences and the heights of
  the four objects, Δh = H·Δp/(p + Δp) with H = B·f/p over each object's foot;
* 07.3 (:class:`ParallaxForHeight`): the parallax difference the site's
  relief makes on the pair, and the stereo model's vertical exaggeration.

:func:`aerophoto.labs.ch07.example_lab` is the guide's example (variant 00's camera and scale,
its own seed) that the chapter's live demo opens on.
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import stereo as st
from ..labs.ch07 import OBJECT_LABELS, PX_PERCENT, stereo_lab
from .base import Answer, Method, Task, Withheld
from .rounding import allowance, consistency, either, numbers, source

__all__ = ["EYE_BASE_MM", "VIEWING_MM", "PRICKED_BASE", "SMALL_FORM", "NOMINAL_H", "PAIR_WITHHELD", "pair_inputs",
           "PairBase", "ObjectHeights",
           "ParallaxForHeight", "TASKS"]

#: slip hint of task 07.3: the base of the pricked principal points (task 07.1) instead of b₀ = B·f/H
PRICKED_BASE = ("that uses b from the pricked principal points, which the photos' tilts shift by 1–3 %; the parallaxes "
                "of the normalised pair go with its base b₀ = B·f/H (chapter 07)")
#: slip hint of task 07.3: the small form b·h/H where it differs from the exact form by more than the tolerance
SMALL_FORM = "that is the small form b₀·h/H; with your H the exact b₀·h/(H − h) differs by more than the tolerance"
#: slip hint of task 07.1: the nominal flying height f·m instead of the height from A's own parallax
NOMINAL_H = ("that uses the nominal flying height H = f·m; the stations' height comes from A's own parallax: "
             "Z_S = Z_A + B·f/p_A")
NOMINAL_H_ALONE = "that is the nominal flying height f·m itself; the stations' height is Z_S = Z_A + B·f/p_A"
#: the viewing the vertical exaggeration of task 07.3 refers to: eye base and viewing distance, mm
EYE_BASE_MM, VIEWING_MM = st.EYE_BASE_MM, st.VIEWING_DISTANCE_MM
#: what the pair knows that tasks 07.1–07.2 ask for
PAIR_WITHHELD = ("b_mm", "pA_mm", "ZS_from_A_m", "photo_bases_mm", "parallaxes", "truth")


def pair_inputs(v) -> Withheld:
    """The student's stereo pair as tasks 07.1–07.2 give it: the tables to read, not their results."""
    return Withheld(stereo_lab(v), PAIR_WITHHELD, why="it is what tasks 07.1–07.2 ask you to compute")


# =========================================================================== task 07.1
@dataclass(frozen=True)
class PairBase(Task):
    """Task 07.1: the photo base b, the parallax of the control point A and the height of the stations from it."""

    id = "task-07-1"
    title = "The base of your pair and the height of its stations"
    points = 3
    spec = (
        Answer("b_mm", "photo base b, the mean of b₁ and b₂, mm", unit="mm", tol_abs=0.02, printed=0.01),
        Answer("pA_mm", "x-parallax of A, mm", unit="mm", tol_abs=0.005, printed=0.01),
        Answer("ZS_m", "height of the projection centres from A, m", unit="m", tol_abs=0.5, printed=0.1),
    )

    def inputs(self, v) -> Withheld:
        return pair_inputs(v)

    def answers(self, v) -> dict:
        lab = stereo_lab(v)
        return {"b_mm": lab.b_mm, "pA_mm": lab.pA_mm, "ZS_m": lab.ZS_from_A_m}

    def slips(self, v) -> dict:
        lab = stereo_lab(v)
        b1, b2 = lab.photo_bases_mm()
        c = lab.control
        H_A = lab.B_record_m * lab.f_mm / lab.pA_mm
        planned = lab.camera.frame_mm * (1.0 - PX_PERCENT / 100.0)
        fm = lab.f_mm / 1000.0 * float(v.m)
        return {
            "b_mm": {"that is the planned base l·(100 − p_x)/100 of §2 — measure b on your photos": planned,
                     "the photo base is the mean of both photos' bases, b = (b₁ + b₂)/2": b1 if abs(b1 - b2) > 0.04
                     else None,
                     "only the x-coordinates: b is the whole distance from o to the transferred point":
                     (abs(lab.principal.iloc[0, 0]) + abs(lab.principal.iloc[1, 0])) / 2.0},
            "pA_mm": {"the sign: the x-parallax is p = x_left − x_right": float(c["x right"] - c["x left"])},
            "ZS_m": {"that is the flying height over A, B·f/p; add A's own height Z_A": H_A,
                     "use A's own parallax p_A in B·f/p, not the photo base b":
                     float(c["Z, m"]) + lab.B_record_m * lab.f_mm / lab.b_mm,
                     NOMINAL_H: float(c["Z, m"]) + fm, NOMINAL_H_ALONE: fm},
        }

    tools = ("aerophoto.labs.ch07.lab_images",)
    methods = (Method("b = (b₁ + b₂)/2 from the pricked principal points, p_A = x_left − x_right, "
                      "Z_S = Z_A + B·f/p_A", "guide §8; chapter 07, the pair's tables"),)

    def hidden(self, v, got) -> list:
        # the stations' height must follow from the student's own parallax of A
        lab = stereo_lab(v)
        Z_A, Bf = float(lab.control["Z, m"]), lab.B_record_m * lab.f_mm
        return [consistency("ZS_m from your own pA_mm", got.get("ZS_m"), 0.1, lambda p: Z_A + Bf / p,
                            [source(self, got, "pA_mm")], target_cap=self.answer("ZS_m").tol_abs)]


# =========================================================================== task 07.2
def _dh_labels():
    return tuple(f"dh{c}_m" for c in "ABCD")


@dataclass(frozen=True)
class ObjectHeights(Task):
    """Task 07.2: the parallax differences of four objects and their heights Δh = H·Δp/(p + Δp), H = B·f/p."""

    id = "task-07-2"
    title = "Heights of four objects from their parallaxes"
    points = 5
    spec = (
        Answer("dp_mm", "parallax differences Δp = p_top − p_foot of A, B, C, D, mm", unit="mm", kind="values",
               tol_abs=0.005, labels=OBJECT_LABELS, printed=0.01),
        Answer("dhA_m", "height of the roof corner A over its foot, m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("dhB_m", "height of the tree top B, m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("dhC_m", "height of the chimney top C, m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("dhD_m", "height of the mast top D, m", unit="m", tol_abs=0.05, printed=0.01),
    )

    def inputs(self, v) -> Withheld:
        return pair_inputs(v)

    def answers(self, v) -> dict:
        t = stereo_lab(v).parallaxes()
        out = {"dp_mm": [float(x) for x in t["Δp, mm"]]}
        for name, val in zip(_dh_labels(), t["Δh, m"]):
            out[name] = float(val)
        return out

    def slips(self, v) -> dict:
        lab = stereo_lab(v)
        t = lab.parallaxes()
        out = {}
        for name, (_, r) in zip(_dh_labels(), t.iterrows()):
            dp, pf, Hf = r["Δp, mm"], r["p foot, mm"], r["H over the foot, m"]
            exact = r["Δh, m"]
            cands = {
                "base mix-up: with the mean photo base b and H = f·m the formula is only approximate — use the "
                "foot's own parallax p and H = B·f/p": lab.H_m * dp / (lab.b_mm + dp),
                "that is the small-Δp form H·Δp/p; the exact formula has p + Δp in the denominator": Hf * dp / pf,
                "H must be the flying height over the foot, B·f/p_foot — not Z_S or f·m": lab.Z_S_m * dp / (pf + dp),
                "the air base B is in metres on the ground; Δp and p are on the photo — B does not go in the "
                "denominator": Hf * dp / (lab.B_record_m + dp),
            }
            out[name] = {h: (float(x) if abs(x - exact) > 0.06 else None) for h, x in cands.items()}
        return out

    methods = (Method("Δp = p_top − p_foot, H = B·f/p_foot, Δh = H·Δp/(p_foot + Δp)", "guide §8; chapter 07"),)

    def hidden(self, v, got) -> list:
        # each height must follow from the student's own Δp with the foot's measured parallax
        t = stereo_lab(v).parallaxes()
        dps = numbers(got.get("dp_mm"), len(t))
        out = []
        for k, (name, (_, r)) in enumerate(zip(_dh_labels(), t.iterrows())):
            H, p = float(r["H over the foot, m"]), float(r["p foot, mm"])
            dp = None if dps is None else float(dps[k])
            out.append(consistency(f"{name} from your own Δp", got.get(name), 0.01, lambda x: H * x / (p + x),
                                   [(dp, 0.01)]))
        return out


# =========================================================================== task 07.3
@dataclass(frozen=True)
class ParallaxForHeight(Task):
    """Task 07.3: the parallax difference of the site's relief on the pair, and the model's vertical exaggeration."""

    id = "task-07-3"
    title = "What a height does to your parallaxes, and how tall the model looks"
    points = 2
    spec = (
        Answer("dp_relief_mm", "parallax difference of the relief h = Z_max − Z_min, mm", unit="mm", tol_abs=0.005,
               printed=0.0001),
        Answer("V", "vertical exaggeration of the stereo model", tol_rel=0.005, printed=0.001),
    )

    def inputs(self, v) -> dict:
        lab = stereo_lab(v)
        return {"h_m": v.Zmax_m - v.Zmin_m, "H_m": lab.H_m, "B_m": lab.B_record_m, "f_mm": lab.f_mm,
                "eye_base_mm": EYE_BASE_MM, "viewing_distance_mm": VIEWING_MM}

    def _ref(self, v):
        # the unbiased base of the normalised pair, b₀ = B·f/H (chapter 07: the pricked principal points carry the
        # tilts' displacements and are 1–3 % off it)
        lab = stereo_lab(v)
        h = v.Zmax_m - v.Zmin_m
        return lab, h, float(st.parallax_difference_mm(h, lab.b_flat_mm, lab.H_m))

    def answers(self, v) -> dict:
        lab, h, dp = self._ref(v)
        V = float(st.vertical_exaggeration(lab.b_flat_mm, lab.f_mm, EYE_BASE_MM, VIEWING_MM))  # B/H = b₀/f
        return {"dp_relief_mm": dp, "V": V}

    def _small_form(self, v):
        """(the small form b₀·h/H, whether it is accepted): accepted where it lies within the tolerance of the
        exact form even when written to its printed unit; a slip elsewhere (every variant is one or the other)."""
        lab, h, dp = self._ref(v)
        small = float(st.parallax_difference_mm(h, lab.b_flat_mm, lab.H_m, approx=True))
        a = self.spec[0]
        return small, abs(small - dp) + allowance(dp, a.printed) <= a.tol_abs

    def slips(self, v) -> dict:
        lab, h, dp = self._ref(v)
        b0 = lab.b_flat_mm
        small, small_ok = self._small_form(v)
        BH = b0 / lab.f_mm
        pricked_dp = float(st.parallax_difference_mm(h, lab.b_mm, lab.H_m))
        pricked_V = float(st.vertical_exaggeration(lab.b_mm, lab.f_mm, EYE_BASE_MM, VIEWING_MM))
        V = float(st.vertical_exaggeration(b0, lab.f_mm, EYE_BASE_MM, VIEWING_MM))
        return {
            "dp_relief_mm": {SMALL_FORM: None if small_ok else small,
                             "the relief's parallax difference uses the photo base b in mm, not B in m":
                             lab.B_record_m * h / (lab.H_m - h),
                             PRICKED_BASE: pricked_dp if abs(pricked_dp - dp) > 0.005 else None},
            "V": {"V is (B/H) divided by (e/d), not the other way round": (EYE_BASE_MM / VIEWING_MM) / BH,
                  "B/H is b/f with both in mm": (b0 / (lab.f_mm / 1000.0)) / (EYE_BASE_MM / VIEWING_MM),
                  PRICKED_BASE: pricked_V if abs(pricked_V / V - 1) > 0.005 else None},
        }

    def quantities(self, v) -> dict:
        lab, h, _ = self._ref(v)
        return {"the base b₀ = B·f/H of your pair, mm": lab.b_flat_mm, "B/H = b₀/f (not yet divided by e/d)":
                lab.b_flat_mm / lab.f_mm, "the relief h = Z_max − Z_min, m": h}

    methods = (Method("Δp = b₀·h/(H − h) with b₀ = B·f/H; V = (b₀/f)/(e/d)", "guide §8; chapter 07, task 07.3"),
               Method("the small form Δp = b₀·h/H, where H is high enough for it to agree with the exact form "
                      "within the tolerance", "chapter 07 teaches it as the limit h ≪ H; elsewhere it is a slip",
                      submit=lambda task, v: ({"dp_relief_mm": task._small_form(v)[0]} if task._small_form(v)[1]
                                              else {})))

    def hidden(self, v, got) -> list:
        # both answers come from one photo base: Δp/V = f·h·e/(d·(H − h)) does not depend on b (for the small
        # form, where it is accepted, f·h·e/(d·H))
        lab, h, _ = self._ref(v)
        k = lab.f_mm * h * EYE_BASE_MM / VIEWING_MM
        V = numbers(got.get("V"))
        exact = consistency("dp_relief_mm and V from one base", got.get("dp_relief_mm"), 0.0001,
                            lambda x: x * k / (lab.H_m - h), [(V, 0.001)])
        if not self._small_form(v)[1]:
            return [exact]
        small = consistency("dp_relief_mm and V from one base", got.get("dp_relief_mm"), 0.0001,
                            lambda x: x * k / lab.H_m, [(V, 0.001)])
        return [either(exact, small)]


TASKS = (PairBase(), ObjectHeights(), ParallaxForHeight())

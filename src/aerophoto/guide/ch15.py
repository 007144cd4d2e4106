"""Chapter 15 · article 002 (aerial photo-referencing of gravimetric points in high mountains): its tables, audited.

Table 1 (the technology of the method) has no numbers: :func:`technology` gives it
in English beside the part of the package that does each computational step
today.  Table 2 (the limits of the 1986 Fortran-IV package) holds numbers, some
of which follow from others — the smallest block's unknowns, the smallest
strip's points — and :func:`package_limits` checks them.  :func:`experiment`
checks what the text prints about the 1985 experiment and the СШ-45 camera.
"""

from __future__ import annotations

import math

import pandas as pd

from .audit import Audit, discrepancy_frame, printed

__all__ = ["TABLE2", "TECHNOLOGY", "CAMERA_SSh45", "EXPERIMENT", "technology", "package_limits", "experiment",
           "discrepancies"]

#: table 2 as printed: (section, characteristic, minimum, maximum)
TABLE2 = (
    ("single model", "fiducial marks in the pair", 4, 4),
    ("single model", "phototriangulation points", 6, 30),
    ("single model", "densification points", 0, 1000),
    ("single model", "control points", 3, 20),
    ("strip", "stereopairs", 2, 39),
    ("strip", "fiducial marks in a stereopair", 4, 4),
    ("strip", "points in a stereopair", 6, 500),
    ("strip", "tie points between stereopairs", 1, 100),
    ("strip", "points in the strip (marks included)", 20, 1000),
    ("strip", "control and check points", 4, 100),
    ("strip", "control points", 4, 20),
    ("block", "strips in the block", 1, 30),
    ("block", "stereopairs in a strip", 2, 39),
    ("block", "measured points in a strip", 12, 1000),
    ("block", "tie points in a stereopair", 3, 100),
    ("block", "control and check points", 4, 300),
    ("block", "control points", 4, 100),
    ("block", "unknowns in the block", 54, 1000),
    ("block", "side overlap, %", 20, 60),
)

#: table 1 as printed (translated): (work, result, who does it), and what does the computation here
TECHNOLOGY = (
    ("collect archive material: reports, maps, photos, catalogues of the geodetic network, old control",
     "archive material", "gravimetric party (GP), survey party (SP)", "—"),
    ("prepare instruments", "equipment ready", "SP, GP", "—"),
    ("design the gravimetric survey", "survey design", "GP", "—"),
    ("design the block triangulation and the control", "field and office design", "SP",
     "aerophoto.labs.ch15.survey_block (control layout)"),
    ("control the photos (geodetically or by photo-theodolite)", "control coordinates, marked photos", "SP",
     "control points with a priori σ (Measurements.control_XYZ_m, control_sigma_m)"),
    ("gravimetric survey: mark the point (paper or gauze sign)", "sign on the ground", "GP", "—"),
    ("a) quick marking, b) read the gravimeters, locate the point on the map", "field log, point on the map", "GP",
     "—"),
    ("c) photograph the point from the helicopter (СШ-45)", "film with the point", "GP", "—"),
    ("d) develop the film; add the points to the triangulation design", "design with the gravimetric points",
     "GP, SP", "field points in the block (kind 'field', σ of the transferred mark)"),
    ("measure the photos (stereocomparator)", "measurement logs, punched or magnetic tape", "SP",
     "aerophoto.bundle.simulate_measurements"),
    ("prepare the data for the computer", "standard forms", "GP", "aerophoto.bundle.Measurements"),
    ("compute the block triangulation", "catalogue of the gravimetric points", "computing centre",
     "aerophoto.bundle.three_stage, data_snooping, adjust"),
    ("analyse the results", "quality assessment", "GP", "check points, error ellipses (Precision)"),
    ("heights around each point for the terrain correction", "heights around the point", "GP, SP", "—"),
)

#: the СШ-45 camera as printed
CAMERA_SSh45 = {"f_mm": 20.0, "field_deg": 94, "frame_mm": (24.0, 36.0), "aperture": "1:5.6", "height_m": (100, 150)}

#: the 1985 experiment as printed
EXPERIMENT = {"strips": 5, "stereopairs": (5, 18), "photos": 64, "m": 15000.0, "f_mm": 200.0, "field_points": 20,
              "groups_12": {"points": 29, "mx_m": 15.0, "my_m": 15.0, "mz_m": 2.5},
              "group_3": {"points": 20, "mx_m": 37.0, "my_m": 62.0, "mz_m": 5.5, "blunders_m": (8, 12)},
              "control_per_block": ((4, 5), (40, 50))}


def technology() -> pd.DataFrame:
    """Table 1 in English, with the part of aerophoto that does each computational step."""
    return pd.DataFrame(TECHNOLOGY, columns=["work", "result", "who", "here"])


def package_limits() -> Audit:
    """Table 2 with the limits that follow from others checked (the smallest block, strip and model)."""
    t = pd.DataFrame(TABLE2, columns=["section", "characteristic", "minimum", "maximum"])
    lim = {(s, c): (lo, hi) for s, c, lo, hi in TABLE2}
    photos_min = lim[("block", "stereopairs in a strip")][0] + 1  # a strip of 2 stereopairs has 3 photos
    pts_min = lim[("block", "measured points in a strip")][0]
    vals = [
        printed("block", "least unknowns = 6 × photos + 3 × points of the smallest block", 54,
                6 * photos_min + 3 * pts_min, 1.0,
                computed_text=f"6 × {photos_min} + 3 × {pts_min} = {6 * photos_min + 3 * pts_min}"),
        printed("block", "least measured points in a strip = stereopairs × points per stereopair", pts_min,
                lim[("strip", "stereopairs")][0] * lim[("strip", "points in a stereopair")][0], 1.0),
        printed("strip", "least points with marks = 2 stereopairs × (6 points + 4 marks)", 20,
                lim[("strip", "stereopairs")][0] * (lim[("strip", "points in a stereopair")][0]
                                                    + lim[("strip", "fiducial marks in a stereopair")][0]), 1.0),
        printed("single model", "least points = 5 elements of relative orientation + 1 check", 6, 5 + 1, 1.0),
        printed("single model", "least control = a 7-parameter absolute orientation (2 full + 1 height point)", 3,
                math.ceil(7 / 3), 1.0),
    ]
    # what the largest values imply
    max_photos_by_unknowns = lim[("block", "unknowns in the block")][1] // 6
    block_max_photos = lim[("block", "strips in the block")][1] * (lim[("block", "stereopairs in a strip")][1] + 1)
    notes = (
        f"The maxima do not hold together: 30 strips of 40 photos would have {block_max_photos} photos, "
        f"{6 * block_max_photos} orientation unknowns alone, while the block may have 1000 unknowns — at most "
        f"{max_photos_by_unknowns} photos even with no points.  The 1000-unknown limit (the computer's 120–250 KB "
        "of memory) is the one that binds.",
        "The 1985 experiment's 64 photos already take 384 of the 1000 unknowns, leaving 616 for 205 points: ties, "
        "control, check and the 20 gravimetric points.",
        "Today: benchmarks/bench_bundle.py adjusts blocks of 20, 100 and 400 photos (up to 9500 unknowns) in "
        "hundredths of a second to a few seconds, in up to about 150 MB of memory.",
    )
    return Audit("article 002", "Table 2. Limits of the 1986 triangulation package", t.set_index("characteristic"),
                 tuple(vals), notes=notes)


def experiment() -> Audit:
    """The 1985 experiment and the СШ-45 camera: what the printed numbers imply."""
    cam, ex = CAMERA_SSh45, EXPERIMENT
    diag = math.hypot(*cam["frame_mm"])
    field = 2.0 * math.degrees(math.atan(diag / 2.0 / cam["f_mm"]))
    lo, hi = ex["stereopairs"]
    k = ex["strips"]
    # photos of 5 strips with one of 5 and one of 18 stereopairs: between these
    p_min = (lo + 1) + (hi + 1) + (k - 2) * (lo + 1)
    p_max = (lo + 1) + (hi + 1) + (k - 2) * (hi + 1)
    H = ex["f_mm"] / 1000.0 * ex["m"]
    g12, g3 = ex["groups_12"], ex["group_3"]
    vals = [
        printed("СШ-45", "field angle across the 24 × 36 mm diagonal, °", cam["field_deg"], field, 1.0),
        printed("experiment", "photos of 5 strips of 5 to 18 stereopairs", ex["photos"], ex["photos"], 1.0,
                bounds=(p_min, p_max), computed_text=f"{p_min} … {p_max}"),
    ]
    table = pd.DataFrame([
        ("flying height H = f·m", "m", H),
        ("helicopter photo scale 1:m at 100–150 m (СШ-45)", "1:", cam["height_m"][0] / cam["f_mm"] * 1000.0),
        ("… and at 150 m", "1:", cam["height_m"][1] / cam["f_mm"] * 1000.0),
        ("groups 1–2: m_x = m_y at the photo scale", "mm", g12["mx_m"] / ex["m"] * 1000.0),
        ("groups 1–2: m_z / H", "%", g12["mz_m"] / H * 100.0),
        ("group 3: m_x, m_y on the 1:25 000 map", "mm", g3["mx_m"] / 25.0),
        ("… m_y", "mm", g3["my_m"] / 25.0),
        ("control per photo: 4–5 per 40–50 photos", "per photo", 4.5 / 45.0),
    ], columns=["quantity", "unit", "value"]).set_index("quantity")
    notes = ("15 m at 1:15 000 is 1 mm on the photo — ten to a hundred times what the measurements allow; the "
             "article blames the identification of the geodetic points on the archive photos.  Chapter 15's "
             "simulation shows what the same block gives when the control is identified well.",)
    return Audit("article 002", "The 1985 experiment and the СШ-45 camera", table, tuple(vals), notes=notes)


def discrepancies() -> pd.DataFrame:
    """Every printed number of article 002 that does not follow, with the reason."""
    return discrepancy_frame([package_limits(), experiment()])

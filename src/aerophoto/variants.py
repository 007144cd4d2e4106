"""The student's variant (guide §1, "Задание на курсовую работу").

Each student works on the variant i = the last two digits of their record-book
number (номер зачётной книжки).  From i the guide derives every input of the
course design:

=====================  ===============================  ======================
quantity               guide §1                         attribute
=====================  ===============================  ======================
aircraft speed         W = 200 + 10·i  km/h             ``W_kmh``
focal length           f = 100 + 10·i  mm               ``f_mm``
photo scale            1/m = 1/(12000 + 100·i)          ``m``
photoplan scale        1/M = 1/10000                    ``M``
frame                  18×18 cm                         ``frame_mm`` = 180
forward overlap        p_x = 60 %                       ``px_percent``
side overlap           p_y = 30 %                       ``py_percent``
area along parallel    L_x = 25 + i  km                 ``Lx_km``
area along meridian    L_y = 30 + i  km                 ``Ly_km``
highest ground         Z_max = 200 + i  m               ``Zmax_m``
lowest ground          Z_min = 170 + i  m               ``Zmin_m``
tilt                   α = 3°                           ``alpha_deg``
swing                  λ = −60° + i                     ``lambda_deg``
=====================  ===============================  ======================

The scan prints the scale as "1/m = 1/12000 + 100i"; the guide's own worked
example (i = 0, m = 12000, §2) and the step of 100 per variant show the intended
reading 1/m = 1/(12000 + 100·i).
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass

import pandas as pd

from ._validate import check_int_range, check_type
from .geometry import Camera, flying_height_m

__all__ = ["Variant", "variant", "variant_for_index", "index_from_record_book", "as_variant"]


@dataclass(frozen=True)
class Variant:
    """All inputs of one student's course design (guide §1).  Units are in the names."""

    record_book: str
    i: int
    W_kmh: float
    f_mm: float
    m: float
    M: float
    frame_mm: float
    px_percent: float
    py_percent: float
    Lx_km: float
    Ly_km: float
    Zmax_m: float
    Zmin_m: float
    alpha_deg: float
    lambda_deg: float

    @property
    def camera(self) -> Camera:
        """The variant's camera: f and the 18×18 cm frame."""
        return Camera(self.f_mm, self.frame_mm)

    @property
    def H_m(self) -> float:
        """Flying height H = f·m in metres (guide §2, step 2)."""
        return flying_height_m(self.f_mm, self.m)

    @property
    def relief_m(self) -> float:
        """Relief h = Z_max − Z_min in metres (guide §2, step 3)."""
        return self.Zmax_m - self.Zmin_m

    def as_dict(self) -> dict:
        return asdict(self)

    def table(self) -> pd.DataFrame:
        """The variant as a two-column table laid out like the guide's §1 list."""
        rows = [
            ("Record-book number (номер зачётной книжки)", "", self.record_book),
            ("Variant i", "", self.i),
            ("Aircraft speed W", "km/h", self.W_kmh),
            ("Frame size", "cm", f"{self.frame_mm / 10:g}×{self.frame_mm / 10:g}"),
            ("Focal length f", "mm", self.f_mm),
            ("Photo scale 1/m", "1:", self.m),
            ("Photoplan scale 1/M", "1:", self.M),
            ("Forward overlap p_x", "%", self.px_percent),
            ("Side overlap p_y", "%", self.py_percent),
            ("Area size L_x (along the parallel)", "km", self.Lx_km),
            ("Area size L_y (along the meridian)", "km", self.Ly_km),
            ("Highest ground Z_max", "m", self.Zmax_m),
            ("Lowest ground Z_min", "m", self.Zmin_m),
            ("Tilt α", "°", self.alpha_deg),
            ("Swing λ", "°", self.lambda_deg),
        ]
        # object dtype: a count stays whole beside the lengths; the mark has a notebook show the table in the book's
        # number format (aerophoto.plots.register_table_display: 1:12 000, 1200, decimal comma in Russian)
        df = pd.DataFrame(rows, columns=["quantity", "unit", "value"], dtype=object).set_index("quantity")
        df.attrs["aerophoto"] = {"caption": "The variant (guide §1)",
                                 "precision": {"Area size L_x (along the parallel)": "{:.4g}",
                                               "Area size L_y (along the meridian)": "{:.4g}"}}
        return df


def index_from_record_book(record_book) -> int:
    """The variant index i: the last two digits of the record-book number (guide §1).

    Accepts a string such as ``"ЗиК-19-0457"`` or an integer; non-digits are
    ignored.  Raises ValueError if fewer than two digits are given.
    """
    if record_book is None:
        raise ValueError("record_book = None: type your record-book number, e.g. '19-0457' (at least two digits)")
    digits = re.sub(r"\D", "", str(record_book))
    if len(digits) < 2:
        raise ValueError(
            f"record_book = {record_book!r} has {len(digits)} digit(s); the valid form is a number "
            "with at least two digits (the variant is its last two digits, 00–99)"
        )
    return int(digits[-2:])


def variant_for_index(i: int, record_book: str | None = None) -> Variant:
    """The variant with index i, 0 ≤ i ≤ 99 (i = 0 is the guide's worked example)."""
    i = check_int_range("i", i, 0, 99)
    return Variant(
        record_book=str(record_book) if record_book is not None else f"(variant {i:02d})",
        i=i,
        W_kmh=200.0 + 10.0 * i,
        f_mm=100.0 + 10.0 * i,
        m=12000.0 + 100.0 * i,
        M=10000.0,
        frame_mm=180.0,
        px_percent=60.0,
        py_percent=30.0,
        Lx_km=25.0 + i,
        Ly_km=30.0 + i,
        Zmax_m=200.0 + i,
        Zmin_m=170.0 + i,
        alpha_deg=3.0,
        lambda_deg=-60.0 + i,
    )


def variant(record_book) -> Variant:
    """The variant of a student, from the record-book number (guide §1)."""
    return variant_for_index(index_from_record_book(record_book), str(record_book))


#: what a variant argument may be, for the messages
VARIANT_FORMS = ("a Variant (variants.variant('19-0457')), a record-book number with at least two digits "
                 "('19-0457', 190457) or None for the guide's worked example (variant 00)")
#: the same without None, where a variant must be given
VARIANT_FORMS_GIVEN = ("a Variant (variants.variant('19-0457')) or a record-book number with at least two digits "
                       "('19-0457', 190457)")


def as_variant(variant, name: str = "variant", *, none: bool = True) -> Variant | None:
    """The one resolution of a variant argument: a :class:`Variant`, or None (the guide's example) when ``none``.

    A record-book number (a string or an integer with at least two digits) is turned into its variant; anything
    else — ``'abc'``, an object without the variant's fields — is a ValueError/TypeError naming ``name`` and the
    valid forms, never a silent fall-back to the guide's example.
    """
    if isinstance(variant, Variant) or (none and variant is None):
        return variant
    forms = VARIANT_FORMS if none else VARIANT_FORMS_GIVEN
    if isinstance(variant, str) or (isinstance(variant, int) and not isinstance(variant, bool)):
        try:
            return _variant_of(variant)
        except ValueError:
            raise ValueError(f"{name} = {variant!r:.40} is not a variant; expected {forms}") from None
    check_type(name, variant, Variant, what=forms, none=none)
    return variant


_variant_of = variant

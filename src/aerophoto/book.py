"""The notebooks' one setup call: style, live figures, installation check, variant.

Every chapter starts with::

    RECORD_BOOK = None          # ← type your record-book number, e.g. "19-0457"
    import aerophoto
    v = aerophoto.setup(RECORD_BOOK)

``setup`` applies the book's plotting style, switches matplotlib to the live
widget backend (ipympl), checks that the installed packages are the ones the
book needs, and returns the student's :class:`~aerophoto.variants.Variant`.

Typing the number once is enough: ``setup`` remembers the last number given
(in ``~/.aerophoto/student.json``, or ``$AEROPHOTO_HOME/student.json``) and
uses it in chapters whose first cell is left at ``None``.  The environment
variable ``AEROPHOTO_RECORD_BOOK`` overrides both (used by tests).  With no
number anywhere, the book shows the guide's own worked example, variant 00.
"""

from __future__ import annotations

import json
import os
from importlib import metadata
from pathlib import Path

from . import __version__
from .plots import use_style
from .variants import Variant, variant, variant_for_index

__all__ = ["setup", "check_installation", "remembered_record_book", "remember_record_book", "state_dir"]

REQUIRED = {  # distribution: (minimum major.minor, why)
    "numpy": ((2, 0), "computing"),
    "matplotlib": ((3, 9), "figures"),
    "ipywidgets": ((8, 1), "sliders"),
    "ipympl": ((0, 9), "live figures"),
    "pandas": ((2, 2), "tables"),
}


def state_dir() -> Path:
    """Where aerophoto keeps the remembered record-book number."""
    return Path(os.environ.get("AEROPHOTO_HOME") or Path.home() / ".aerophoto")


def remembered_record_book() -> str | None:
    """The record-book number from the environment or the last ``setup`` call, or None."""
    env = os.environ.get("AEROPHOTO_RECORD_BOOK")
    if env:
        return env
    path = state_dir() / "student.json"
    try:
        return json.loads(path.read_text(encoding="utf-8")).get("record_book") or None
    except (OSError, ValueError):
        return None


def remember_record_book(record_book: str) -> None:
    """Save the number so later chapters can leave their first cell at None."""
    d = state_dir()
    try:
        d.mkdir(parents=True, exist_ok=True)
        (d / "student.json").write_text(json.dumps({"record_book": str(record_book)}), encoding="utf-8")
    except OSError:
        pass  # a read-only home must not stop the book


def _version_tuple(text: str) -> tuple:
    parts = []
    for p in text.split(".")[:2]:
        digits = "".join(ch for ch in p if ch.isdigit())
        parts.append(int(digits or 0))
    return tuple(parts)


def check_installation() -> list[str]:
    """Return a list of problems with the installed packages (empty when all is well)."""
    problems = []
    for dist, (minimum, why) in REQUIRED.items():
        try:
            have = metadata.version(dist)
        except metadata.PackageNotFoundError:
            problems.append(f"{dist} is not installed (needed for {why}); run: python -m pip install -r environment.txt")
            continue
        if _version_tuple(have) < minimum:
            problems.append(f"{dist} {have} is too old (need ≥ {'.'.join(map(str, minimum))} for {why})")
    return problems


def _in_ipython():
    try:
        from IPython import get_ipython
    except ImportError:
        return None
    return get_ipython()


def setup(record_book=None, *, live: bool = True, quiet: bool = False) -> Variant:
    """Prepare a chapter and return the student's variant.

    Parameters
    ----------
    record_book : str or int or None
        The student's record-book number (номер зачётной книжки); the variant
        is its last two digits (guide §1).  None: use the remembered number,
        else the guide's worked example (variant 00).
    live : bool
        Switch to the ipympl widget backend (``%matplotlib widget``) so demos
        update in place.  Set False for static figures.
    quiet : bool
        Do not display the banner.
    """
    use_style()
    problems = check_installation()
    if problems:
        raise RuntimeError("aerophoto cannot run in this environment:\n- " + "\n- ".join(problems))
    ip = _in_ipython()
    if live and ip is not None:
        ip.run_line_magic("matplotlib", "widget")
    note = ""
    if record_book is not None and str(record_book).strip():
        v = variant(record_book)
        remember_record_book(str(record_book).strip())
    else:
        saved = remembered_record_book()
        if saved:
            v = variant(saved)
            note = f"(remembered from an earlier chapter: {saved})"
        else:
            v = variant_for_index(0, "not given — the guide's worked example")
            note = "Type your record-book number in the first cell to get your own variant."
    if not quiet:
        _banner(v, note, ip)
    return v


def _banner(v: Variant, note: str, ip) -> None:
    text = (
        f"aerophoto {__version__} · variant i = {v.i:02d} · record book: {v.record_book} {note}\n"
        f"f = {v.f_mm:g} mm, 1/m = 1:{v.m:.0f}, W = {v.W_kmh:g} km/h, α = {v.alpha_deg:g}°, λ = {v.lambda_deg:g}°. "
        "The code behind every figure is in the package: add ?? to a name to read it, "
        "e.g. aerophoto.geometry.ground_to_photo??"
    )
    if ip is None:
        print(text)
        return
    from IPython.display import HTML, display

    line1, line2 = text.split("\n")
    display(HTML(f"<div style='border-left:4px solid #0072B2;padding:4px 8px'><b>{line1}</b><br>{line2}</div>"))

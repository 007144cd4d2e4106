"""Helpers shared by the presentation tests (the demos' test files import them: ``from .conftest import …``)."""


def _extremes(demo_cls):
    """Every slider at its low and high end (choices: every option), one at a time."""
    out = []
    for p in demo_cls.params:
        if p.kind == "choice":
            out += [{p.name: o[1] if isinstance(o, tuple) else o} for o in p.options]
        else:
            out += [{p.name: p.lo}, {p.name: p.hi}]
    return out

"""Bundle block adjustment (блочная фототриангуляция по методу связок), article 002 — chapter 15.
"""
from __future__ import annotations

from . import block, collinearity, design, solve, stages
from .block import *  # noqa: F403
from .collinearity import *  # noqa: F403
from .design import *  # noqa: F403
from .solve import *  # noqa: F403
from .stages import *  # noqa: F403

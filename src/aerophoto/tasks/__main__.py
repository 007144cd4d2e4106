"""``python -m aerophoto.tasks``: write docs/grading_table.md (``--measure`` first measures the deviations)."""

import sys

from .table import main

sys.exit(main())

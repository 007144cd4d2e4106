"""``python -m aerophoto.course``: the same as the ``aerophoto-course`` command."""

from .cli import main

raise SystemExit(main())

"""``python -m pendula ...`` is the ``pendula`` command (see pendula.cli)."""

from .cli import main

raise SystemExit(main())

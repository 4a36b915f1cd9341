"""``python -m lumped``: see :mod:`lumped.cli`."""

from lumped.cli import main

raise SystemExit(main())

"""``python -m cdpr_algebra``: the same CLI as the ``cdpr`` console script."""

import sys

from .cli import main

sys.exit(main())

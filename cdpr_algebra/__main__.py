"""``python -m cdpr_algebra``: the same CLI as the ``cdpr`` console script."""

import sys

from cdpr_algebra.cli.main import main

sys.exit(main())

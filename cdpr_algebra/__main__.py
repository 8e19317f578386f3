"""``python -m cdpr_algebra``: the same CLI as the ``cdpr`` console script."""

from cdpr_algebra.cli.main import console

console()

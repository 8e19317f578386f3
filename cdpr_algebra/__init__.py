"""cdpr_algebra: every equilibrium of underconstrained cable-driven parallel robots.

Data flow: robot file -> :class:`Robot` -> problem (IGP / DGP) -> solver -> filter -> result -> CLI.
"""

from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.model.robot import Robot, load_robot
from cdpr_algebra.model.pose import Pose

__all__ = ["CdprInputError", "Robot", "load_robot", "Pose"]
__version__ = "0.1.0"

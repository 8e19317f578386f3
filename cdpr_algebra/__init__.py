"""cdpr_algebra: every equilibrium of underconstrained cable-driven parallel robots.

Data flow: robot file -> :class:`Robot` (``model/``) -> problem (``igp/``, ``dgp/``, ``bp/``, ``cc/``, ``track/``) -> solver
(``homotopy/``, ``intervals/``) -> filter -> certificate (``certificates/``) -> result -> table/JSON/plot
(``report/``) -> CLI (``cli/``).  The README's "Architecture" section draws the layers.

The public API below is imported lazily (module ``__getattr__``), so ``import cdpr_algebra`` loads only what a
name needs::

    from cdpr_algebra import load_robot, solve_dgp
    robot = load_robot("examples/seed000_test1.toml")
    result = solve_dgp(robot)          # every equilibrium, every set of taut cables, certified
"""

from importlib import import_module

__version__ = "0.1.0"

# public name -> (module, attribute)
_API = {
    "CdprInputError": ("cdpr_algebra.model.errors", "CdprInputError"),
    "Robot": ("cdpr_algebra.model.robot", "Robot"),
    "load_robot": ("cdpr_algebra.model.robot", "load_robot"),
    "Pose": ("cdpr_algebra.model.pose", "Pose"),
    "solve_igp_orientation": ("cdpr_algebra.igp.orientation", "igp_orientation"),
    "solve_igp_position": ("cdpr_algebra.igp.position", "igp_position"),
    "solve_dgp": ("cdpr_algebra.dgp.solve", "dgp"),
    "solve_dgp_interval": ("cdpr_algebra.bp.search", "interval_dgp"),
    "certify": ("cdpr_algebra.certificates.equilibria", "certify_taut_root"),
    "crosscheck": ("cdpr_algebra.comparison.compare", "crosscheck"),
    "settle_incomplete": ("cdpr_algebra.comparison.settle", "settle_incomplete"),
    "cable_configurations": ("cdpr_algebra.cc.configurations", "valid_configurations"),
    "robustness_radius": ("cdpr_algebra.cc.radii", "cc_radii"),
    "plot_equilibrium": ("cdpr_algebra.report.plot", "plot_equilibria"),
    "track_equilibrium": ("cdpr_algebra.track.follow", "track"),
    "LengthTrajectory": ("cdpr_algebra.track.trajectory", "LengthTrajectory"),
}

__all__ = sorted(_API)


def __getattr__(name):
    try:
        module, attribute = _API[name]
    except KeyError:
        raise AttributeError(f"module 'cdpr_algebra' has no attribute {name!r}") from None
    value = getattr(import_module(module), attribute)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__():
    return sorted(set(globals()) | set(_API))

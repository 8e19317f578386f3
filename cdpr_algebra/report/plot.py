"""Pictures of equilibria with matplotlib (issue 7).

* :func:`plot_equilibria`: DGP solutions (:class:`cdpr_algebra.dgp.solve.DGPSolution`), one 3-D panel per equilibrium;
* :func:`plot_igp_solutions`: IGP results (:class:`cdpr_algebra.igp.results.IGPResult`), one panel per solution, or the
  special solution set of seed 004 App. A;
* :func:`plot_radius_along_path`: a ranking of cable configurations along a trajectory (radius against
  the path parameter);
* :func:`draw_configuration`: one configuration on a given 3-D axes (the building block of the first two).

What a panel shows: the base exit points A_i (black triangles, numbered), the platform as a solid body (the
filled convex hull of its anchor points B_i = p + R b_i' and its centre of mass G), cables A_i B_i (taut:
solid, coloured by tension with a colour bar; slack: dashed grey), the load Q d as an arrow at G, equal
axes.  When the load acts along +z (z pointing down, seed 000 Test 1, seed 004) the z axis is inverted so
the load points down on the page.  Cables are the only ``Line3D`` artists of a panel (``gid`` "cable i",
1-based), so they can be counted.

The functions build bare :class:`matplotlib.figure.Figure` objects (no pyplot state, no GUI backend);
``fig.savefig(path)`` writes PNG or SVG.  In a notebook run ``%matplotlib inline`` once and the returned
figures display themselves.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib import colormaps
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.cm import ScalarMappable
from matplotlib.colors import LinearSegmentedColormap, Normalize, TwoSlopeNorm
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from cdpr_algebra.model.errors import CdprInputError

__all__ = ["draw_configuration", "plot_equilibria", "plot_igp_solutions", "plot_radius_along_path",
           "set_equal_axes", "tension_colours"]

PANEL_INCHES = 4.0
BODY_COLOUR = "#8fb3d9"
SLACK_COLOUR = "0.55"
_DIVERGING = LinearSegmentedColormap.from_list("tension_sign", ["#1f3fbf", "#7a7a7a", "#c8201e"])


# ----------------------------------------------------------------------------------------- geometry
def _body_polygons(points: np.ndarray) -> list[np.ndarray]:
    """Faces of the convex hull of ``points`` (k, 3): triangles of a 3-D hull, one polygon for coplanar
    points, a degenerate 2-point polygon for collinear ones."""
    from scipy.spatial import ConvexHull, QhullError

    pts = np.asarray(points, dtype=float)
    c = pts.mean(axis=0)
    _, s, Vt = np.linalg.svd(pts - c)
    scale = max(s[0], 1e-300)
    if len(pts) >= 4 and s[2] > 1e-9 * scale:
        try:
            hull = ConvexHull(pts)
            return [pts[simplex] for simplex in hull.simplices]
        except QhullError:
            pass
    if len(pts) >= 3 and s[1] > 1e-9 * scale:
        uv = (pts - c) @ Vt[:2].T
        try:
            hull = ConvexHull(uv)
            return [pts[hull.vertices]]
        except QhullError:
            pass
    t = (pts - c) @ Vt[0]
    return [pts[[int(np.argmin(t)), int(np.argmax(t))]]]


def set_equal_axes(ax, points, invert_z: bool = False) -> None:
    """Equal scales on a 3-D axes: a cube around ``points`` (k, 3); ``invert_z`` turns z downwards."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    lo, hi = points.min(axis=0), points.max(axis=0)
    mid = (lo + hi) / 2
    half = max(float((hi - lo).max()) / 2, 1e-9) * 1.05
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_box_aspect((1, 1, 1))
    if invert_z:
        ax.invert_zaxis()
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")


def tension_colours(tensions) -> tuple:
    """(norm, cmap) for cable tensions: 0 .. max on 'viridis' when no tension is negative, else a diverging
    map centred on 0 (negative blue, zero grey, positive red; no white, so weak cables stay visible)."""
    t = np.asarray([v for v in np.ravel(tensions) if np.isfinite(v)], dtype=float)
    tmin = float(t.min()) if t.size else 0.0
    tmax = float(t.max()) if t.size else 1.0
    if tmin < 0:
        return TwoSlopeNorm(vcenter=0.0, vmin=tmin, vmax=max(tmax, 1e-12 * abs(tmin))), _DIVERGING
    return Normalize(0.0, tmax if tmax > 0 else 1.0), colormaps["viridis"]


def draw_configuration(ax, robot, position, rotation, tensions, taut=None, *, norm=None, cmap=None,
                       label_base: bool = True):
    """Draw one configuration of ``robot`` on a 3-D axes.

    ``position``: platform-frame origin p; ``rotation``: R (B_i = p + R b_i', G = p + R g'); ``tensions``: n
    values; ``taut``: the 1-based taut cables (default: all).  Taut cables are solid lines coloured by
    ``cmap(norm(tau_i))``, slack ones dashed grey.  Returns the (2n + 2, 3) array of drawn points (A_i, B_i, G
    and the arrow tip) for :func:`set_equal_axes`.
    """
    A = robot.base
    R = np.asarray(rotation, dtype=float)
    p = np.asarray(position, dtype=float)
    B = p + robot.platform @ R.T
    G = p + R @ robot.com
    tau = np.asarray(tensions, dtype=float)
    taut = set(range(1, robot.n + 1)) if taut is None else set(taut)
    if norm is None or cmap is None:
        norm, cmap = tension_colours(tau[[i - 1 for i in sorted(taut)]])
    # the platform: hull of the anchors and G
    faces = _body_polygons(np.vstack([B, G]))
    ax.add_collection3d(Poly3DCollection(faces, facecolors=BODY_COLOUR, edgecolors="#4a6f99", linewidths=0.4,
                                         alpha=0.55))
    ax.scatter(*A.T, marker="^", color="black", s=22, depthshade=False)
    if label_base:
        for i, a in enumerate(A):
            ax.text(*a, f" {i + 1}", fontsize=7, color="black")
    for i in range(robot.n):
        xs, ys, zs = zip(A[i], B[i])
        if i + 1 in taut:
            ax.plot(xs, ys, zs, linestyle="-", linewidth=2.0, color=cmap(norm(tau[i])), gid=f"cable {i + 1}")
        else:
            ax.plot(xs, ys, zs, linestyle="--", linewidth=1.0, color=SLACK_COLOUR, gid=f"cable {i + 1}")
    d = np.asarray(robot.load_direction, dtype=float)
    d = d / np.linalg.norm(d)
    arrow = 0.2 * robot.size * d
    ax.quiver(*G, *arrow, color="crimson", linewidth=1.5, arrow_length_ratio=0.3)
    ax.scatter(*G, color="crimson", s=12, depthshade=False)
    return np.vstack([A, B, G, G + arrow])


def _grid(n: int, ncols: int | None) -> tuple[int, int]:
    ncols = max(1, min(n, ncols or (n if n <= 4 else 3 if n <= 9 else 4 if n <= 16 else 6)))
    return math.ceil(n / ncols), ncols


def _new_figure(nrows: int, ncols: int) -> Figure:
    fig = Figure(figsize=(PANEL_INCHES * ncols + 1.2, PANEL_INCHES * nrows + 0.6), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _colour_bar(fig, axes, norm, cmap, label="cable tension") -> None:
    sm = ScalarMappable(norm=norm, cmap=cmap)
    sm.set_array([])
    fig.colorbar(sm, ax=axes, shrink=0.6, label=label)


# ----------------------------------------------------------------------------------------- DGP
def plot_equilibria(robot, solutions, *, ncols: int | None = None, title: str | None = None,
                    max_panels: int | None = None) -> Figure:
    """One 3-D panel per equilibrium of the DGP (:class:`cdpr_algebra.dgp.solve.DGPSolution` records, e.g. ``dgp(...).solutions``).

    Panel k is titled "#k taut [i, j, ...]" and its stability ("stable" when H_r is '>', else the H_r class);
    one colour bar for the tensions of all panels.  With no solution the figure has one panel with the base.
    """
    sols = list(solutions)[:max_panels] if max_panels else list(solutions)
    if not sols:
        fig = _new_figure(1, 1)
        ax = fig.add_subplot(1, 1, 1, projection="3d")
        ax.scatter(*robot.base.T, marker="^", color="black", s=22)
        set_equal_axes(ax, robot.base, robot.load_direction[2] > 0)
        ax.set_title("no admissible equilibrium")
        fig.suptitle(title or robot.name)
        return fig
    nrows, ncols = _grid(len(sols), ncols)
    fig = _new_figure(nrows, ncols)
    taut_tensions = [s.tensions[i - 1] for s in sols for i in s.taut]
    norm, cmap = tension_colours(taut_tensions)
    axes = []
    for k, s in enumerate(sols):
        ax = fig.add_subplot(nrows, ncols, k + 1, projection="3d")
        pts = draw_configuration(ax, robot, s.position, s.rotation, s.tensions, s.taut, norm=norm, cmap=cmap)
        set_equal_axes(ax, pts, robot.load_direction[2] > 0)
        stab = "stable" if s.stable else f"unstable (H_r {s.hessian})"
        ax.set_title(f"#{k + 1}  taut {list(s.taut)}\n{stab}", fontsize=9)
        axes.append(ax)
    _colour_bar(fig, axes, norm, cmap)
    nstable = sum(1 for s in sols if s.stable)
    fig.suptitle(title or f"{robot.name}: {len(sols)} admissible equilibria, {nstable} stable")
    return fig


# ----------------------------------------------------------------------------------------- IGP
_SELECT = {
    "real": lambda s: s.real,
    "admissible": lambda s: s.admissible,
    "stable": lambda s: s.real and bool(s.stable),
    "admissible_or_stable": lambda s: s.admissible or (s.real and bool(s.stable)),
}


def plot_igp_solutions(robot, result, *, select="real", ncols: int | None = None, title: str | None = None) -> Figure:
    """One 3-D panel per solution of an IGP (:class:`cdpr_algebra.igp.results.IGPResult` of :func:`cdpr_algebra.igp.orientation.igp_orientation`
    or :func:`cdpr_algebra.igp.position.igp_position`).

    ``select``: 'real' (default), 'admissible', 'stable', 'admissible_or_stable' or a predicate on
    :class:`cdpr_algebra.igp.results.IGPSolution`.  Panels are numbered by the solution's 1-based index in ``result.solutions``
    and say whether every tension is >= 0 and the H_r class.  All three cables have the lengths the IGP
    computed, so all are drawn solid, coloured by tension (a diverging map when some tension is negative).
    When the result is a special set of seed 004 App. A instead (``result.solution_set``), one panel shows the
    base and, for a vertical line or a crane, the line of G (dash-dot, ``gid`` "solution set").
    """
    pick = _SELECT.get(select, select) if isinstance(select, str) else select
    if not callable(pick):
        raise CdprInputError("select", f"expected one of {sorted(_SELECT)} or a predicate, got {select!r}")
    chosen = [(k, s) for k, s in enumerate(result.solutions) if s.real and pick(s)]
    if not chosen:
        fig = _new_figure(1, 1)
        ax = fig.add_subplot(1, 1, 1, projection="3d")
        ax.scatter(*robot.base.T, marker="^", color="black", s=22)
        pts = [robot.base]
        sset = result.solution_set
        if sset is not None and "line_point" in sset.data:
            q = np.asarray(sset.data["line_point"], dtype=float)
            d = np.asarray(sset.data["line_direction"], dtype=float)
            seg = np.array([q - robot.size * d, q + robot.size * d])
            ax.plot(*seg.T, linestyle="-.", color="crimson", gid="solution set")
            pts.append(seg)
        set_equal_axes(ax, np.vstack(pts), robot.load_direction[2] > 0)
        ax.set_title(sset.kind.replace("_", " ") if sset is not None else "no solution selected", fontsize=9)
        fig.suptitle(title or f"{robot.name}: IGP with assigned {result.problem}")
        return fig
    nrows, ncols = _grid(len(chosen), ncols)
    fig = _new_figure(nrows, ncols)
    norm, cmap = tension_colours([t for _, s in chosen for t in np.real(s.tensions)])
    axes = []
    for j, (k, s) in enumerate(chosen):
        ax = fig.add_subplot(nrows, ncols, j + 1, projection="3d")
        pts = draw_configuration(ax, robot, np.real(s.position), np.real(s.rotation), np.real(s.tensions),
                                 norm=norm, cmap=cmap)
        set_equal_axes(ax, pts, robot.load_direction[2] > 0)
        adm = "all tau >= 0" if s.admissible else "some tau < 0"
        ax.set_title(f"#{k + 1}  {adm}\nH_r {s.hessian}", fontsize=9)
        axes.append(ax)
    _colour_bar(fig, axes, norm, cmap)
    nadm = sum(1 for _, s in chosen if s.admissible)
    fig.suptitle(title or f"{robot.name}: IGP with assigned {result.problem}, {len(chosen)} shown, {nadm} admissible")
    return fig


# ----------------------------------------------------------------------------------------- rankings
def plot_radius_along_path(ts, radii, labels, *, xlabel: str = "path parameter t",
                           ylabel: str = "robustness radius", title: str | None = None) -> Figure:
    """Radius of each cable configuration against the path parameter: one line per configuration.

    ``ts``: (N,) path parameters; ``radii``: (K, N) radii (NaN where a configuration is not valid: a gap);
    ``labels``: K names (e.g. "[3, 4, 5, 6, 7, 8]").  The largest radius at each t is the best-ranked
    configuration there.
    """
    t = np.asarray(ts, dtype=float)
    r = np.asarray(radii, dtype=float)
    if t.ndim != 1 or t.size == 0:
        raise CdprInputError("ts", f"expected a non-empty 1-D array of path parameters, got shape {t.shape}")
    if r.ndim == 1:
        r = r[None, :]
    if r.ndim != 2 or r.shape[1] != t.size:
        raise CdprInputError("radii", f"expected shape (K, {t.size}) to match ts, got {np.shape(radii)}")
    labels = [str(v) for v in labels]
    if len(labels) != r.shape[0]:
        raise CdprInputError("labels", f"expected {r.shape[0]} labels (one per row of radii), got {len(labels)}")
    fig = Figure(figsize=(7, 4), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    for row, lab in zip(r, labels):
        ax.plot(t, row, label=lab, linewidth=1.6)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    if title:
        ax.set_title(title)
    return fig

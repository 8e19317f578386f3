"""Pictures of a sweep: a value per grid point (``n_stable``, ``n_admissible``, ``min_tension``, ``rmin``) against
one varied name (a line), two (a heat map), or x, y, z of a pose sweep (the workspace: the grid's points in space
coloured by the value); points with an error or incomplete are marked."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from cdpr_algebra.model.errors import CdprInputError

from .run import read_table

VALUES = ("n_stable", "n_admissible", "min_tension", "rmin")


def sweep_figure(out, value: str = "n_stable"):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out)
    header_file = out / "sweep.json"
    if not header_file.exists():
        raise CdprInputError("DIR", f"{out} holds no sweep (no sweep.json)")
    try:
        header = json.loads(header_file.read_text(encoding="utf-8"))
        axes = header["grid"]["axes"]
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise CdprInputError("DIR", f"{header_file} is not a sweep's header ({type(exc).__name__}: {exc})") from None
    pts = read_table(out, "points")
    if pts is None:
        raise CdprInputError("DIR", f"{out} has no finished point yet")
    if value not in VALUES or value not in pts.column_names:
        have = [v for v in VALUES if v in pts.column_names]
        raise CdprInputError("--value", f"expected one of {', '.join(have)}, got {value!r}")
    rows = pts.to_pylist()
    bad = [r for r in rows if r["error"] or not r["complete"]]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    if len(axes) == 1:
        name = axes[0]["name"]
        rows.sort(key=lambda r: r[name])
        x = np.array([r[name] for r in rows])
        y = np.array([np.nan if r[value] is None else r[value] for r in rows], dtype=float)
        ax.plot(x, y, "o-", ms=3)
        if bad:
            ax.plot([r[name] for r in bad], [0 if r[value] is None else r[value] for r in bad], "rx",
                    label="error / incomplete")
            ax.legend()
        ax.set_xlabel(name)
        ax.set_ylabel(value)
    elif len(axes) == 2:
        n0, n1 = axes[0]["name"], axes[1]["name"]
        v0, v1 = np.array(axes[0]["values"]), np.array(axes[1]["values"])
        Z = np.full((len(v0), len(v1)), np.nan)
        for r in rows:
            i, j = divmod(r["point"], len(v1))
            Z[i, j] = np.nan if r[value] is None else r[value]
        mesh = ax.pcolormesh(v1, v0, Z, shading="nearest")
        fig.colorbar(mesh, ax=ax, label=value)
        if bad:
            ax.plot([r[n1] for r in bad], [r[n0] for r in bad], "rx", label="error / incomplete")
            ax.legend()
        ax.set_xlabel(n1)
        ax.set_ylabel(n0)
    elif len(axes) == 3 and {a["name"] for a in axes} == {"x", "y", "z"}:
        # a workspace picture: the points of the pose grid in space, coloured by the value (failed ones marked)
        plt.close(fig)
        fig = plt.figure(figsize=(6.5, 5))
        ax = fig.add_subplot(projection="3d")
        X = np.array([[r["x"], r["y"], r["z"]] for r in rows])
        V = np.array([np.nan if r[value] is None else r[value] for r in rows], dtype=float)
        sc = ax.scatter(*X.T, c=V, cmap="viridis", s=18, depthshade=False)
        fig.colorbar(sc, ax=ax, label=value, shrink=0.7)
        if bad:
            ax.scatter(*np.array([[r["x"], r["y"], r["z"]] for r in bad]).T, marker="x", color="red", s=30,
                       label="error / incomplete")
            ax.legend()
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
    else:
        raise CdprInputError("DIR", f"pictures are drawn for 1 or 2 varied names, or x, y, z (a workspace); this "
                             f"sweep varies {[a['name'] for a in axes]}")
    ax.set_title(f"{header['robot']['name']}: {value} ({header['grid']['kind']} sweep, {len(rows)} points)")
    fig.tight_layout()
    return fig


def save_sweep_figure(out, path, value: str = "n_stable") -> None:
    fig = sweep_figure(out, value)
    fig.savefig(path)
    import matplotlib.pyplot as plt

    plt.close(fig)

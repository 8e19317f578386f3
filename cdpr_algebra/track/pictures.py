"""Pictures of a tracking: tensions and the lowest reduced-Hessian eigenvalue against t, events marked."""

from __future__ import annotations

import numpy as np

COLOURS = {"slack": "tab:orange", "taut": "tab:green", "fold": "tab:red", "jump": "tab:purple", "singular": "k"}


def tracking_figure(res, robot):
    """A matplotlib figure: tensions / Q (top) and the scaled lowest eigenvalue of the reduced Hessian (bottom)
    at the reported states, with a vertical line at every event."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    states = sorted([(s.t, s) for s in res.steps] + [(e.t, e.state) for e in res.events]
                    + [(e.t, e.landing) for e in res.events if e.landing is not None], key=lambda v: v[0])
    t = np.array([v[0] for v in states])
    tau = np.array([v[1].tensions for v in states]) / robot.load
    eig = np.array([v[1].min_eigenvalue for v in states])
    fig, (a1, a2) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    for i in range(robot.n):
        a1.plot(t, tau[:, i], label=f"cable {i + 1}")
    a1.set_ylabel("tension / load")
    a1.legend(fontsize="small", ncol=min(robot.n, 4))
    a2.plot(t, np.where(np.isfinite(eig), eig, np.nan), color="k")
    a2.axhline(0.0, color="0.6", lw=0.8)
    a2.set_ylabel("lowest eigenvalue of H_r (scaled)")
    a2.set_xlabel("t")
    seen = set()
    for e in res.events:
        for ax in (a1, a2):
            ax.axvline(e.t, color=COLOURS.get(e.kind, "k"), ls="--", lw=0.8,
                       label=e.kind if ax is a2 and e.kind not in seen else None)
        seen.add(e.kind)
    if seen:
        a2.legend(fontsize="small")
    fig.suptitle(f"{robot.name}: {res.status}")
    fig.tight_layout()
    return fig


def save_tracking_figure(res, robot, path) -> None:
    fig = tracking_figure(res, robot)
    fig.savefig(path)
    import matplotlib.pyplot as plt

    plt.close(fig)


def save_tracking_animation(res, robot, path, fps: int = 4) -> int:
    """An animation of the tracked robot, one frame per reported state (samples, events and landings, in order of
    t), saved as GIF (matplotlib's PillowWriter) or MP4 (FFMpegWriter, when ffmpeg is installed); taut cables solid
    and coloured by tension, slack ones dashed grey (:func:`cdpr_algebra.report.plot.draw_configuration`).  Returns
    the number of frames."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import animation

    from cdpr_algebra.model.errors import CdprInputError
    from cdpr_algebra.report.plot import draw_configuration, set_equal_axes

    frames = sorted([(s.t, "", s) for s in res.steps] + [(e.t, e.kind, e.state) for e in res.events]
                    + [(e.t, "landing", e.landing) for e in res.events if e.landing is not None], key=lambda v: v[0])
    suffix = str(path).lower().rsplit(".", 1)[-1]
    if suffix == "gif":
        writer = animation.PillowWriter(fps=fps)
    elif suffix == "mp4":
        if not animation.FFMpegWriter.isAvailable():
            raise CdprInputError("--animate", "MP4 needs ffmpeg, which is not installed: save a .gif")
        writer = animation.FFMpegWriter(fps=fps)
    else:
        raise CdprInputError("--animate", f"expected a .gif or .mp4 file name, got {path!r}")
    points = []
    for _, _, s in frames:
        B = s.position + robot.platform @ s.rotation.T
        points.append(np.vstack([robot.base, B, s.position + s.rotation @ robot.com]))
    points = np.vstack(points)
    fig = plt.figure(figsize=(6, 5))
    ax = fig.add_subplot(projection="3d")
    invert = robot.load_direction[2] > 0  # z down (gravity along +z): draw it pointing down

    def draw(k):
        ax.cla()
        t, kind, s = frames[k]
        draw_configuration(ax, robot, s.position, s.rotation, s.tensions, s.taut)
        set_equal_axes(ax, points, invert_z=invert)
        label = f"t = {t:.4g}" + (f"  ({kind})" if kind else "") + f"  taut {list(s.taut)}"
        ax.set_title(label, fontsize=9)
        return []

    anim = animation.FuncAnimation(fig, draw, frames=len(frames), blit=False)
    anim.save(str(path), writer=writer)
    plt.close(fig)
    return len(frames)

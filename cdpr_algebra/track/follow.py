"""Quasi-static tracking of the robot's equilibrium along a cable-length trajectory rho(t) (issue: which equilibrium is
the robot in, and where does it go as the winches turn; Berti, Merlet and Carricato 2016, Sec. 5, leave it open).

From a stable equilibrium at rho(t_0) (default: the DGP's unique, or lowest-potential, stable equilibrium there),
the branch of the current taut set is continued by steps of a linear predictor (:func:`.branch.tangent`) and
Newton's corrector, halved when Newton needs many iterations or moves far from the prediction (so a step never
switches branch silently).  After every step the event functions of :func:`.branch.event_values` are checked; a
sign change is located by bisection in t to ``EVENT_TOL`` and handled:

* ``slack``: the cable leaves the taut set (its tension is 0 there); ``taut``: the slack cable joins it (with zero
  tension); the branch goes on with the new set;
* ``fold``: the lowest eigenvalue of the reduced Hessian reaches 0 (stability is lost, or the branch turns back):
  the robot jumps; :func:`.jump.land` finds the stable equilibrium it lands on (reported as a ``jump`` event with
  the energy released) and tracking goes on from there;
* ``singular``: the taut cables' wrench matrix loses rank, or one cable is left taut (the platform may turn about
  it): tracking stops there with the reason.

Every state reported is an equilibrium at its own lengths (residual of its equations), admissible, and between
events stable.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.report.jsonable import jsonable

from . import branch
from .jump import land
from .trajectory import LengthTrajectory

EVENT_TOL = 1e-10  # events located to this in t
EVENT_EPS = 1e-9  # event functions (tension / load, margin / size) within this of 0 count as 0
MAX_LENGTH_STEP = 0.02  # largest change of a cable length per step, relative to the robot's size
MIN_STEP = 1e-12  # steps in t below this: the branch cannot be continued (it turns back: a fold)
WRENCH_RANK_TOL = 1e-8  # sigma_min / sigma_max of the unit wrenches below this: singular
ADMISSIBLE_TOL = 1e-8  # tensions and slack margins down to -this (x load, x size) at a located event are rounding
LANDING_DTS = (1e-6, 1e-5, 1e-4, 1e-3)  # a jump's landing is sought at t_fold + these x the trajectory's span
START_TOL = 1e-3  # a start pose must be within this (x size; rotation entries) of an equilibrium: the DGP table
# prints poses to 3 decimals (1e-4 refused the rounded poses of Test 1, whose size is 12)
JUMP_MIN = 1e-2  # a landing within this (x size) of the fold pose on the same taut set is the old minimum
KINDS = ("slack", "taut", "fold", "jump", "singular")


@dataclass(frozen=True)
class TrackEvent:
    """An event between the requested samples ``step - 1`` and ``step``: ``kind`` (KINDS), the cables involved
    (1-based), the state there, and for a jump the landing state and the energy released."""

    step: int
    t: float
    kind: str
    cables: tuple
    state: branch.TrackState
    landing: branch.TrackState | None = None
    energy_released: float | None = None
    note: str | None = None

    def to_dict(self) -> dict:
        out = {"step": self.step, "t": self.t, "kind": self.kind, "cables": list(self.cables),
               "state": self.state.to_dict()}
        if self.landing is not None:
            out["landing"] = self.landing.to_dict()
            out["energy_released"] = self.energy_released
        if self.note:
            out["note"] = self.note
        return out


@dataclass(frozen=True)
class TrackResult:
    """The states at the requested samples (``steps``; fewer when tracking stopped), the events in order,
    ``status`` 'complete' (every sample reached) or 'stopped' (``reason``), the trajectory and the time taken."""

    steps: tuple
    events: tuple
    status: str
    reason: str | None
    trajectory: LengthTrajectory
    samples: np.ndarray
    seconds: float
    newton_steps: int = 0
    options: dict = field(default_factory=dict)
    start: dict = field(default_factory=dict)  # how the starting equilibrium was chosen (start_equilibrium)

    @property
    def complete(self) -> bool:
        return self.status == "complete"

    def to_dict(self) -> dict:
        return {"status": self.status, "reason": self.reason, "samples": jsonable(self.samples),
                "steps": [s.to_dict() for s in self.steps], "events": [e.to_dict() for e in self.events],
                "trajectory": self.trajectory.to_dict(), "seconds": self.seconds, "newton_steps": self.newton_steps,
                "options": self.options, "start": self.start}


def _start_state(robot, rho, t0, start):
    return start_equilibrium(robot, rho, t0, start)[0]


def start_equilibrium(robot, rho, t0, start):
    """(state, how it was chosen: {"method", "dgp_complete", "stable_found"}).  The starting equilibrium: ``start`` (a TrackState, or a (position, rotation) pose within START_TOL of a
    stable equilibrium, which Newton polishes) or the DGP's unique / lowest-potential stable equilibrium at rho (the
    DGP solved here, or ``start`` when it is the :class:`cdpr_algebra.dgp.solve.DGPResult` at rho); ``dgp_complete``:
    every admissible equilibrium of that DGP is known (``DGPResult.admissible_complete``)."""
    from cdpr_algebra.dgp.solve import DGPResult, dgp

    if start is not None and not isinstance(start, (branch.TrackState, DGPResult)):
        from cdpr_algebra.model.pose import check_rotation

        from .jump import statics_lam

        position = np.asarray(start[0], dtype=float)
        if position.shape != (3,) or not np.all(np.isfinite(position)):
            raise CdprInputError("start position", "expected 3 finite numbers")
        rotation = check_rotation(start[1], "start rotation", tol=START_TOL)
        tol = START_TOL * robot.size
        B = position + robot.platform @ rotation.T
        margin = rho - np.linalg.norm(robot.base - B, axis=1)
        if np.any(margin < -tol):
            bad = int(np.argmin(margin))
            raise CdprInputError("start", f"cable {bad + 1} would have to stretch by {-margin[bad]:.6g} at that pose")
        cables = tuple(int(i) for i in np.flatnonzero(margin <= tol))
        if not 2 <= len(cables) <= 6:
            raise CdprInputError("start", f"the pose has {len(cables)} taut cables (2 to 6 can be tracked)")
        lam, _ = statics_lam(robot, cables, position, rotation)
        x, ok, resid, _ = branch.newton(robot, cables, rho, branch.unknowns(position, rotation, lam))
        st = branch.state(robot, cables, rho, x, t0, resid) if ok else None
        if st is None or np.abs(st.position - position).max() > tol or np.abs(st.rotation - rotation).max() > START_TOL:
            raise CdprInputError("start", f"the pose is not within {START_TOL:g} (relative) of an equilibrium of its "
                                 f"taut cables {[c + 1 for c in cables]}")
        if np.any(st.tensions < -ADMISSIBLE_TOL * robot.load):
            raise CdprInputError("start", f"the equilibrium there has a negative tension ({st.tensions.round(6)})")
        if not st.stable:
            raise CdprInputError("start", f"the equilibrium there is not stable (H_r class {st.hessian}): the robot "
                                 "would not stay there")
        return st, {"method": "given pose", "dgp_complete": None, "stable_found": None}
    if isinstance(start, branch.TrackState):
        return start, {"method": "given state", "dgp_complete": None, "stable_found": None}
    # a DGPResult given as ``start`` is the DGP at the start lengths (e.g. settled by interval branch and prune)
    res = start if isinstance(start, DGPResult) else dgp(robot, rho, certify=False)
    stable = [s for s in res.solutions if s.stable and 2 <= len(s.taut) <= 6]
    if not stable:
        raise CdprInputError("lengths", "no stable equilibrium with 2 to 6 taut cables at the start lengths: give a "
                             "start pose")
    d = np.asarray(robot.load_direction, dtype=float)
    s = max(stable, key=lambda s: float(d @ (s.position + s.rotation @ robot.com)))  # lowest potential
    cables = tuple(c - 1 for c in s.taut)
    lam = s.tensions[list(cables)] / rho[list(cables)]
    x, ok, resid, _ = branch.newton(robot, cables, rho, branch.unknowns(s.position, s.rotation, lam))
    # what matters is that every admissible equilibrium is known (a complete DGP, or one whose incomplete
    # subproblems were settled by interval branch and prune)
    info = {"method": "the DGP's stable equilibrium of lowest potential", "dgp_complete": bool(res.admissible_complete),
            "stable_found": len(stable)}
    settled = [s for s in res.incomplete if s.settled]
    if settled and res.admissible_complete:
        info["note"] = (f"the admissible equilibria of the {len(settled)} DGP subproblem(s) with failed paths were "
                        "proven by interval branch and prune")
    if not res.admissible_complete:
        info["note"] = (f"the DGP at the start lengths is incomplete ({len(res.incomplete)} subproblem(s)): a stable "
                        "equilibrium of lower potential may be missing, so the start is not proven")
    return branch.state(robot, cables, rho, x, t0, resid), info


class _Stop(Exception):
    def __init__(self, reason, event=None):
        super().__init__(reason)
        self.reason, self.event = reason, event


def _step(robot, traj, st, t1):
    """One predictor-corrector step of the branch of ``st`` to t1 (compiled: :func:`.kernel.predict_correct`):
    (state, newton iterations) or None."""
    from .kernel import predict_correct

    rho0, rho1 = st.lengths, traj(t1)
    p0 = st.parameters if st.parameters is not None else branch.parameters(robot, st.cables, rho0).astype(complex)
    p1 = branch.parameters(robot, st.cables, rho1).astype(complex)
    x = np.empty(len(st.x), dtype=complex)
    status, its, ratio, resid = predict_correct(st.x.astype(complex), p0, p1, branch.NEWTON_TOL, branch.RESIDUAL_TOL,
                                                branch.residual_scale(robot), 6, x)
    # the corrector must stay near the prediction: a large correction means the step is too long for the
    # branch's curvature (and could land on another branch)
    if status != 1 or ratio > 0.1:
        return None
    nxt = branch.state(robot, st.cables, rho1, x.real, t1, resid)
    object.__setattr__(nxt, "parameters", p1)  # the next step's start parameters
    return nxt, its


def _crossed(robot, before, after):
    """Event keys whose function changed sign from > 0 to <= 0 between two states of one branch; a function that
    starts at 0 within EVENT_EPS (the cable that just became taut or slack at an event) counts once it passes
    -EVENT_EPS, so a cable that only grazes its length or zero tension is not followed into an inadmissible state."""
    a, b = branch.event_values(robot, before), branch.event_values(robot, after)
    out = []
    for k, va in a.items():
        if k not in b:
            continue
        if (va > 0 and b[k] <= 0) or (-EVENT_EPS < va <= 0 and b[k] < -EVENT_EPS):
            out.append(k)
    return out


def _locate(robot, traj, st, t1, key):
    """Bisection in t for the earliest sign change of event ``key`` between st.t and t1; returns the last state
    before it (within EVENT_TOL) and the first state after (or None when the branch ends there)."""
    lo, hi = st, None
    t_hi = t1
    while t_hi - lo.t > EVENT_TOL:
        tm = 0.5 * (lo.t + t_hi)
        r = _advance(robot, traj, lo, tm, events=False)
        if r is None:  # the branch does not reach tm from lo: the event is before
            t_hi = tm
            continue
        if branch.event_values(robot, r).get(key, 1.0) <= 0:
            hi, t_hi = r, tm
        else:
            lo = r
    return lo, hi


def _advance(robot, traj, st, t1, events=True, counter=None):
    """Continue the branch of ``st`` to t1 with adaptive steps; without ``events`` returns the state at t1 or None
    (used inside bisections); with ``events`` returns (state, crossed keys, t where they crossed)."""
    h = t1 - st.t
    cur = st
    while cur.t < t1 - 1e-15:
        rho_now, rho_end = cur.lengths, traj(min(t1, cur.t + h))
        dl = np.abs(rho_end - rho_now).max() / robot.size
        if dl > MAX_LENGTH_STEP:
            h *= MAX_LENGTH_STEP / dl
        tn = min(t1, cur.t + h)
        r = _step(robot, traj, cur, tn)
        if r is None:
            h *= 0.5
            if h < MIN_STEP:
                if events:
                    return cur, [("end", None)], tn
                return None
            continue
        nxt, its = r
        if counter is not None:
            counter[0] += its
        if events:
            keys = _crossed(robot, cur, nxt)
            if keys:
                return cur, keys, tn
        cur = nxt
        h = min(2 * h, t1 - cur.t) if cur.t < t1 else h
    return (cur, [], t1) if events else cur


def track(robot, traj: LengthTrajectory, samples=None, start=None, max_events: int = 100) -> TrackResult:
    """Follow the equilibrium along ``traj`` (module doc); ``samples``: the t at which states are reported
    (default 11 evenly spaced); ``start``: a TrackState or (position, rotation), default the DGP's stable
    equilibrium of lowest potential at rho(t_0) (or that of ``start`` when it is the DGPResult at rho(t_0))."""
    t0 = time.perf_counter()
    samples = np.linspace(traj.start, traj.end, 11) if samples is None else np.asarray(samples, dtype=float)
    if len(samples) < 1 or np.any(np.diff(samples) <= 0):
        raise CdprInputError("samples", "sample times must increase")
    if samples[0] < traj.start - 1e-12 or samples[-1] > traj.end + 1e-12:
        raise CdprInputError("samples", f"sample times must lie in [{traj.start:g}, {traj.end:g}]")
    st, start_info = start_equilibrium(robot, traj(samples[0]), float(samples[0]), start)
    steps, events = [st], []
    counter = [0]
    reason = None
    try:
        for k in range(1, len(samples)):
            t1 = float(samples[k])
            knots = traj.breakpoints(st.t, t1) + [t1]
            for tk in knots:
                while st.t < tk - 1e-15:
                    cur, keys, t_cross = _advance(robot, traj, st, tk, events=True, counter=counter)
                    if not keys:
                        st = cur
                        break
                    if len(events) >= max_events:
                        raise _Stop(f"more than {max_events} events")
                    st = _handle(robot, traj, cur, t_cross, keys, k, events)
            steps.append(st)
        status = "complete"
    except _Stop as stop:
        status, reason = "stopped", stop.reason
    return TrackResult(steps=tuple(steps), events=tuple(events), status=status, reason=reason, trajectory=traj,
                       samples=samples, seconds=time.perf_counter() - t0, newton_steps=counter[0],
                       options={"event_tol": EVENT_TOL, "max_length_step": MAX_LENGTH_STEP}, start=start_info)


def _handle(robot, traj, cur, t_cross, keys, k, events):
    """Locate the earliest of the crossed events, record it, and return the state to go on from."""
    if keys == [("end", None)]:
        # the branch cannot be continued past cur: a turning point (fold) of the branch, where the Jacobian of the
        # taut set's equations is singular and beyond which the equilibrium does not exist: the robot jumps
        if branch.wrench_condition(robot, cur) < WRENCH_RANK_TOL:
            raise _Stop(_singular(events, k, cur, "the taut cables' wrench matrix loses rank"))
        from cdpr_algebra.dgp.solve import prune

        t_after = min(traj.end, cur.t + LANDING_DTS[0] * (traj.end - traj.start))
        no_pose = prune(robot, traj(t_after), ())
        if no_pose is not None:  # the lengths stop admitting any pose: the tensions grow without bound
            tmax = float(np.max(cur.tensions) / robot.load)
            raise _Stop(_singular(events, k, cur, f"just after t = {cur.t:.12g} the lengths admit no pose ({no_pose});"
                                  f" the tensions grow without bound (up to {tmax:.4g} times the load here)"))
        located = [(cur.t, ("fold", None), cur, None)]
    else:
        located = []
        for key in keys:
            lo, hi = _locate(robot, traj, cur, t_cross, key)
            located.append((lo.t, key, lo, hi))
        located.sort(key=lambda v: v[0])
    t_ev, (kind, cable), lo, hi = located[0]
    if kind == "slack":
        cables = tuple(c for c in lo.cables if c != cable)
        events.append(TrackEvent(k, lo.t, "slack", (cable + 1,), lo))
        if len(cables) < 2:
            raise _Stop(_singular(events, k, lo, "one taut cable left: the platform may turn about it (not tracked)"))
        return _new_taut_set(robot, events, k, lo, cables, "went slack")
    if kind == "taut":
        cables = tuple(sorted(lo.cables + (cable,)))
        if len(cables) > 6:
            raise _Stop(_singular(events, k, lo, "a seventh cable becomes taut (redundantly constrained, not tracked)"))
        events.append(TrackEvent(k, lo.t, "taut", (cable + 1,), lo))
        return _new_taut_set(robot, events, k, lo, cables, "became taut")
    # fold: the equilibrium stops being stable; the robot jumps
    # the landing at lengths just past the fold, where the old minimum of the potential has gone: the fold is
    # located to where the steps underflow, so the first tries may still find the old minimum (not a jump)
    landing, why = None, "no try"
    for dt in LANDING_DTS:
        t_land = min(traj.end, lo.t + dt * (traj.end - traj.start))
        landing, why = land(robot, lo, traj(t_land), t_land)
        if landing is not None and np.abs(landing.position - lo.position).max() <= JUMP_MIN * robot.size \
                and landing.taut == lo.taut:
            landing, why = None, f"the potential still has its minimum near the fold at t = {t_land:.12g}"
            continue
        if landing is not None or t_land >= traj.end:
            break
    if landing is not None and np.abs(landing.position - lo.position).max() <= JUMP_MIN * robot.size:
        # no jump: the branch of this taut set ends where the robot goes on, continuously, with another taut set
        # (a cable reaching its length or going slack right at the branch's end)
        for c in sorted(set(landing.cables) - set(lo.cables)):
            events.append(TrackEvent(k, lo.t, "taut", (c + 1,), lo, note="at the end of the previous taut set's branch"))
        for c in sorted(set(lo.cables) - set(landing.cables)):
            events.append(TrackEvent(k, lo.t, "slack", (c + 1,), lo, note="at the end of the previous taut set's branch"))
        return _checked(robot, events, k, landing)
    events.append(TrackEvent(k, lo.t, "fold", tuple(c + 1 for c in lo.cables), lo))
    if landing is None:
        raise _Stop(f"fold at t = {lo.t:.12g}: no landing found ({why})")
    if not landing.stable:
        raise _Stop(f"fold at t = {lo.t:.12g}: the landing found is not stable ({landing.hessian})")
    events.append(TrackEvent(k, lo.t, "jump", landing.taut, lo, landing=landing,
                             energy_released=lo.potential(robot) - landing.potential(robot)))
    return landing


def _new_taut_set(robot, events, k, lo, cables, what):
    """The equilibrium of the taut set ``cables`` at the event state ``lo`` (Newton from its pose and tensions),
    checked by :func:`_checked`."""
    lam = lo.tensions[list(cables)] / lo.lengths[list(cables)]
    x, ok, resid, _ = branch.newton(robot, cables, lo.lengths, branch.unknowns(lo.position, lo.rotation, lam))
    if not ok:
        raise _Stop(_singular(events, k, lo, f"Newton does not converge after the cable {what}"))
    return _checked(robot, events, k, branch.state(robot, cables, lo.lengths, x, lo.t, resid))


def _checked(robot, events, k, st):
    """A state after a change of taut set must be an admissible, stable equilibrium (else the robot jumps)."""
    if branch.wrench_condition(robot, st) < WRENCH_RANK_TOL:
        raise _Stop(_singular(events, k, st, "the taut cables' wrench matrix lost rank"))
    if st.stable and np.all(st.tensions >= -ADMISSIBLE_TOL * robot.load) \
            and np.all(branch.slack_margins(robot, st) >= -ADMISSIBLE_TOL * robot.size):
        return st
    landing, why = land(robot, st, st.lengths, st.t)
    if landing is None or not landing.stable:
        raise _Stop(f"at t = {st.t:.12g} the new taut set {list(st.taut)} is not a stable admissible equilibrium and "
                    f"no stable landing was found ({why or landing.hessian})")
    events.append(TrackEvent(k, st.t, "jump", landing.taut, st, landing=landing,
                             energy_released=st.potential(robot) - landing.potential(robot)))
    return landing


def _singular(events, k, st, why):
    events.append(TrackEvent(k, st.t, "singular", st.taut, st, note=why))
    return f"t = {st.t:.12g}: {why}"


def tracking_table(res: TrackResult, robot) -> str:
    """The states at the samples and at the events, in order of t, then a summary line."""
    from cdpr_algebra.report.tables import format_table

    rows = []
    items = [(s.t, 0, "", s) for s in res.steps] + [(e.t, 1, e.kind, e) for e in res.events]
    items.sort(key=lambda v: (v[0], v[1]))
    for t, is_event, kind, item in items:
        st = item.landing if is_event and item.landing is not None else (item.state if is_event else item)
        what = kind if is_event else ""
        if is_event and kind in ("slack", "taut"):
            what = f"{kind} {','.join(str(c) for c in item.cables)}"
        if is_event and kind == "jump":
            what = f"jump (releases {item.energy_released:.4g})"
        if is_event and kind == "singular":
            what = "singular"
        rows.append([f"{t:.10g}", what, " ".join(f"{v:.5g}" for v in st.lengths), str(list(st.taut)),
                     " ".join(f"{v:.4g}" for v in st.position), " ".join(f"{v:.4g}" for v in st.tensions),
                     "yes" if st.stable else f"no ({st.hessian})", f"{st.min_eigenvalue:.3g}"])
    table = format_table(["t", "event", "lengths", "taut", "position", "tensions", "stable", "min eig"], rows)
    counts = {k: sum(1 for e in res.events if e.kind == k) for k in KINDS}
    summary = (f"{res.status}: {len(res.steps)} of {len(res.samples)} samples, events "
               + ", ".join(f"{v} {k}" for k, v in counts.items() if v) if any(counts.values()) else
               f"{res.status}: {len(res.steps)} of {len(res.samples)} samples, no event")
    summary += f", {res.seconds:.3g} s" + (f"; stopped: {res.reason}" if res.reason else "")
    return f"{robot.name}: equilibrium tracked along the cable lengths\n{table}\n{summary}"

"""The DGP's table for people (seed 000 Tables 1-3 layout), its summary line, and why a subproblem is incomplete."""

from __future__ import annotations

from cdpr_algebra.model.rod_equations import BINARY

from .positive_dimensional import ROD

__all__ = ["dgp_table", "summary_line", "incompleteness"]


def _certified_label(s) -> str:
    if s.certificate is None:
        return "-"
    if s.certified:
        return "yes" if s.certificate.hessian == "proven" else "yes (H_r undecided)"
    return "boundary" if "boundary" in s.certificate.tension_signs else "no"


def dgp_table(result: DGPResult, n: int) -> str:
    """Seed 000 Tables 1-3 layout: Conf., m, position of O', angles, tensions, H_r class."""
    from cdpr_algebra.report.tables import format_table

    headers = ["conf", "m", "x_O'", "y_O'", "z_O'", "phi_x", "phi_y", "phi_z"] + [f"tau_{i + 1}" for i in range(n)] + ["H_r", "certified"]
    rows = []
    for k, s in enumerate(result.solutions):
        rows.append([str(k + 1), str(len(s.taut))] + [f"{v:.3f}" for v in s.position] + [f"{v:.3f}" for v in s.angles]
                    + [f"{v:.3f}" for v in s.tensions] + [s.hessian, _certified_label(s)])
    lines = [format_table(headers, rows)] if rows else ["no admissible equilibrium"]
    for k, s in enumerate(result.solutions):
        if s.found_by != "homotopy":
            lines.append(f"  #{k + 1} found by the {s.found_by} solver only (the homotopy's subproblem is incomplete)")
        if s.certificate is not None and not s.certified:
            lines.append(f"  #{k + 1} not certified: {s.certificate.reason}")
        for a in s.alternatives:
            lines.append(f"  #{k + 1} is also an equilibrium with taut cables {list(a.taut)}: tensions "
                         + " ".join(f"{v:.3f}" for v in a.tensions) + f", H_r {a.hessian}, certified {_certified_label(a)}")
    ms = sorted({len(s.taut) for s in result.subproblems})
    counts = ", ".join(f"{len(result.by_m(m))} with {m} taut" for m in reversed(ms))
    excluded = [s for s in result.subproblems if s.excluded is not None]
    skipped = sum(1 for s in result.subproblems if s.skipped) - len(excluded)
    ncert = sum(1 for s in result.solutions if s.certified)
    lines.append(f"{len(result.solutions)} admissible equilibria ({counts}), {len(result.stable)} stable, "
                 f"{ncert} certified; {len(result.subproblems)} subproblems ({skipped} skipped"
                 + (f", {len(excluded)} not tracked" if excluded else "") + f"); {result.seconds:.2f} s")
    if excluded:
        lines.append(f"  not tracked, {len(excluded)} taut set(s) the interval filter proves to hold no admissible "
                     f"equilibrium (every box of the domain excluded; their inadmissible solutions not counted): "
                     + ", ".join(str(list(s.taut)) for s in excluded))
    for s in result.subproblems:
        for f in s.family.members if s.family is not None else ():
            method = s.family.method + (", the robot read in decimal" if s.family.reading != BINARY else "")
            lines.append("  " + f.describe(s.family.fixed, method))
    for s in result.subproblems:
        if s.collinear_anchors is not None:
            lines.append(f"  {list(s.taut)}: taut anchors on one line, G off it: tracked from that subfamily's generic set "
                         f"({s.generic_count} paths)"
                         + (", the robot read in decimal" if s.collinear_anchors != BINARY else ""))
        if s.parallelogram is not None:
            a, b, c, d = s.parallelogram
            where = {"centred": "the anchors' centred on G", "off_centre": "G off the anchors' centre",
                     "squares": "both squares, G off the plate's axis",
                     "squares_axis": "both squares, G on the plate's axis"}.get(s.parallelogram_kind, "")
            lines.append(f"  {list(s.taut)}: exit points and platform anchors two parallelograms (diagonals {a}-{c} and "
                         f"{b}-{d}), {where}: tracked from that subfamily's generic set ({s.generic_count} paths)")
    for s in result.subproblems:
        if s.excluded is not None:
            continue
        if s.skipped:
            lines.append(f"  skipped {list(s.taut)}: {s.skipped}")
        elif not s.complete:
            lines.append(f"  incomplete {list(s.taut)}: {incompleteness(s)}"
                         + (f"; admissible set settled by {s.settled}" if s.settled else ""))
    lines.append(summary_line(result))
    return "\n".join(lines)


def summary_line(result: DGPResult) -> str:
    """Paths, finite, real, admissible, at infinity, singular, failed over all subproblems, and completeness."""
    o = result.outcomes()
    subs = result.subproblems
    paths = sum(s.paths for s in subs)
    verdict = "complete" if result.complete else f"INCOMPLETE: {len(result.incomplete)} subproblem(s)"
    settled = sum(1 for s in result.incomplete if s.settled)
    if settled:
        verdict += (f", the admissible equilibria of {settled} of them proven by interval branch and prune"
                    + ("; every admissible equilibrium known" if result.admissible_complete else ""))
    cert = sum(s.certified or 0 for s in subs)
    cert_real = sum(s.certified_real or 0 for s in subs)
    excluded = sum(1 for s in subs if s.excluded is not None)
    families = result.families
    return (f"paths {paths}: {o['regular']} regular, {o['singular']} singular, {o['at_infinity']} at infinity, "
            f"{o['failed']} failed; {sum(s.finite for s in subs)} finite ({cert} certified distinct roots, "
            f"{cert_real} of them proven real), {sum(s.real for s in subs)} real, "
            f"{sum(s.admissible for s in subs)} admissible"
            + (f" and {len(families)} admissible famil{'y' if len(families) == 1 else 'ies'} of equilibria (not "
               f"isolated; {sum(f.certified for f in families)} of their listed poses certified)" if families else "")
            + (f" ({excluded} taut set(s) not tracked: no admissible equilibrium, interval proof)" if excluded else "")
            + f"; {verdict}")


def incompleteness(sub: DGPSubproblem) -> str:
    """Why a subproblem is not complete, in words (failed paths per reason, uncertified endpoints, counts)."""
    if sub.skipped:
        return sub.skipped
    parts = []
    if sub.failed_paths:
        why = ", ".join(f"{v} {k.replace('_', ' ')}" for k, v in sorted(sub.failures.items()))
        parts.append(f"{sub.failed_paths} of {sub.paths} paths failed ({why})")
    if sub.uncertified and (sub.family is None or sub.family.method == ROD
                            or sub.family.endpoints < sum(sub.uncertified.values())):
        why = "; ".join(f"{v}: {k}" for k, v in sorted(sub.uncertified.items()))
        parts.append(f"{sum(sub.uncertified.values())} regular endpoint(s) not certified ({why})")
    if sub.family is not None:  # the certificates refuse points of a positive-dimensional set: its account says why
        parts.append(sub.family.describe())
    if sub.certified is None and sub.paths:
        parts.append("endpoints not certified")
    if sub.generic_count is not None and sum(sub.outcomes.values()) != sub.generic_count:
        parts.append(f"outcomes add up to {sum(sub.outcomes.values())}, not the generic count {sub.generic_count}")
    return "; ".join(parts) or "not complete"

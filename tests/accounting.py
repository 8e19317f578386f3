"""The completeness rule of a DGP subproblem (issue 15, items 2 and 4), stated once for the tests."""


def expected_complete(sub) -> bool:
    """No failed path, outcomes adding up to the generic count, and every regular endpoint certified distinct
    (no certification: pruned or solved analytically)."""
    return sub.accounted and (sub.certified is None or (sub.certified == sub.outcomes["regular"] and not sub.uncertified))

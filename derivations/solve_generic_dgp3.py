"""Compute and store the generic solution set of the 3-cable DGP family of the homotopy tests and benchmarks
(:func:`cdpr_algebra.homotopy.families.dgp3_family`: cable points B_i and lam_i, 12 unknowns, 156 solutions).

Re-runnable, NOT a ``derive_*.py`` (monodromy is randomized and takes a minute, so it is not part of
tests/test_derivations.py):

    python derivations/solve_generic_dgp3.py        # writes cdpr_algebra/data/dgp3_generic.json

Method: a seed point near seed 000 Test 1's equilibria with complex noise, parameters found from it by
monodromy_solve's minimum-norm fit to a noisy copy of Test 1's parameters, monodromy loops until the solution
count is stable (MonodromyOptions defaults); the count must equal 156 (the published generic count, seed 000
and ../shared/PEERS.md), otherwise nothing is written.  tests/test_homotopy.py checks the stored file
(residuals, count, the parameter homotopy to Test 1 reproducing Table 1).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from cdpr_algebra.dgp.anchor_points import dgp3_family, dgp3_parameters  # noqa: E402
from cdpr_algebra.homotopy.monodromy import MonodromyOptions, monodromy_solve, save_instance  # noqa: E402
from cdpr_algebra.model.robot import load_robot  # noqa: E402

DATA = ROOT / "cdpr_algebra" / "data" / "dgp3_generic.json"
ROBOT = ROOT / "examples" / "seed000_test1.toml"
GENERIC_COUNT = 156


def regenerate(seed: int = 7, path: Path = DATA) -> int:
    S = dgp3_family()
    pr = dgp3_parameters(load_robot(ROBOT))
    rng = np.random.default_rng(2024)
    B = np.array([[3.5, 4, 5.5], [2.5, 4.5, 5.5], [2.5, 3.5, 5.5]]) + 0.3 * (rng.normal(size=(3, 3)) + 1j * rng.normal(size=(3, 3)))
    x0 = np.concatenate([B.ravel(), 0.05 + 0.02 * (rng.normal(size=3) + 1j * rng.normal(size=3))])
    pg = pr + 0.2 * (1 + abs(pr)) * (rng.normal(size=21) + 1j * rng.normal(size=21))
    r = monodromy_solve(S, seed=seed, options=MonodromyOptions(), p_guess=pg, x0=x0)
    print(r.summary_line())
    if len(r.solutions) != GENERIC_COUNT:
        print(f"{len(r.solutions)} solutions, expected {GENERIC_COUNT}: NOT stored")
        return 1
    save_instance(path, S, r.parameters, r.solutions,
                  generated_by=f"derivations/solve_generic_dgp3.py (monodromy_solve seed {seed})",
                  generic_count=GENERIC_COUNT)
    print(f"stored {path}")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=7)
    return regenerate(ap.parse_args(argv).seed)


if __name__ == "__main__":
    raise SystemExit(main())

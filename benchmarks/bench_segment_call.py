"""The fixed cost of one call of the compiled tracker (:func:`cdpr_algebra.homotopy.compiled.track_segment_compiled`):
the DGP's endgame and detours call it thousands of times with few paths (seed 002's serial DGP: 15,677 calls), so
what a call costs besides its steps counts.  Run by hand: ``python -m benchmarks.bench_segment_call`` (median of 5
rounds of 2000 calls of a short segment of the 3-cable system, with 1 and 20 paths)."""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from timing import machine, run_times, spread  # noqa: E402


def main():
    from cdpr_algebra.dgp.solve import _generic, fast_family
    from cdpr_algebra.homotopy.compiled import track_segment_compiled
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    print(machine())
    p, X = _generic(3)
    rng = np.random.default_rng(1)
    h = ParameterHomotopy(fast_family(3), p, p + 0.01 * (rng.normal(size=p.shape) + 1j * rng.normal(size=p.shape)))
    o = TrackerOptions()
    calls = 2000
    for n in (1, 20):
        def batch():
            for _ in range(calls):
                track_segment_compiled(h, X[:n], 1.0, 0.9999, o)

        times = run_times(batch, 5)
        print(f"{n:2d} path(s), a 1e-4 segment: {spread(times, 'us', 1e6 / calls)} per call")


if __name__ == "__main__":
    main()

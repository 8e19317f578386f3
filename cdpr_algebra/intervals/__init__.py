"""Generic rigorous arithmetic: outward-rounded interval arrays, arb balls, Krawczyk tests (imports nothing else of the package)."""

"""Comparison of two independent solvers of the DGP, taut set by taut set."""

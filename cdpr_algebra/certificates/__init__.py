"""Interval certificates of equilibria: existence and uniqueness of roots, tension signs, stability class."""

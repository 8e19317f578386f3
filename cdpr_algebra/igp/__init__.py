"""Inverse geometrico-static problem of 3-cable robots (Carricato 2013): assigned orientation, assigned position."""

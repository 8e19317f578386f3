"""Interval branch-and-prune solver of the DGP (Berti, Merlet and Carricato 2016, Sec. 4), independent of dgp/."""

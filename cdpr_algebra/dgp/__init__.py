"""Direct geometrico-static problem of n-cable robots by parameter homotopies (Berti, Merlet and Carricato 2016)."""

"""Interval branch-and-prune DGP solver (Berti, Merlet and Carricato 2016): an independent, complete method
that finds every admissible equilibrium (real, tensions >= 0, other cables slack) of each set of taut cables.

Everything rests on the outward-rounded arithmetic of :mod:`cdpr_algebra.intervals.arithmetic`: boxes are processed in batches
(arrays of lower / upper bounds of shape (nboxes, ncols)), and every exclusion, every contraction and every
existence-and-uniqueness proof is rigorous.  The filter and the second-order operator, where the time goes, run
box by box in compiled kernels (numba; ``BPOptions.kernels = "compiled"``, the default) made of the scalar twins of the
vectorized interval operations (same bounds, bit for bit), with each projection applied at once and the work on a
box stopped as soon as it is empty; ``"numpy"`` keeps the vectorized operators as the reference (tests
compare the two).  Seed 000 Test 3, profiled: 942 s vectorized, of which the filter 64 % and the second-order
operator 33 %; each kernel is 3-6 times faster than its vectorized form.

**Equation sets (Sec. 3), tensions as unknowns.**  lam_i = tau_i / rho_i (tensions scaled by the constant 1/rho_i).

* m = 1 (Sec. 3.2): B_i = A_i + rho_i d and G on the vertical through B_i (G below or above, tension Q > 0);
  the platform turns freely about the cable.  Instead of Algorithm 2 (a float test of each slack cable alone), the
  turning angle is searched by interval bisection in two rational charts t = tan(theta / 2) of the circle, where
  every other cable must satisfy |B_j - A_j| <= rho_j (an equilibrium is proven when an interval of t satisfies all
  of them strictly, excluded when one is violated over every t).
* m = 2 (Sec. 3.3): the frame turned about the load so that A_i, A_j and the load lie in the plane y = 0; unknowns
  (x, z) of B_i, B_j, G and lam: 8 equations (eqs. 10-12: three distances, two lengths, force x, force z, moment y).
* m >= 3 (Secs. 3.4-3.6): l = 3 reference points (the taut anchors are coplanar; other platform points by eq. 18, or
  eq. 17 with the cross product n = b12 x b13 when off the plane) or l = 4 (eq. 19), the reference points among the
  taut anchors; unknowns the 3l coordinates and the m lam: m lengths (eqs. 14, 20, 21), C(l, 2) distances (eqs. 13,
  22) and 6 statics equations (eq. 5, moments about a fixed pole P0), 3l + m equations.  With l = 4 the six
  distances also admit the mirror image of the platform, rejected on the verified enclosure by the sign of
  det(b12, b13, b14).  m = 6 keeps lam as unknowns (the paper drops them; an implementation choice).

**Initial search domain (Sec. 4.1).**  Each anchor in the box of its sphere (taut: |B_i - A_i| = rho_i) or ball
(slack: <= rho_i), every platform point P within rho_j + d_Pj of every A_j; lam_i in [0, +inf).  The refined bounds
of Fig. 5 and the tension bound of eq. 26 are then produced by the same 2B contraction run on the initial box:
the force balance along the load, lam_i (B_i - A_i).d <= Q - ..., bounds lam_i exactly as eq. 26 whenever the box
is suspended ((B_i - A_i).d > 0); otherwise the statics filter bounds them (the paper's non-suspended case).

**Filter operator (Sec. 4.3)**: the geometric contractors iterated while the pose shrinks by more than 10 %
(``max_sweeps``), then the statics ones, which narrow only the tensions (``filter_order = 1``; ``0``: all of them
iterated, the vectorized order):

* 2B / HC4 on the geometric constraints: the spheres of the taut anchors (eqs. 14, 20, 21), the distances between
  all platform points (reference and secondary, eqs. 13, 22), the inequalities of eqs. 31-32 (every platform point
  P and cable j: (rho_j - d_Pj)^2 <= |P - A_j|^2 <= (rho_j + d_Pj)^2 if j is taut, |P - A_j| <= rho_j + d_Pj and
  |B_j - A_j| <= rho_j if j is slack), the secondary points by eqs. 17-19 both ways, n = b12 x b13 with |n| constant
  and n . b12 = n . b13 = 0 (the constant products of eq. 33).
* statics: 2B (exclusion and projection onto lam) on the force rows (x, y, z and along the load), the moment rows
  about P0, about each taut exit point A_j (cable j drops out) and about each axis A_j A_k (cables j, k drop out: the
  sign of one cable's term is fixed by the load's), repeated while a lam shrinks by 10 %; then the interval Gauss
  elimination of K J lam = -K Q L_e (eqs. 34-35) with the generalized inverse K = (W^T mid J)^-1 W^T of eq. 37 (the
  length-scaled pseudoinverse where W^T J is singular, e.g. m = 2, whose force and moment rows do not pair), its
  entries written with single occurrences of the pose (J is affine in each anchor), followed by one Gauss-Seidel
  step.  The Plucker-constrained optimization of C (eqs. 39-42) is not done.

**Evaluation operator with unicity test (Sec. 4.2).**  Every equation set is quadratic (seed 000's remark, which
makes its Kantorovich constant p fixed), so F(x) = F(y) + J(y)(x - y) + (1/2) Q(x - y) holds exactly with constant
Hessians (:class:`cdpr_algebra.intervals.arithmetic.QuadraticSystem`).  On every bounded box the operator
T(X) = y - C F(y) - (C J(y) - I)(X - y) - C (1/2) Q(X - y), C = mid J(y)^-1, excludes the box (T(X) cap X empty) or
contracts it (X cap T(X)); it plays the role of the gradient-based evaluation and interval Newton filtering of
ALIAS's Solve_General_Gradient_Interval and is about twice as tight as the Krawczyk operator.  On boxes narrower
than ``krawczyk_width`` the Krawczyk operator K(X) proves a unique solution (K(X) in the interior of X) -- it
replaces the Kantorovich test.  It is tried where T(X) lies in the interior of X (``unicity_gate``; Brouwer: X holds a
solution), elsewhere it would hardly ever succeed and the box is bisected.  A box where Newton converges is also
tried inflated around the Newton point (epsilon-inflation); a box inside a proven box is discarded (its only
solution is already counted); two proven boxes are the same solution when one's enclosure lies in the other
(uniqueness), so nothing is counted twice.

**Bisection**: the widest pose variable (lengths) until every pose width is below ``eps`` (relative to the robot
size), then the widest variable overall (lam scaled by Q / size).  Boxes that reach ``eps`` undecided are
reported (:class:`UndecidedBox`), never dropped: the result is complete -- every admissible equilibrium lies in a
proven solution box or in an undecided box.  A proven solution whose enclosure straddles a domain boundary
(a tension interval containing 0, a slack cable exactly at its length, an undecided mirror sign) is reported as
undecided as well (it is an equilibrium of a smaller taut set or a degenerate one).


Modules: :mod:`.model` (equation sets and search domain of one taut set), :mod:`.contractors` (filter operator,
vectorized reference), :mod:`.kernels` (the same, compiled box by box), :mod:`.codac_filter` (the same on Codac 2's
contractors, ``kernels="codac"``: 60-200 times slower, kept for the comparison), :mod:`.precondition` (the
generalized inverse of eq. 37), :mod:`.search` (branch and prune, every taut set; :func:`.search.excluded_by_filter`,
the short filter-only search by which the DGP excludes a taut set), :mod:`.one_cable` (m = 1), :mod:`.results`
(options and results).  Independent of :mod:`cdpr_algebra.dgp`.
"""

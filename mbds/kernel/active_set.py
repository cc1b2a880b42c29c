"""A guessed active set for the impact LCPs (the form of mbds.kernel.contact_problem.build_matrix),
tried before Lemke's method.

Each contact of an LCP is in one of six states. Three have a normal force: PRESSED (a stick
candidate then sticks), SLIDE_POS (sliding with gT' > 0: lambda_T = -mu lambda_N) and SLIDE_NEG
(gT' < 0: lambda_T = +mu lambda_N); OPEN has none (nor a tangential reserve; a slip rate where
its tangential row needs one). The expansion LCP of an impact starts from impulses already in
the cone (the third block of q, 2 mu Lambda_N, is positive), so a contact without a normal
increment may still hold a tangential one: OPEN_STICK (its reserve lambda_0R an unknown, the
contact sticks) and OPEN_NEG (its reserve at the cone's far end, lambda_0R = q_L, sliding
backwards). Given the states, the LCP reduces to a linear system over the normal forces of the
pressed contacts and the tangential reserves lambda_0R of the sticking ones (rows gN'' = 0 and
gT''^+ = 0 of those contacts); the slip rates gT''^- of SLIDE_NEG, OPEN_NEG and of open contacts
that move backwards follow from their own rows. If the solution is feasible, the full LCP
vector z is assembled and must pass Lemke's solution check (mbds.kernel.lcp.check_solution) on
the original data: only a solution of the same LCP is accepted. Otherwise the infeasible
contacts change state (a negative normal force opens, an approaching open contact is pressed, a
tangential reserve outside its cone slides, a slip against its direction sticks) for at most
``rounds`` rounds; then the caller falls back to lexicographic Lemke.

The states come from a memory of the last solved LCP of the same family (the compression or the
expansion phase of impacts), matched contact by contact by vertex and edge; contacts not in it
are pressed where their free normal rate is negative. After each solve the states of its
solution are remembered.
"""

from __future__ import annotations

from mbds.kernel.jit import jit
from mbds.kernel.lcp import absmax, add_columns, check_solution, failed_rows
from mbds.kernel.linalg import gauss_solve

OPEN = 0
PRESSED = 1
SLIDE_POS = 2
SLIDE_NEG = 3
OPEN_STICK = 4
OPEN_NEG = 5
AT_BOUND = 1e-9
"""A reserve lambda_0L below AT_BOUND times lambda_0R counts as zero when states are remembered
(it is computed as A z + q, so an exact zero comes out as round-off)."""


@jit(refcount=False)
def recall_states(active, na, vertex, edge, memory, count, bvec, state):
    """state[a] of each contact active[a] from memory[:count] (rows: vertex, edge, state);
    contacts not remembered are PRESSED where bvec[a] (their free normal rate) is negative."""
    for a in range(na):
        c = active[a]
        s = PRESSED if bvec[a] < 0.0 else OPEN
        for k in range(count):
            if memory[k, 0] == vertex[c] and memory[k, 1] == edge[c]:
                s = memory[k, 2]
                break
        state[a] = s


@jit(refcount=False)
def remember_states(active, na, nh, hrow, vertex, edge, z, w, memory):
    """Store the states of the solution z, w of an LCP over the contacts active[:na] (nh stick
    candidates at hrow) in memory[:na] (rows: vertex, edge, state).

    A pressed stick candidate whose reserve lambda_0R is exactly 0 (non-basic in Lemke's answer)
    is remembered as sliding forwards, one whose other reserve lambda_0L (w) is zero (AT_BOUND) as
    sliding backwards (OPEN_NEG without a normal increment), even where it does not slip: two
    sticking contacts of one body on one line make the system of the states singular, one of them
    at a bound of the cone does not."""
    g = 0
    for a in range(na):
        c = active[a]
        s = PRESSED if z[a] > 0.0 else OPEN
        if g < nh and hrow[g] == a:
            at_far_end = z[na + nh + g] > 0.0 or w[na + nh + g] <= AT_BOUND * z[na + g]
            if s == PRESSED:
                if at_far_end:
                    s = SLIDE_NEG
                elif z[na + g] == 0.0:
                    s = SLIDE_POS
            elif z[na + g] > 0.0:  # no normal increment, a tangential reserve (expansion)
                s = OPEN_NEG if at_far_end else OPEN_STICK
            g += 1
        memory[a, 0] = vertex[c]
        memory[a, 1] = edge[c]
        memory[a, 2] = s


@jit(refcount=False)
def solve_states(A, q, z, w, na, nh, hrow, state, rounds, tol_piv, tol_lex, max_pivots, fwork, iwork):
    """Solve the LCP (A, q) of size m = na + 2 nh from the contact states ``state`` (see the
    module doc); return True when z, w hold a verified solution (state then holds its states).

    A system of k unknowns is tried only when Lemke's method could reach that basis within
    max_pivots (at least k + 1 pivots), so the pivot limit bounds both paths alike.

    fwork, iwork: from mbds.kernel.lcp.lcp_workspace of any size >= m.
    """
    m = na + 2 * nh
    candidate = iwork[:na]  # index g of each contact's stick candidate rows, -1 if none
    var = iwork[na : 2 * na + nh]  # the unknowns of the system: a (lambda_N) or na + g (lambda_0R)
    zlist = iwork[2 * na + nh : 2 * na + nh + m]
    x = fwork[m * m : m * m + m]
    msum = fwork[m * m + m : m * m + 2 * m]
    for a in range(na):
        candidate[a] = -1
    for g in range(nh):
        candidate[hrow[g]] = g
    for _ in range(rounds + 1):
        k = 0
        for a in range(na):
            if _pressed(state[a]):
                var[k] = a
                k += 1
        for g in range(nh):
            if state[hrow[g]] == PRESSED or state[hrow[g]] == OPEN_STICK:
                var[k] = na + g
                k += 1
        if k + 1 > max_pivots:
            return False
        S = fwork[: k * k].reshape((k, k))
        for r in range(k):
            row = var[r]
            x[r] = -q[row]
            for g in range(nh):  # OPEN_NEG: a known reserve lambda_0R = q_L
                if state[hrow[g]] == OPEN_NEG:
                    x[r] -= A[row, na + g] * q[na + nh + g]
            for c in range(k):
                v = var[c]
                S[r, c] = A[row, v]
                if v < na and candidate[v] >= 0 and state[v] == SLIDE_NEG:
                    # row gamma_0L = 0: lambda_0R = A[L, a] lambda_N + q[L]
                    low = na + nh + candidate[v]
                    S[r, c] += A[low, v] * A[row, na + candidate[v]]
                    x[r] -= A[row, na + candidate[v]] * q[low]
        if not gauss_solve(S, x, k, tol_piv):
            return False
        for i in range(m):
            z[i] = 0.0
        nz = 0
        for r in range(k):
            z[var[r]] = x[r]
            zlist[nz] = var[r]
            nz += 1
        for g in range(nh):
            a = hrow[g]
            if state[a] == SLIDE_NEG or state[a] == OPEN_NEG:
                z[na + g] = A[na + nh + g, a] * z[a] + q[na + nh + g]
                zlist[nz] = na + g
                nz += 1
        for i in range(m):  # w = A z + q without the slip rates
            w[i] = q[i]
            msum[i] = 0.0
        add_columns(A, z, w, zlist, 0, nz, msum)
        unknowns = nz
        for g in range(nh):  # slip rates gT''^-: only their own row gT''^+ holds them
            a = hrow[g]
            if state[a] == SLIDE_NEG or state[a] == OPEN_NEG or (state[a] == OPEN and w[na + g] < 0.0):
                z[na + nh + g] = -w[na + g]
                zlist[nz] = na + nh + g
                nz += 1
        if _restate(z, w, q, msum, na, nh, candidate, state, tol_lex):
            continue
        kept = True
        for a in range(nz):
            if z[zlist[a]] < 0.0:
                z[zlist[a]] = 0.0
                kept = kept and a >= unknowns
        if not kept:  # Lemke's solution check on the point as it is
            return check_solution(A, q, tol_lex, z, w, zlist, nz, msum) == 0
        add_columns(A, z, w, zlist, unknowns, nz, msum)  # (the sums over the unknowns' columns stand)
        return failed_rows(q, tol_lex, z, w, zlist, nz, msum) == 0
    return False


@jit(refcount=False)
def _restate(z, w, q, msum, na, nh, candidate, state, tol_lex):
    """Change the states of the contacts whose point z (w: A z + q before the slip rates) is
    infeasible beyond tol_lex, measured as in Lemke's solution check: an entry of z relative to
    the largest entry of z, a row of w (and the slip rate it holds) relative to
    |q|_max + |z|_max msum (msum: the sums of |A| over the columns of the nonzeros of z, from
    mbds.kernel.lcp.check_solution), so that a row the check accepts does not change a state; a
    sticking contact outside Coulomb's cone by any amount changes. Returns whether any changed."""
    scale = absmax(z)
    tol = tol_lex * scale
    qnorm = absmax(q)
    changed = False
    for a in range(na):
        g = candidate[a]
        s = state[a]
        new = s
        if not _pressed(s) and w[a] < -_row_tolerance(tol_lex, qnorm, scale, msum, a):  # an open contact approaches
            new = SLIDE_NEG if s == OPEN_NEG else PRESSED
        elif _pressed(s) and z[a] < -tol:
            new = OPEN
        elif g >= 0:
            row_tol = _row_tolerance(tol_lex, qnorm, scale, msum, na + g)  # of gT''^+ and the slip rate it holds
            reserve, far, slip = z[na + g], w[na + nh + g], z[na + nh + g]
            # the cone is kept exactly: no friction beyond it, none at mu = 0
            if s == PRESSED or s == OPEN_STICK:
                if reserve < 0.0:  # the reserve lambda_0R below 0
                    new = SLIDE_POS if s == PRESSED else OPEN
                elif far < 0.0:  # above the cone's far end
                    new = SLIDE_NEG if s == PRESSED else OPEN_NEG
            elif s == SLIDE_POS:
                if w[na + g] < -row_tol:
                    new = PRESSED
            elif s == OPEN:
                # slips backwards while its reserve is inside the cone
                if slip > 0.0 and far > _row_tolerance(tol_lex, qnorm, scale, msum, na + nh + g):
                    new = OPEN_NEG
            elif slip < -row_tol:  # SLIDE_NEG, OPEN_NEG: a slip against the direction sticks
                new = PRESSED if s == SLIDE_NEG else OPEN_STICK
        if new != s:
            state[a] = new
            changed = True
    return changed


@jit(inline="always")
def _row_tolerance(tol_lex, qnorm, scale, msum, i):
    """The tolerance of row i of w in Lemke's solution check: tol_lex (|q|_max + |z|_max msum[i])."""
    return tol_lex * (qnorm + scale * msum[i])


@jit(inline="always")
def _pressed(s):
    """Whether contact state s has a normal force (its normal row is an equation)."""
    return s == PRESSED or s == SLIDE_POS or s == SLIDE_NEG

"""Independent groups of contacts: the LCPs of contacts that no mass couples are solved apart.

Two contacts are coupled when a force at one changes the relative acceleration (or, at an
impact, the relative velocity) of the other: when row W of one and row Y = M^-1 W of the
other share a nonzero column. The matrix of a contact LCP (mbds.kernel.contact_problem) then
has exact zeros between groups of contacts that are not coupled, directly or through others,
so its solutions are those of the groups' own LCPs taken together. Five balls resting on a
driven floor are five LCPs of one or two contacts each, not one LCP of up to ten.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit


@jit(inline="always")
def split_components(active, na, WN, WT, YN, YT, group, root, grouped, masks):
    """Reorder the contacts active[:na] (rows of WN, WT and of YN, YT = M^-1 W) so that each
    group of coupled contacts is contiguous, group g at active[group[g]:group[g + 1]]; return
    the number of groups. Groups come in the order of their first contact, and contacts keep
    their order within a group. root, grouped: int64 scratch of at least na entries; masks:
    uint64 scratch (2, na or more, ceil(n / 64)) for the nonzero columns of each W and Y row."""
    words = masks.shape[2]
    for a in range(na):
        root[a] = a
        for j in range(words):
            masks[0, a, j] = 0
            masks[1, a, j] = 0
        c = active[a]
        for k in range(WN.shape[1]):
            bit = np.uint64(1) << np.uint64(k % 64)
            if WN[c, k] != 0.0 or WT[c, k] != 0.0:
                masks[0, a, k // 64] |= bit
            if YN[c, k] != 0.0 or YT[c, k] != 0.0:
                masks[1, a, k // 64] |= bit
    for a in range(na):
        for b in range(a + 1, na):
            ra = _root(root, a)
            rb = _root(root, b)
            if ra != rb and _couples(masks, a, b):
                root[max(ra, rb)] = min(ra, rb)  # a root is the first contact of its group
    for a in range(na):
        root[a] = _root(root, a)
    ng = 0
    k = 0
    for a in range(na):
        if root[a] == a:
            group[ng] = k
            ng += 1
            for b in range(a, na):
                if root[b] == a:
                    grouped[k] = active[b]
                    k += 1
    group[ng] = na
    for a in range(na):
        active[a] = grouped[a]
    return ng


@jit(inline="always")
def _root(root, a):
    """The root of a's group (halving the path on the way)."""
    while root[a] != a:
        root[a] = root[root[a]]
        a = root[a]
    return a


@jit(inline="always")
def _couples(masks, a, b):
    """Whether a force at one of the contacts a, b moves the other: the W row of one and the Y
    row of the other share a nonzero column."""
    for j in range(masks.shape[2]):
        if (masks[0, a, j] & masks[1, b, j]) != 0 or (masks[0, b, j] & masks[1, a, j]) != 0:
            return True
    return False

"""User forces written in Python (for the API hook test): a spring of stiffness fields[0, 0]
(N/m) pulling body 1 to the origin, as a plain function and as a numba-compiled one."""

import numba


def spring_to_origin(t, r, p, r_d, p_d, A, rP, rP_d, sP, fields, state, f, n):
    f[0, 0] -= fields[0, 0] * r[0, 0]
    f[0, 1] -= fields[0, 0] * r[0, 1]


@numba.njit
def compiled_spring_to_origin(t, r, p, r_d, p_d, A, rP, rP_d, sP, fields, state, f, n):
    f[0, :] -= fields[0, 0] * r[0, :]

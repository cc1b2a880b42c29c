"""DAP_BC's driver functions f(t) (manual Table B.6; the book's Eqs. 8.1-8.3) evaluated from a
table whose rows are: type code (FUNCT_TYPES), t_start, f_start, t_end, f_end (s and the
function's unit), then the coefficients c1..c4 that mbds.model.dapbc.functs computes."""

from __future__ import annotations

from mbds.kernel.jit import jit

FUNCT_TYPES = {"a": 0, "b": 1, "c": 2}
FUNCT_COLUMNS = 9


@jit
def _poly_c(row, tau):
    c1, c2, c3, c4 = row[5], row[6], row[7], row[8]
    return (c1 + tau ** 4 * (c2 + tau * (c3 + tau * c4)),
            tau ** 3 * (4 * c2 + tau * (5 * c3 + 6 * tau * c4)),
            tau ** 2 * (12 * c2 + tau * (20 * c3 + 30 * tau * c4)))


@jit
def funct_value(row, t):
    """(f, f', f'') of one function at time t (s)."""
    kind, t_start, f_start, t_end, f_end = int(row[0]), row[1], row[2], row[3], row[4]
    if kind == 0:
        return row[5] + t * (row[6] + t * row[7]), row[6] + 2.0 * t * row[7], 2.0 * row[7]
    tau = t - t_start
    if tau <= 0.0:
        return f_start, 0.0, 0.0
    span = t_end - t_start
    if kind == 1:
        if tau >= span:
            return f_end, 0.0, 0.0
        c1, c2, c3 = row[5], row[6], row[7]
        return (f_start + tau ** 3 * (c1 + tau * (c2 + tau * c3)),
                tau ** 2 * (3 * c1 + tau * (4 * c2 + 5 * tau * c3)),
                tau * (6 * c1 + tau * (12 * c2 + 20 * tau * c3)))
    if tau >= span:
        f_at_end, rate_at_end, _ = _poly_c(row, span)
        return f_at_end + rate_at_end * (tau - span), rate_at_end, 0.0
    return _poly_c(row, tau)


@jit
def funct_values(table, t, out):
    """out[k] = (f, f', f'') of every function of ``table`` at time t (s)."""
    for k in range(table.shape[0]):
        out[k, 0], out[k, 1], out[k, 2] = funct_value(table[k], t)

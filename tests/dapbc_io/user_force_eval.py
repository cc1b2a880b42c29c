"""Evaluating a compiled user force at a given state of a model (test helper)."""

from __future__ import annotations

import numpy as np

from mbds.io.dapbc.records import DapbcModel
from mbds.io.dapbc.user_force import force_field_table


def point_kinematics(model: DapbcModel, r, p, r_d, p_d):
    """A (nB,2,2), and sP, rP, rP_d (nP,2) of the points; the ground (body 0) at rest at the origin."""
    A = np.array([[[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]] for a in p])
    nP = len(model.points)
    sP, rP, rP_d = np.zeros((nP, 2)), np.zeros((nP, 2)), np.zeros((nP, 2))
    for j, point in enumerate(model.points):
        if point.Bindex == 0:
            rP[j] = point.sPlocal
            continue
        b = point.Bindex - 1
        sP[j] = A[b] @ point.sPlocal
        rP[j] = r[b] + sP[j]
        rP_d[j] = r_d[b] + p_d[b] * np.array([-sP[j, 1], sP[j, 0]])
    return A, sP, rP, rP_d


def evaluate(function, model: DapbcModel, r, p, r_d, p_d, state=None, f=None, n=None, t=0.0):
    """Call ``function`` with the model's state; returns (f, n, state) after the call."""
    r, r_d = np.array(r, float).reshape(-1, 2), np.array(r_d, float).reshape(-1, 2)
    p, p_d = np.array(p, float).reshape(-1), np.array(p_d, float).reshape(-1)
    A, sP, rP, rP_d = point_kinematics(model, r, p, r_d, p_d)
    f = np.zeros((model.nB, 2)) if f is None else np.array(f, float)
    n = np.zeros(model.nB) if n is None else np.array(n, float)
    state = np.zeros(4) if state is None else state
    function(t, r, p, r_d, p_d, A, rP, rP_d, sP, force_field_table(model.forces), state, f, n)
    return f, n, state

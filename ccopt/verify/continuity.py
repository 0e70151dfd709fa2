"""Continuity: jumps between consecutive tool segments, and tangent breaks.

A jump (in-plane and out-of-plane together) larger than ``eps`` fails the
check. Tangent breaks (direction changes at a joint, measured between the
last in-plane segment and the next one, skipping Z-only moves) are listed
for information: inside corners and lead-in diagonals have them by design
(a verifier decision, docs/compensation.md section 8.5: they are what the
controllers do, so they never fail the check).
"""
from __future__ import annotations

import math

import numpy as np

from ccopt.geometry.columns import take_rows
from ccopt.tolerances import POINT_EPS, VERIFY_TANGENT_BREAK
from ccopt.verify.certificate import EXACT, Check, Violation
from ccopt.verify.segments import Packed, end_tangents

#: Tangent breaks listed in the check's detail (the count covers all).
LISTED_BREAKS = 50


def check_continuity(tool: Packed, w0: np.ndarray, w1: np.ndarray, eps: float, lengths, info):
    """``w0``, ``w1``: out-of-plane coordinate at each segment's start and end."""
    A = tool.arr
    n = len(A)
    viol = []
    if n >= 2:
        d = A.p0[1:] - A.p1[:-1]
        jump = np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2 + (w0[1:] - w1[:-1]) ** 2)
        worst = float(jump.max())
        for i in np.flatnonzero(jump > eps):
            line, role = info(int(i) + 1)
            viol.append(Violation("gap", float(jump[i]), int(i) + 1, line, role, None, None,
                                  (float(A.p0[i + 1, 0]), float(A.p0[i + 1, 1])),
                                  None, EXACT,
                                  {"previous_end": [float(A.p1[i, 0]), float(A.p1[i, 1])]}))
    else:
        worst = 0.0
    # tangent breaks between consecutive in-plane segments
    ts, te = end_tangents(tool)
    moving = np.flatnonzero(lengths > POINT_EPS)
    breaks = []
    if moving.size >= 2:
        a, b = moving[:-1], moving[1:]
        te_a, ts_b = take_rows(te, a), take_rows(ts, b)
        cosang = np.clip(np.einsum("ij,ij->i", te_a, ts_b), -1.0, 1.0)
        cross = te_a[:, 0] * ts_b[:, 1] - te_a[:, 1] * ts_b[:, 0]
        ang = np.arctan2(np.abs(cross), cosang)
        idx = np.flatnonzero(ang > VERIFY_TANGENT_BREAK)
        for q in idx[:LISTED_BREAKS]:
            line, role = info(int(b[q]))
            breaks.append({"tool_segment": int(b[q]), "tool_block": line,
                           "angle_deg": math.degrees(float(ang[q])),
                           "at": [float(A.p0[b[q], 0]), float(A.p0[b[q], 1])]})
        nbreaks = int(idx.size)
    else:
        nbreaks = 0
    check = Check("continuity", not viol, worst, eps, EXACT, "length",
                  "consecutive tool segments meet within eps (figure: largest jump); "
                  "tangent breaks listed, not faults", max(n - 1, 0), len(viol),
                  {"tangent_breaks": nbreaks, "tangent_breaks_listed": breaks})
    return check, viol

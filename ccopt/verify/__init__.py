"""Verification: a certificate that the cutter radius offset holds.

``verify(toolpath, program, profile=None)`` returns a
:class:`~ccopt.verify.certificate.Certificate` with five checks, each with
its figure, tolerance and basis (exact / certified bound / sampled):

- ``gouge``: every tool position is at least ``r - eps`` from every contour
  element (:mod:`.clearance`, broad phase :mod:`.broadphase`, exact kernels of
  :mod:`ccopt.geometry.distance`, :mod:`.certified` bounds for spirals/curves);
- ``contact``: every steady tool segment stays within ``r + eps`` of its
  element, every corner arc of its corner point (:mod:`.contact`);
- ``side``: the tool is on the programmed side (:mod:`.side`);
- ``continuity``: no jump above ``eps``; tangent breaks listed (:mod:`.continuity`);
- ``limits``: axis velocity/acceleration and feed from a feed profile (:mod:`.limits`).

Which programmed elements are the contour, and the other choices the spec
leaves open, are documented in docs/compensation.md (section 8); those with a
real alternative are switches in :mod:`.decisions`. ``verify`` consumes a tool
path and a program and never compensates. Cross-checks (CVXPY, CasADi) are found as
``ccopt.crosschecks`` entry points (:mod:`.crosschecks`).
"""
from ccopt.verify.certificate import Certificate, Check, Violation
from ccopt.verify.contour import Contour, contour_of
from ccopt.verify.run import VerifyContext, verify

__all__ = ["Certificate", "Check", "Contour", "VerifyContext", "Violation", "contour_of", "verify"]

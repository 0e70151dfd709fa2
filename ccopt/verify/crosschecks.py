"""Cross-checks of a certificate by independent formulations, found as entry points.

A cross-check is any callable registered under the entry-point group
``ccopt.crosschecks`` (pyproject ``[project.entry-points."ccopt.crosschecks"]``).
ccopt never imports the ``formulations`` package; it finds them here with
:mod:`importlib.metadata`, so a researcher adds one in their own package.

Protocol: ``crosscheck(certificate) -> dict`` with at least ``name``,
``agree`` (bool: the formulation agrees with the certificate's figures) and
``summary`` (one line); it reads the geometry from ``certificate.context``
(:class:`ccopt.verify.run.VerifyContext`).
"""
from __future__ import annotations

from importlib.metadata import entry_points

GROUP = "ccopt.crosschecks"


def available() -> dict:
    """Registered cross-checks: name -> entry point."""
    return {ep.name: ep for ep in entry_points(group=GROUP)}


def run_crosschecks(certificate, names=None) -> list[dict]:
    """Run the registered cross-checks (all, or those in ``names``) on ``certificate``.

    A cross-check that cannot be loaded or raises is reported as not agreeing,
    with its error, rather than stopping the others.
    """
    out = []
    for name, ep in sorted(available().items()):
        if names is not None and name not in names:
            continue
        try:
            fn = ep.load()
            res = dict(fn(certificate))
        except Exception as exc:  # a broken plug-in must not hide the others
            res = {"agree": False, "summary": f"failed: {type(exc).__name__}: {exc}",
                   "error": f"{type(exc).__name__}: {exc}"}
        res.setdefault("name", name)
        res["agree"] = bool(res.get("agree", False))
        out.append(res)
    return out

"""toppra's names ccopt uses, imported without loading ``matplotlib.pyplot``.

toppra imports ``matplotlib.pyplot`` at module level (``toppra.algorithm``,
``toppra.parametrizer``) only for its plotting helpers, which ccopt never
calls; pyplot is about 0.3 s of the 0.7 s ``import toppra`` takes, paid by
every command that plans a feed. While toppra is imported here, a stand-in
module takes pyplot's place in ``sys.modules``; it leaves ``sys.modules``
right after, so anyone's later ``import matplotlib.pyplot`` loads the real
one, and the stand-in toppra keeps forwards every name to the real pyplot
(loaded then) should a toppra plotting helper ever run. Every ccopt module
takes its toppra names from here, so this always happens first.
"""
from __future__ import annotations

import importlib
import sys
import types

_PYPLOT = "matplotlib.pyplot"


class _PyplotOnFirstUse(types.ModuleType):
    """Stands for ``matplotlib.pyplot`` in toppra's namespace: the real module
    is imported when a name is first read from it."""

    def __getattr__(self, name: str):
        return getattr(importlib.import_module(_PYPLOT), name)


def _import_toppra() -> None:
    """Import toppra with the stand-in in place (unless pyplot is loaded already)."""
    if _PYPLOT in sys.modules or "toppra" in sys.modules:
        importlib.import_module("toppra")
        return
    stand_in = _PyplotOnFirstUse(_PYPLOT)
    sys.modules[_PYPLOT] = stand_in
    try:
        importlib.import_module("toppra")
    finally:
        if sys.modules.get(_PYPLOT) is stand_in:
            del sys.modules[_PYPLOT]


_import_toppra()

# from the toppra just imported (the point of this module)
from toppra.algorithm import TOPPRA  # noqa: E402
from toppra.algorithm.algorithm import ParameterizationReturnCode  # noqa: E402
from toppra.constraint import DiscretizationType, LinearConstraint  # noqa: E402
from toppra.interpolator import AbstractGeometricPath  # noqa: E402

__all__ = ["TOPPRA", "AbstractGeometricPath", "DiscretizationType", "LinearConstraint",
           "ParameterizationReturnCode"]

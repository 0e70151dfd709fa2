"""toppra's names ccopt uses, imported without loading ``matplotlib.pyplot``
or ``scipy.interpolate``.

toppra imports ``matplotlib.pyplot`` at module level (``toppra.algorithm``,
``toppra.parametrizer``) only for its plotting helpers, and names of
``scipy.interpolate`` (``toppra.interpolator``, ``toppra.simplepath``) only
for its own spline paths; ccopt never calls either. They are about 0.3 s
and 0.6 s of the 1.4 s ``import toppra`` takes, paid by every command that
plans a feed. While toppra is imported here, a stand-in module takes each
one's place in ``sys.modules``; it leaves ``sys.modules`` right after, so
anyone's later import loads the real module, and what toppra keeps of the
stand-ins forwards to the real module (loaded then) should toppra ever use
it: pyplot's names when read, scipy.interpolate's classes when called or
read from (toppra only calls them and their class methods, at run time).
Every ccopt module takes its toppra names from here, so this always happens
first.
"""
from __future__ import annotations

import importlib
import sys
import types

_PYPLOT = "matplotlib.pyplot"
_INTERPOLATE = "scipy.interpolate"


class _PyplotOnFirstUse(types.ModuleType):
    """Stands for ``matplotlib.pyplot`` in toppra's namespace: the real module
    is imported when a name is first read from it."""

    def __getattr__(self, name: str):
        return getattr(importlib.import_module(_PYPLOT), name)


class _NameOnFirstUse:
    """Stands for one name of a module (a class such as ``scipy.interpolate.PPoly``)
    in toppra's namespace: the real one is imported when called or read from."""

    def __init__(self, module: str, name: str):
        self._where = (module, name)

    def _real(self):
        module, name = self._where
        return getattr(importlib.import_module(module), name)

    def __call__(self, *args, **kwargs):
        return self._real()(*args, **kwargs)

    def __getattr__(self, attr: str):
        if attr.startswith("__"):
            raise AttributeError(attr)
        return getattr(self._real(), attr)


class _InterpolateOnFirstUse(types.ModuleType):
    """Stands for ``scipy.interpolate`` while toppra imports names from it: each
    name read is a :class:`_NameOnFirstUse`."""

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        return _NameOnFirstUse(_INTERPOLATE, name)


def _import_toppra() -> None:
    """Import toppra with the stand-ins in place (for the modules not loaded already)."""
    if "toppra" in sys.modules:
        return
    stand_ins = {}
    for name, kind in ((_PYPLOT, _PyplotOnFirstUse), (_INTERPOLATE, _InterpolateOnFirstUse)):
        if name not in sys.modules:
            stand_ins[name] = sys.modules[name] = kind(name)
    try:
        importlib.import_module("toppra")
    finally:
        for name, stand_in in stand_ins.items():
            if sys.modules.get(name) is stand_in:
                del sys.modules[name]


_import_toppra()

# from the toppra just imported (the point of this module)
from toppra.algorithm import TOPPRA  # noqa: E402
from toppra.algorithm.algorithm import ParameterizationReturnCode  # noqa: E402
from toppra.constraint import DiscretizationType, LinearConstraint  # noqa: E402
from toppra.interpolator import AbstractGeometricPath  # noqa: E402

__all__ = ["TOPPRA", "AbstractGeometricPath", "DiscretizationType", "LinearConstraint",
           "ParameterizationReturnCode"]

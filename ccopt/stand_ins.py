"""Importing a library without the modules it loads only for what ccopt never calls.

toppra imports ``matplotlib.pyplot`` (its plotting helpers) and names of
``scipy.interpolate`` (its own spline paths); cvxpy imports ``scipy.stats``
(one atom's entropy): together more than a second of every command that
plans a feed or solves a convex blend, for code that never runs here.
:func:`import_with_stand_ins` imports such a library with a stand-in in
``sys.modules`` for each of those modules; the stand-in leaves
``sys.modules`` right after, so anyone's later import loads the real module,
and what the library keeps of it forwards to the real module (loaded then)
should the library ever use it:

- :class:`ModuleOnFirstUse` for a module the library keeps as a module
  (``import matplotlib.pyplot as plt``): the real one loads when a name is
  first read from it;
- :class:`NamesOnFirstUse` for a module the library takes names from
  (``from scipy.interpolate import PPoly``): each name is a
  :class:`NameOnFirstUse`, the real object loaded when it is called or read
  from (good for classes and functions used at run time, not for
  ``isinstance`` or subclassing at import time).
"""
from __future__ import annotations

import importlib
import sys
import types


class ModuleOnFirstUse(types.ModuleType):
    """Stands for a module: the real one is imported when a name is first read
    from it. For a package, a submodule that has its own stand-in in
    ``sys.modules`` is that stand-in (``import matplotlib.pyplot as plt`` reads
    ``pyplot`` from ``matplotlib``)."""

    def __getattr__(self, name: str):
        sub = sys.modules.get(f"{self.__name__}.{name}")
        if isinstance(sub, (ModuleOnFirstUse, NamesOnFirstUse)):
            return sub
        return getattr(importlib.import_module(self.__name__), name)


class NameOnFirstUse:
    """Stands for one name of a module (a class or a function): the real one is
    imported when called or read from."""

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

    def __repr__(self) -> str:
        return f"<{'.'.join(self._where)}, imported on first use>"


class NamesOnFirstUse(types.ModuleType):
    """Stands for a module names are taken from: each name read is a
    :class:`NameOnFirstUse`."""

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        return NameOnFirstUse(self.__name__, name)


def import_with_stand_ins(module: str, stand_ins: dict) -> types.ModuleType:
    """``module`` imported with ``stand_ins`` (``{module name: stand-in class}``)
    in ``sys.modules`` for the modules not loaded already (see the module
    docstring); as ``importlib.import_module`` once ``module`` is loaded."""
    if module in sys.modules:
        return sys.modules[module]
    placed = {}
    for name, kind in stand_ins.items():
        if name not in sys.modules:
            placed[name] = sys.modules[name] = kind(name)
    try:
        return importlib.import_module(module)
    finally:
        for name, stand_in in placed.items():
            if sys.modules.get(name) is stand_in:
                del sys.modules[name]


def import_cvxpy() -> types.ModuleType:
    """``cvxpy``, without ``scipy.stats`` (0.4 s): cvxpy takes one function from
    it, for its quantum relative entropy atom, which ccopt's models never use."""
    return import_with_stand_ins("cvxpy", {"scipy.stats": NamesOnFirstUse})

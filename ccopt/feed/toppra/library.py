"""toppra's names ccopt uses, imported without loading ``matplotlib.pyplot``
or ``scipy.interpolate``.

toppra imports ``matplotlib.pyplot`` at module level (``toppra.algorithm``,
``toppra.parametrizer``) only for its plotting helpers, and names of
``scipy.interpolate`` (``toppra.interpolator``, ``toppra.simplepath``) only
for its own spline paths, which ccopt never uses: about 0.5 s (matplotlib
with pyplot) and 0.6 s of the 1.4 s ``import toppra`` took, paid by every
command that plans a feed.
toppra is imported here with stand-ins for both
(:func:`ccopt.stand_ins.import_with_stand_ins`). Every ccopt module takes
its toppra names from here, so this always happens first.
"""
from __future__ import annotations

from ccopt.stand_ins import ModuleOnFirstUse, NamesOnFirstUse, import_with_stand_ins

import_with_stand_ins("toppra", {"matplotlib": ModuleOnFirstUse,
                                 "matplotlib.pyplot": ModuleOnFirstUse,
                                 "scipy.interpolate": NamesOnFirstUse})

# from the toppra just imported (the point of this module)
from toppra.algorithm import TOPPRA  # noqa: E402
from toppra.algorithm.algorithm import ParameterizationReturnCode  # noqa: E402
from toppra.constraint import DiscretizationType, LinearConstraint  # noqa: E402
from toppra.interpolator import AbstractGeometricPath  # noqa: E402

__all__ = ["TOPPRA", "AbstractGeometricPath", "DiscretizationType", "LinearConstraint",
           "ParameterizationReturnCode"]

"""Optimisation models (CasADi, CVXPY) that plug into ccopt through entry points.

ccopt never imports this package; each model registers itself under
``[project.entry-points."ccopt.blends"]`` or ``"ccopt.crosschecks"`` in
pyproject.toml and the core finds it with ``importlib.metadata``.
"""

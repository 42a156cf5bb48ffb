"""Clump: a DEM simulator for rigid clumps of spheres, driven from Python.

The engine is the one behind the ``clump`` command: ``Simulation`` runs a
scenario (TOML) through the same runner as ``clump run``, bit for bit.
SI units throughout; vectors are in the world frame unless named
``*_body``. See docs/python.md and the type stubs (``__init__.pyi``).
"""

from ._clump import (  # noqa: F401
    Bodies,
    Coupling,
    ScenarioError,
    Simulation,
    SimulationError,
    Spheres,
    Template,
    UnstableError,
    Wall,
    Walls,
    __version__,
)

__all__ = [
    "Bodies",
    "Coupling",
    "ScenarioError",
    "Simulation",
    "SimulationError",
    "Spheres",
    "Template",
    "UnstableError",
    "Wall",
    "Walls",
    "__version__",
]

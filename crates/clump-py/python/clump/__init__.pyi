"""Clump from Python: the engine of `clump run`, with numpy state.

Units are SI (m, kg, s, N, rad). Vectors are in the world frame unless the
name says ``_body`` (the body's principal frame). Quaternions are
(w, x, y, z) and map body → world: ``v_world = q v_body q*``.

Every array an accessor returns is a **fresh copy** (writing to it changes
nothing in the simulation; assign it back through the setter). Bodies are
listed in ascending id order, spheres in ascending sphere id order, whatever
order the engine keeps internally.
"""

from os import PathLike
from typing import Any, Callable, Iterator, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, PathLike]
_F64 = npt.NDArray[np.float64]
_ArrayLike = npt.ArrayLike
_I64 = npt.NDArray[np.int64]

class ScenarioError(ValueError):
    """Bad input: a scenario (file, text or dict), checkpoint or template
    that cannot be used. ``str(e)`` is the CLI's message (with the source
    line and a hint). The first problem's location:"""

    file: Optional[str]
    """The scenario file (``<string>``/``<dict>`` for text and dicts)."""
    line: Optional[int]
    """1-based line, or None."""
    column: Optional[int]
    """1-based column (characters), or None."""
    key: Optional[str]
    """Dotted key, e.g. ``"simulation.dt"``, ``"contact.friction"``, or None."""

class SimulationError(RuntimeError):
    """A failure while running (I/O, the engine)."""

class UnstableError(SimulationError):
    """The run became unstable (NaN/Inf, an overlap above
    ``max_overlap_ratio``, a kinetic-energy blow-up). The message names the
    step, the bodies and the likely cause. The state left is the bad one
    (continue from a checkpoint taken before, not from it)."""

class Simulation:
    """A scenario's run: the same runner, stages, insertions and outputs as
    ``clump run``, bit for bit. A new simulation has done the work of its
    first step boundary (stage start, insertions), so ``bodies`` holds the
    bodies inserted at the start; ``spheres`` are derived at the first step."""

    @staticmethod
    def from_file(path: _Path, output_dir: Optional[_Path] = None,
                  overwrite: bool = False, device: str = "cpu") -> "Simulation":
        """Reads and validates a scenario TOML file (as ``clump run``; files it
        refers to are relative to it). With ``output_dir``, the run writes
        the scenario's outputs there as ``clump run -o`` does (VTK, thermo.csv,
        trajectories, periodic checkpoints, final_state.json and manifest.json
        when the stages end); a folder holding another run's files is refused
        unless ``overwrite``. ``device="gpu"`` hands the steps between
        events to the GPU path, as ``clump run --device gpu`` (a package
        built with the ``gpu`` feature: ``MATURIN_PEP517_ARGS="--features
        gpu" pip install ./crates/clump-py``); settings it does not run, or
        a package built without it, raise ValueError before anything is
        written. Raises ScenarioError."""

    @staticmethod
    def from_toml(text: str, base_dir: _Path = ".", output_dir: Optional[_Path] = None,
                  overwrite: bool = False, name: str = "<string>",
                  device: str = "cpu") -> "Simulation":
        """A scenario from TOML text; files it refers to are relative to
        ``base_dir``; ``name`` names it in messages. Raises ScenarioError."""

    @staticmethod
    def from_dict(d: dict, base_dir: _Path = ".", output_dir: Optional[_Path] = None,
                  overwrite: bool = False, device: str = "cpu") -> "Simulation":
        """A scenario from a dict shaped like the TOML file (tables are dicts,
        arrays of tables lists of dicts; numpy arrays and scalars allowed).
        It is written as TOML and read like a file: same validation, same
        messages (lines refer to that text; ``.key`` names the key).
        Raises ScenarioError."""

    @staticmethod
    def from_checkpoint(path: _Path, output_dir: Optional[_Path] = None,
                        device: str = "cpu") -> "Simulation":
        """The run saved in a checkpoint (by ``save_checkpoint`` or by
        ``clump run``); it continues bit for bit as the uninterrupted run.
        With ``output_dir`` the outputs continue there (as ``clump resume``);
        ``device`` as in ``from_file`` (a checkpoint of either device
        resumes on either). Raises ScenarioError."""

    def run(self, steps: Optional[int] = None, time: Optional[float] = None,
            callback: Optional[Callable[["Simulation"], Optional[bool]]] = None,
            every: int = 1) -> int:
        """Advances ``steps`` steps, or ``time`` seconds (the smallest whole
        number of steps covering it), or — with neither — to the end of the
        scenario's stages; never past that end. Steps run on the engine's
        fused path with the GIL released. ``callback(sim)`` is called at
        every ``every``-th step boundary counted from the start of this call
        (not at the start); there it may read anything and steer (body and
        wall setters, gravity), and the next step starts from what it leaves;
        returning ``False`` stops the run. Stage changes and insertions due at
        a boundary are done before the callback sees it. Ctrl-C raises
        KeyboardInterrupt at a step boundary with the state intact (a
        further ``run`` continues exactly). An exception in the callback
        stops the run and propagates. Returns the number of steps taken.
        Raises UnstableError, SimulationError, ValueError (bad arguments)."""

    def step(self) -> int:
        """One step (``run(steps=1)``); returns 1, or 0 at the end."""

    @property
    def time(self) -> float:
        """Simulated time, s."""
    @property
    def step_count(self) -> int:
        """Steps taken since the run began (also across checkpoints)."""
    @property
    def dt(self) -> float:
        """Time step, s."""
    @property
    def total_steps(self) -> int:
        """Steps of all the scenario's stages."""
    @property
    def finished(self) -> bool:
        """True once all stages are done (``run`` then takes no step)."""
    @property
    def stage(self) -> Optional[str]:
        """Name of the current stage (None once finished)."""
    @property
    def gravity(self) -> _F64:
        """Gravitational acceleration, (3,), world frame, m/s². A copy;
        settable between steps (a stage's ``gravity`` does the same)."""
    @gravity.setter
    def gravity(self, value: npt.ArrayLike) -> None: ...
    @property
    def template_names(self) -> list[str]:
        """Template names by template index (``bodies.template``)."""
    @property
    def bodies(self) -> "Bodies":
        """The bodies (a live view object; its arrays are copies)."""
    @property
    def spheres(self) -> "Spheres":
        """The spheres (a live view object; its arrays are copies)."""
    @property
    def walls(self) -> "Walls":
        """The walls by name."""
    @property
    def coupling(self) -> "Coupling":
        """The coupling arrays of a fluid solver or other driver: external
        loads, fluid velocity and void fraction per body, fluid forces, the
        void fraction on a grid."""

    def contacts(self) -> dict[str, np.ndarray]:
        """The touching contacts of the last step, as the kernels computed
        them (the very forces summed into the bodies and walls). Keys, each
        an array with one row per contact (copies):

        - ``sphere_i``, ``body_i`` (int64): sphere and body ids of side i;
        - ``sphere_j``, ``body_j`` (int64): the other sphere and body, −1 for
          a wall contact;
        - ``wall`` (int64): the wall's index (scenario order), −1 for a
          sphere–sphere contact;
        - ``point`` (N×3, m): contact point, world frame;
        - ``normal`` (N×3): unit normal from the partner to sphere i;
        - ``overlap`` (N, m);
        - ``force_normal``, ``force_tangential`` (N×3, N): force on sphere i,
          world frame (the partner gets the negative).

        Order: sphere–sphere contacts in the pair list's order, then
        sphere–wall ones; it depends only on the state. Available at every
        boundary ``run``/``step`` stopped at; raises SimulationError before
        the first step or after bodies were inserted at this boundary."""

    def thermo(self) -> dict[str, Union[float, int]]:
        """The current thermo row: the columns of ``thermo.csv`` (names
        with units, e.g. ``"time[s]"``, ``"ke_rotational[J]"``,
        ``"<wall>_fz[N]"``, ``"<wall>_tx[N*m]"`` about the wall's torque
        point, ``"<wall>_power[W]"`` for moving walls) with the same values."""

    def write_vtk(self, directory: _Path) -> None:
        """Writes the current state as one VTK frame (``spheres_<step>.vtp``,
        ``bodies_…``, ``walls_…``) into ``directory`` and adds it to the
        ``.pvd`` series there (continued by later calls with that folder)."""

    def save_checkpoint(self, path: _Path) -> None:
        """Writes a checkpoint of the run to ``path``; ``from_checkpoint``
        and ``clump resume`` continue from it bit for bit."""

    def final_state_json(self) -> str:
        """Every body's state with exact f64 bit patterns, as the
        ``final_state.json`` ``clump run`` writes (for bit comparisons)."""

    def __len__(self) -> int:
        """Number of bodies."""

class Bodies:
    """The bodies, sorted by id. Every getter returns a new array (a copy).
    Setters take an array of the getter's shape (rows in the same id
    order), validate all of it first (shape, finite values, unit
    quaternions) and then apply it through the engine's steering methods;
    a refused array changes nothing (ValueError). Set between steps, i.e.
    in a callback or between ``run`` calls."""

    def __len__(self) -> int: ...
    @property
    def id(self) -> _I64:
        """Global body ids (N,), ascending."""
    @property
    def template(self) -> _I64:
        """Template index of each body (N,); names: ``Simulation.template_names``."""
    @property
    def template_name(self) -> list[str]:
        """Template name of each body."""
    @property
    def mass(self) -> _F64:
        """Mass (N,), kg."""
    @property
    def temperature(self) -> _F64:
        """Temperature (N,), K (one per body). Settable (each > 0). Only
        with ``[heat]`` in the scenario, else ValueError."""
    @temperature.setter
    def temperature(self, value: npt.ArrayLike) -> None: ...
    @property
    def heat_source(self) -> _F64:
        """Heat source (N,), W (a template's ``heat_source`` times the
        body's volume). Settable. Only with ``[heat]``, else ValueError."""
    @heat_source.setter
    def heat_source(self, value: npt.ArrayLike) -> None: ...
    @property
    def inertia(self) -> _F64:
        """Principal moments of inertia (N×3), body frame, kg m²."""
    @property
    def position(self) -> _F64:
        """Centre of mass (N×3), world frame, m."""
    @position.setter
    def position(self, value: npt.ArrayLike) -> None: ...
    @property
    def velocity(self) -> _F64:
        """Centre-of-mass velocity (N×3), world frame, m/s."""
    @velocity.setter
    def velocity(self, value: npt.ArrayLike) -> None: ...
    @property
    def quaternion(self) -> _F64:
        """Orientation (N×4), (w, x, y, z), body → world. The setter refuses
        quaternions whose norm differs from 1 by more than 1e-6 and
        normalises the rest; the angular velocity is kept."""
    @quaternion.setter
    def quaternion(self, value: npt.ArrayLike) -> None: ...
    @property
    def omega(self) -> _F64:
        """Angular velocity (N×3), world frame, rad/s. The setter also sets
        the angular momentum to match (L = R I Rᵀ ω)."""
    @omega.setter
    def omega(self, value: npt.ArrayLike) -> None: ...
    @property
    def omega_body(self) -> _F64:
        """Angular velocity (N×3), body frame, rad/s (read only)."""
    @property
    def angular_momentum(self) -> _F64:
        """Angular momentum about the centre of mass (N×3), world frame, kg m²/s."""
    @property
    def force(self) -> _F64:
        """Total force of the last force evaluation (contacts + gravity),
        (N×3), world frame, N."""
    @property
    def torque(self) -> _F64:
        """Total torque about the centre of mass, last force evaluation,
        (N×3), world frame, N m."""
    @property
    def force_flag(self) -> npt.NDArray[np.bool_]:
        """Per world axis, whether the force component acts (N×3, bool;
        LIGGGHTS ``fflag``): False freezes that velocity component."""
    @force_flag.setter
    def force_flag(self, value: npt.ArrayLike) -> None: ...
    @property
    def torque_flag(self) -> npt.NDArray[np.bool_]:
        """Per world axis, whether the torque component acts (N×3, bool;
        LIGGGHTS ``tflag``): False freezes that angular-momentum component."""
    @torque_flag.setter
    def torque_flag(self, value: npt.ArrayLike) -> None: ...

class Spheres:
    """The spheres, sorted by sphere id (``body_id << 16 | index in the
    template``); read only, arrays are copies. Empty before the first step."""

    def __len__(self) -> int: ...
    @property
    def id(self) -> _I64:
        """Global sphere ids (M,)."""
    @property
    def position(self) -> _F64:
        """Centres (M×3), world frame, m (not wrapped into a periodic box)."""
    @property
    def radius(self) -> _F64:
        """Radii (M,), m."""
    @property
    def body(self) -> _I64:
        """Id of each sphere's body (M,)."""

class Coupling:
    """What a coupled code exchanges with the run between steps (CFD–DEM).
    Per-body arrays are in body-id order (the order of ``sim.bodies``);
    SI units, world frame. A load, fluid velocity or void fraction set at a
    step boundary acts from the force evaluation at the end of the next
    step: a persistent force F held for N steps gives the impulse
    F (N − ½) dt, a next-step force F dt (velocity Verlet). Every array is
    checked (shape, finite, range) before anything changes; a bad one
    raises ValueError. docs/python.md, "Coupling"."""

    def set_external_loads(self, force: _ArrayLike, torque: Optional[_ArrayLike] = None,
                           persistent: bool = True) -> None:
        """External force (N×3, N) and torque about the centre of mass
        (N×3, N m; None: zero) per body. ``persistent``: until set again;
        else for the next step only, on top of the persistent ones."""
    def set_fluid_velocity(self, velocity: _ArrayLike) -> None:
        """A 3-vector: the uniform ``[fluid] velocity`` (needs ``[fluid]``).
        An N×3 array: the interstitial fluid velocity at each body, m/s,
        which the drag uses instead of the uniform one."""
    def set_void_fractions(self, eps: _ArrayLike) -> None:
        """The void fraction at each body (N values in (0, 1]), read by the
        hindered drag laws (di_felice, beetstra, gidaspow)."""
    def set_fluid_velocity_grid(self, origin: Optional[_ArrayLike], spacing: Optional[_ArrayLike],
                                velocity: Optional[_ArrayLike]) -> None:
        """The fluid velocity on a regular grid of nodes: ``velocity`` an
        (n0, n1, n2, 3) array, m/s, node [i, j, k] at ``origin + (i, j, k)
        * spacing`` (m). Each step a body without a per-body velocity gets
        the trilinear interpolation at its centre of mass (outside the
        grid, the value at its nearest point). ``velocity`` None removes
        the grid. Needs ``[fluid]``; not kept in checkpoints."""
    def set_void_fraction_field(self, lo: Optional[_ArrayLike], cell: Optional[_ArrayLike],
                                eps: Optional[_ArrayLike]) -> None:
        """A void-fraction field computed by a CFD code: ``eps`` an (n0, n1,
        n2) array of values in (0, 1], cell [i, j, k] of edges ``cell`` (m)
        from the corner ``lo`` (m), laid out as ``void_fraction`` returns
        it. Each step a body without a per-body void fraction takes the
        value of the cell holding its centre of mass (1 outside the grid);
        the drag laws read it. ``eps`` None removes the field. Needs
        ``[fluid]``; not kept in checkpoints."""
    def clear(self) -> None:
        """Removes every external load and per-body fluid value (not the
        fields on grids)."""
    @property
    def fluid_force(self) -> _F64:
        """Fluid force of the last step per body (N×3, N): drag, buoyancy,
        pressure gradient; zeros without ``[fluid]``. A copy."""
    def void_fraction(self, lo: _ArrayLike, cell: _ArrayLike, n: tuple[int, int, int],
                      periodic: tuple[bool, bool, bool] = (False, False, False)) -> np.ndarray:
        """Void fraction of the cells of a grid: ``n`` cells per axis of
        edges ``cell`` (m) from the corner ``lo`` (m), as an (n0, n1, n2)
        array indexed [i, j, k], from the bodies as they are (theory T-69;
        overlaps within a body counted once; not clamped). ``periodic``
        per axis: solid beyond the grid wraps into it (a grid spanning a
        periodic axis of the domain)."""

class Walls:
    """The walls as a read-only mapping name → Wall (scenario order)."""

    def __len__(self) -> int: ...
    def __getitem__(self, name: str) -> "Wall":
        """KeyError naming the walls there are."""
    def __contains__(self, name: str) -> bool: ...
    def __iter__(self) -> Iterator[str]: ...
    def keys(self) -> list[str]: ...

class Wall:
    """One wall: the load the particles exert on it and its prescribed
    motion, which may be changed between steps (as ``[[stage.wall]]``)."""

    @property
    def name(self) -> str: ...
    @property
    def index(self) -> int:
        """Index in scenario order (``contacts()["wall"]``)."""
    @property
    def force(self) -> _F64:
        """Force the particles exert on the wall, last force evaluation,
        (3,), world frame, N. A copy."""
    @property
    def torque(self) -> _F64:
        """Torque the particles exert on the wall about its centre of
        rotation ``center``, (3,), world frame, N m. A copy."""
    @property
    def velocity(self) -> _F64:
        """Translation velocity (3,), world frame, m/s. Settable (finite)."""
    @velocity.setter
    def velocity(self, value: npt.ArrayLike) -> None: ...
    @property
    def angular_velocity(self) -> _F64:
        """Angular velocity about ``center`` (3,), world frame, rad/s. Settable."""
    @angular_velocity.setter
    def angular_velocity(self, value: npt.ArrayLike) -> None: ...
    @property
    def center(self) -> _F64:
        """Centre of rotation (3,), world frame, m; moves with the wall."""
    @property
    def active(self) -> bool:
        """An inactive wall exerts no force. Settable."""
    @active.setter
    def active(self, value: bool) -> None: ...

class Template:
    """A multi-sphere template and its exact mass properties (the union of
    the spheres, overlaps counted once), as ``clump template``."""

    def __init__(self, spheres: npt.ArrayLike, density: float = 1.0) -> None:
        """``spheres``: rows (x, y, z, r), m, input frame; ``density``: kg/m³.
        Raises ValueError (shape, non-finite values) or ScenarioError."""

    @staticmethod
    def from_file(path: _Path, scale: float = 1.0, density: float = 1.0) -> "Template":
        """A LIGGGHTS-format template file (``x y z r`` per line, ``#``
        comments), every length times ``scale``. Raises ScenarioError."""

    @staticmethod
    def from_mesh(path: _Path, spheres: Optional[int] = None, tolerance: Optional[float] = None,
                  resolution: int = 50, overlap: float = 0.6, min_radius: float = 0.0,
                  refine: int = 20, scale: float = 1.0, density: float = 1.0) -> "Template":
        """Generates a template from a closed STL/OBJ mesh as ``clump
        template --from-mesh`` (same options and defaults: at most
        ``spheres`` spheres, default 50, or 1000 with only ``tolerance``;
        ``resolution`` voxels along the shortest edge; ``min_radius`` in m
        after ``scale``; ``refine`` least-squares passes). ``fidelity`` holds
        the CLI's JSON report. Raises ScenarioError."""

    @property
    def spheres(self) -> _F64:
        """The spheres (N×4: x, y, z, r), m, input frame. A copy."""
    @property
    def density(self) -> float:
        """Density, kg/m³."""
    @property
    def fidelity(self) -> Optional[dict[str, Any]]:
        """``from_mesh``'s fidelity report (the keys of ``clump template
        --from-mesh --json``), else None."""

    def mass_properties(self) -> dict[str, Any]:
        """The keys and values of ``clump template --json``: ``volume``
        (m³), ``mass`` (kg), ``center_of_mass`` (m), ``inertia`` (3×3 rows,
        about the centre of mass, kg m²), ``principal_moments`` (kg m²,
        ascending), ``principal_axes`` (rows), ``naive_volume``,
        ``naive_principal_moments``, ``relative_error_bound``; input frame."""

    def write(self, path: _Path) -> None:
        """Writes the spheres as a template file (``x y z r``, m)."""

    def __len__(self) -> int:
        """Number of spheres."""

"""Shared fixtures of the Python suite: scenarios written into a temporary
folder, and the `clump` binary of this checkout (the CLI the package must
agree with bit for bit)."""

import json
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[3]


def clump_bin() -> pathlib.Path:
    """The `clump` binary: $CLUMP_BIN, else target/release/clump of this
    checkout (scripts/test-all.sh sets $CLUMP_BIN to target/ci/clump, built
    by its Rust suite with the profile the package is built with)."""
    p = pathlib.Path(os.environ.get("CLUMP_BIN", REPO / "target" / "release" / "clump"))
    if not p.exists():
        pytest.fail(f"the clump binary {p} is missing: run `cargo build --release -p clump-cli` "
                    "or set CLUMP_BIN (scripts/test-all.sh builds it first)")
    return p


def run_cli(*args, cwd=None):
    """Runs `clump ARGS…`; returns the completed process (check=True)."""
    return subprocess.run([str(clump_bin()), *map(str, args)], cwd=cwd, check=True,
                          capture_output=True, text=True)


def final_state(path) -> dict:
    """A final_state.json (file path or JSON text) as a dict."""
    p = pathlib.Path(path) if not str(path).lstrip().startswith("{") else None
    return json.loads(p.read_text() if p else path)


# Three dimers dropped on a floor: contacts, friction, rebuilds, two stages.
BODIES = """template,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
dimer,0.000,0,0.006,1,0,0,0,0,0,0,0,0,0
dimer,0.012,0,0.006,0.9238795,0,0.3826834,0,0,0,0,0,0,0
dimer,0.006,0.010,0.015,1,0,0,0,0,0,0,0,0,0
"""


def dimers_toml(body_change: str = "", steps=(3000, 4000), extra: str = "") -> str:
    return f"""
[simulation]
dt = 5e-6
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.05, -0.05, -0.01]
hi = [0.05, 0.05, 0.08]

[[material]]
name = "grain"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500

[[material]]
name = "steel"
youngs_modulus = inf
poisson_ratio = 0.3
density = 7800

[contact]
restitution = 0.5
friction = 0.4

[[template]]
name = "dimer"
material = "grain"
spheres = [[-0.002, 0.0, 0.0, 0.003], [0.002, 0.0, 0.0, 0.003]]

[[wall]]
name = "floor"
material = "steel"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
kind = "file"
file = "bodies.csv"

[[stage]]
name = "settle"
steps = {steps[0]}

[[stage]]
name = "kicked"
steps = {steps[1]}
{body_change}

[output]
thermo = {{ every_steps = 500 }}
{extra}
"""


@pytest.fixture
def dimers(tmp_path):
    """Writes the dimer scenario (optionally with a stage-2 body change)
    into a fresh folder; returns a function (name, body_change) -> path."""
    def make(name="dimers", body_change="", **kw):
        d = tmp_path / name
        d.mkdir()
        (d / "bodies.csv").write_text(BODIES)
        p = d / "scenario.toml"
        p.write_text(dimers_toml(body_change, **kw))
        return p
    return make

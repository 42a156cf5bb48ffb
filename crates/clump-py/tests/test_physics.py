"""Physics through Python, against values from outside the code: free fall
(analytic), Chung & Ooi (2011) test 1 (Hertz closed form), and the exact
mass properties of `clump template --json`."""

import json
import math

import numpy as np

import clump
from conftest import REPO, run_cli

SPHERE = """
[simulation]
dt = {dt}
gravity = [0.0, 0.0, {g}]
[domain]
lo = [-1.0, -1.0, -10.0]
hi = [1.0, 1.0, 10.0]
[[material]]
name = "{name}"
youngs_modulus = {E}
poisson_ratio = {nu}
density = {rho}
[contact]
restitution = 1.0
friction = 0.0
[[template]]
name = "ball"
material = "{name}"
spheres = [[0.0, 0.0, 0.0, {R}]]
[[insert]]
kind = "file"
file = "bodies.csv"
[[stage]]
steps = {steps}
"""


def test_free_fall_matches_analytic(tmp_path):
    """z(t) = z0 + v0 t − g t²/2, x(t) = x0 + vx t: velocity Verlet is exact
    for a constant force, so only rounding separates them."""
    (tmp_path / "bodies.csv").write_text("template,x,y,z,vx,vz\nball,0.1,0,5,0.3,2.0\n")
    (tmp_path / "s.toml").write_text(SPHERE.format(dt=1e-4, g=-9.81, name="rubber", E=1e7, nu=0.3,
                                                   rho=7800, R=0.01, steps=10000))
    sim = clump.Simulation.from_file(tmp_path / "s.toml")
    seen = []

    def probe(s):
        seen.append((s.time, s.bodies.position[0].copy(), s.bodies.velocity[0].copy()))

    sim.run(steps=10000, callback=probe, every=500)
    assert len(seen) == 20 and sim.step_count == 10000
    for t, x, v in seen:
        z = 5.0 + 2.0 * t - 0.5 * 9.81 * t * t
        assert abs(x[2] - z) <= 1e-12 * 50 + 1e-12 * abs(z)
        assert abs(x[0] - (0.1 + 0.3 * t)) <= 1e-12
        assert abs(v[2] - (2.0 - 9.81 * t)) <= 1e-11
    assert math.isclose(sim.time, 1.0, rel_tol=1e-12)


def hertz_peak(E, nu, rho, R, v_rel):
    """Chung & Ooi (2011) / Hertz: peak force and overlap of two identical
    spheres approaching at v_rel (REFERENCE.md §3)."""
    e_star = E / (2.0 * (1.0 - nu * nu))
    r_star = R / 2.0
    m_star = (4.0 / 3.0 * math.pi * R ** 3 * rho) / 2.0
    d_max = (15.0 * m_star * v_rel ** 2 / (16.0 * e_star * math.sqrt(r_star))) ** 0.4
    return 4.0 / 3.0 * e_star * math.sqrt(r_star) * d_max ** 1.5, d_max


def test_chung_ooi_test1_hertz_peak_force(tmp_path):
    """Test 1, glass: two spheres R = 10 mm at ±10 m/s; the peak contact
    force and overlap read from Python (`contacts()` at every step) match
    Hertz (10.70 kN, 274.1 µm in the paper) within 0.5 %."""
    R, E, nu, rho = 0.01, 4.8e10, 0.20, 2800.0
    (tmp_path / "bodies.csv").write_text(
        f"template,x,y,z,vx\nball,{-R - 1e-5},0,0,10\nball,{R + 1e-5},0,0,-10\n")
    (tmp_path / "s.toml").write_text(SPHERE.format(dt=4e-8, g=0.0, name="glass", E=E, nu=nu,
                                                   rho=rho, R=R, steps=1500))
    sim = clump.Simulation.from_file(tmp_path / "s.toml")
    peak = {"f": 0.0, "d": 0.0}

    def probe(s):
        c = s.contacts()
        if len(c["overlap"]):
            assert (c["wall"] == -1).all()
            peak["f"] = max(peak["f"], float(np.linalg.norm(c["force_normal"], axis=1).max()))
            peak["d"] = max(peak["d"], float(c["overlap"].max()))

    sim.run(callback=probe)
    f_max, d_max = hertz_peak(E, nu, rho, R, 20.0)
    assert abs(f_max - 10.70e3) / 10.70e3 < 1e-3  # the closed form itself vs the paper
    assert abs(peak["f"] - f_max) / f_max < 5e-3, (peak, f_max)
    assert abs(peak["d"] - d_max) / d_max < 5e-3, (peak, d_max)
    # elastic: both rebound at 10 m/s
    v = sim.bodies.velocity
    assert np.allclose(np.abs(v[:, 0]), 10.0, rtol=5e-3)
    assert v[0, 0] < 0 < v[1, 0]


TEMPLATE = """# three overlapping spheres (m)
0.0 0.0 0.0 0.010
0.012 0.0 0.0 0.008
0.004 0.009 0.003 0.006
"""


def test_mass_properties_equal_cli_json(tmp_path):
    f = tmp_path / "t.txt"
    f.write_text(TEMPLATE)
    for scale, density in [(1.0, 1.0), (2.5, 2650.0)]:
        cli = json.loads(run_cli("template", f, "--json", "--scale", scale,
                                 "--density", density).stdout)
        py = clump.Template.from_file(f, scale=scale, density=density).mass_properties()
        assert py == cli  # same keys, same floats exactly
    rows = [[float(x) for x in line.split()] for line in TEMPLATE.splitlines()[1:]]
    inline = clump.Template(spheres=rows, density=1.0)
    cli = json.loads(run_cli("template", f, "--json").stdout)
    assert inline.mass_properties() == cli
    assert inline.spheres.shape == (3, 4)


def test_template_from_mesh_as_cli(tmp_path):
    """`Template.from_mesh` gives the spheres `clump template --from-mesh`
    writes (to the 10 digits of its text) and the same fidelity report."""
    mesh = REPO / "examples" / "data" / "rock.stl"
    out = tmp_path / "rock.txt"
    cli = json.loads(run_cli("template", "--from-mesh", mesh, "--spheres", 6, "--resolution", 20,
                             "--out", out, "--json").stdout)
    t = clump.Template.from_mesh(mesh, spheres=6, resolution=20)
    cli_spheres = np.loadtxt(out)
    assert t.spheres.shape == cli_spheres.shape == (len(t), 4)
    assert np.allclose(t.spheres, cli_spheres, rtol=1e-9, atol=0)
    fid = t.fidelity
    cli.pop("seconds"), fid.pop("seconds")
    assert fid == cli

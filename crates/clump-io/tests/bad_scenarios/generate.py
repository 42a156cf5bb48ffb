#!/usr/bin/env python3
"""Regenerates the bad-scenario corpus from base_valid.toml.

Each case edits the valid base scenario, writes NN_name.toml and
NN_name.expected: one substring per line that the error message must
contain, including `:LINE:` where LINE is the line of the offending key
(found by a marker string in the edited text). Run from this folder:
python3 generate.py
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))
BASE = open(os.path.join(HERE, "base_valid.toml")).read()


def rep(old, new, count=1):
    def f(t):
        assert old in t, old
        return t.replace(old, new, count)
    return f


def chain(*fs):
    def f(t):
        for g in fs:
            t = g(t)
        return t
    return f


def append(s):
    return lambda t: t + s


def line_of(text, marker, nth=1):
    pos = -1
    for _ in range(nth):
        pos = text.index(marker, pos + 1)
    return text[:pos].count("\n") + 1


# a mesh wall appended at the end of the base scenario (after [output], so
# it starts its own [[wall]] table)
MESH = """
[[wall]]
name = "funnel"
material = "steel"
type = "mesh"
%s
"""

PACK = 'kind = "pack"\nstage = "fill"\nmix = "pebbles"\ncount = 100\nregion = { type = "box", lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1] }\nseed = 1'

CASES = [
    ("unknown_key_pair", rep("restitution = 0.4", "restitutoin = 0.4"), "restitutoin",
     ["unknown key 'restitutoin' in [[pair]]", "did you mean 'restitution'?"]),
    ("unknown_table", rep("[simulation]", "[simulaton]"), "[simulaton]",
     ["unknown key 'simulaton' at the top level", "did you mean 'simulation'?"]),
    ("unknown_key_material", rep("youngs_modulus = 5e6", "youngs = 5e6"), "youngs =",
     ["unknown key 'youngs' in [[material]]", "did you mean 'youngs_modulus'?"]),
    ("radius_with_unit", rep("radius = 0.002", 'radius = "2 mm"'), '"2 mm"',
     ["wrong type for 'radius' in [[template]]: expected a number in m", "radius = 0.002"]),
    ("friction_bool", rep("friction = 0.5", "friction = true"), "friction = true",
     ["wrong type for 'friction' in [contact]: expected a number", "found boolean"]),
    ("gravity_two_components", rep("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, -9.81]"), "gravity",
     ["'gravity' in [simulation]: expected an array of 3 numbers [x, y, z] in m/s^2"]),
    ("rotation_typo", rep("[simulation]", '[integrator]\nrotation = "richardsen"\n\n[simulation]'), "richardsen",
     ["invalid value \"richardsen\" for 'rotation' in [integrator]", 'did you mean "richardson"?', '"no_squish"']),
    ("template_material_missing", rep('material = "rock"\nshape', 'material = "granite"\nshape'), '"granite"',
     ["material 'granite' does not exist", "defined materials: 'rock' and 'steel'"]),
    ("insert_template_missing", rep('mix = "pebbles"\ncount', 'template = "pebbel"\ncount'), '"pebbel"',
     ["template 'pebbel' does not exist", "did you mean 'pebble'?"]),
    ("insert_mix_missing", rep('mix = "pebbles"\ncount', 'mix = "gravel"\ncount'), '"gravel"',
     ["mix 'gravel' does not exist", "defined mixes: 'pebbles'"]),
    ("stage_wall_missing", rep('name = "gate"\nactive = false', 'name = "gat"\nactive = false'), '"gat"',
     ["wall 'gat' does not exist", "did you mean 'gate'?", "defined walls: 'floor' and 'gate'"]),
    ("insert_stage_missing", rep('stage = "fill"', 'stage = "filling"'), '"filling"',
     ["stage 'filling' does not exist", "defined stages: 'fill' and 'drain'"]),
    ("negative_radius_shape", rep("radius = 0.002", "radius = -0.002"), "-0.002",
     ["'radius' must be > 0 m, found -0.002"]),
    ("negative_radius_inline",
     rep('shape = "tetrahedron"\nradius = 0.002\nedge = 0.0025', 'spheres = [\n    [0.0, 0.0, 0.0, 0.002],\n    [0.002, 0.0, 0.0, -0.001],\n]'),
     "-0.001", ["sphere 1 of template has radius -0.001 m; radii must be > 0"]),
    ("poisson_half", rep("poisson_ratio = 0.3", "poisson_ratio = 0.5"), "poisson_ratio = 0.5",
     ["poisson_ratio must be < 0.5, found 0.5"]),
    ("restitution_above_one", rep("restitution = 0.5", "restitution = 1.2"), "1.2",
     ["restitution must lie in [0, 1], found 1.2"]),
    ("negative_density", rep("density = 7800", "density = -7800"), "-7800",
     ["density must be > 0 kg/m^3, found -7800"]),
    ("dt_above_limit", rep('dt = "auto"', "dt = 1e-3"), "dt = 1e-3",
     ["dt = 1e-3 s is above the stability limit", "Rayleigh time", "help: use dt <="]),
    ("dt_fraction_too_big", rep('dt = "auto"', 'dt = "auto"\ndt_fraction = 0.8'), "dt_fraction",
     ["dt_fraction must lie in (0, 0.5], found 0.8"]),
    ("region_too_small", rep("count = 100", "count = 100000"), "count = 100000",
     ["the region cannot hold 100000 bodies", "at most about"]),
    ("template_file_missing", rep('shape = "tetrahedron"\nradius = 0.002\nedge = 0.0025', 'file = "no_such_stone.txt"'), "no_such_stone",
     ["cannot read template file 'no_such_stone.txt'", "relative to the scenario file"]),
    ("template_file_bad", rep('shape = "tetrahedron"\nradius = 0.002\nedge = 0.0025', 'file = "data_bad_template.txt"'), "data_bad_template",
     ["template file 'data_bad_template.txt' is invalid", "data_bad_template.txt:3"]),
    ("body_file_missing", rep('kind = "pack"\nstage = "fill"\nmix = "pebbles"\ncount = 100\nregion = { type = "box", lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1] }\nseed = 1', 'kind = "file"\nfile = "no_such_bodies.csv"'), "no_such_bodies",
     ["cannot read body file 'no_such_bodies.csv'"]),
    ("body_file_bad_column", rep('kind = "pack"\nstage = "fill"\nmix = "pebbles"\ncount = 100\nregion = { type = "box", lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1] }\nseed = 1', 'kind = "file"\nfile = "data_bad_bodies.csv"'), "data_bad_bodies",
     ["data_bad_bodies.csv:2: unknown column 'vxx'"]),
    ("missing_domain", rep('[domain]\nlo = [-0.1, -0.1, -0.01]\nhi = [0.1, 0.1, 0.3]\n', ''), None,
     ["missing table [domain]", "lo = ["]),
    ("missing_duration", rep('name = "fill"\nduration = 0.1', 'name = "fill"'), '[[stage]]',
     ["missing key 'duration' in [[stage]]"]),
    ("duration_and_steps", rep('name = "fill"\nduration = 0.1', 'name = "fill"\nduration = 0.1\nsteps = 100'), 'duration = 0.1',
     ["give either 'duration' (s) or 'steps' in [[stage]], not both"]),
    ("linear_without_kn", rep("friction = 0.5\n", 'friction = 0.5\nlaw = "linear"\n'), "[contact]",
     ["missing key 'kn' in [contact]", "kn = 1e5"]),
    ("kn_with_hertz", rep("friction = 0.3\n", "friction = 0.3\nkn = 1e5\n"), "kn = 1e5",
     ["'kn' is only used with law = \"linear\""]),
    ("plane_with_radius", rep("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 0.0, 1.0]\nradius = 0.1"), "radius = 0.1",
     ["'radius' does not apply to a wall of type \"plane\"", "a plane uses point, normal"]),
    ("duplicate_material", rep('name = "steel"', 'name = "rock"'), 'name = "rock"',
     ["duplicate material name 'rock'"], 2),
    ("toml_syntax", rep("friction = 0.5", "friction = 0.5 0.6"), "0.6",
     ["invalid TOML"]),
    ("zero_normal", rep("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 0.0, 0.0]"), "normal = [0.0, 0.0, 0.0]",
     ["'normal' must be a non-zero direction vector"]),
    ("pack_count_and_fraction", rep("count = 100", "count = 100\nvolume_fraction = 0.2"), "volume_fraction",
     ["give either 'count' or 'volume_fraction', not both"]),
    ("stream_without_rate", rep('kind = "pack"\nstage = "fill"\nmix = "pebbles"\ncount = 100', 'kind = "stream"\nstage = "fill"\nmix = "pebbles"'), "[[insert]]",
     ["missing key 'bodies_per_second' in [[insert]] of kind \"stream\"", "kg_per_second"]),
    ("template_two_sources", rep("edge = 0.0025", 'edge = 0.0025\nfile = "x.txt"'), 'file = "x.txt"',
     ["gives more than one of 'spheres', 'file', 'shape'"]),
    ("region_unknown_key", rep("hi = [0.05, 0.05, 0.1] }", "hi = [0.05, 0.05, 0.1], hieght = 0.1 }"), "hieght",
     ["unknown key 'hieght'", "did you mean 'height'?"]),
    ("pair_material_missing", rep('materials = ["rock", "steel"]', 'materials = ["rock", "stel"]'), '"stel"',
     ["material 'stel' does not exist", "did you mean 'steel'?"]),
    ("mass_without_inertia", rep("edge = 0.0025", "edge = 0.0025\nmass = 0.001"), "mass = 0.001",
     ["'mass' needs 'inertia' too"]),
    ("inertia_not_positive", rep("edge = 0.0025", "edge = 0.0025\nmass = 0.001\ninertia = [[1e-9, 0.0, 0.0], [0.0, -1e-9, 0.0], [0.0, 0.0, 1e-9]]"), "inertia =",
     ["invalid inertia tensor"]),
    ("size_max_below_min", rep("fraction = 1.0", 'fraction = 1.0\nsize = { distribution = "uniform", min = 1.2, max = 0.8 }'), "size =",
     ["size 'max' (0.8) is below 'min' (1.2)"]),
    ("volume_fraction_too_high", rep("count = 100", "volume_fraction = 0.6"), "volume_fraction",
     ["volume_fraction 0.6 cannot be reached by random packing"]),
    ("domain_hi_below_lo", rep("hi = [0.1, 0.1, 0.3]", "hi = [0.1, -0.2, 0.3]"), "hi = [0.1, -0.2",
     ["domain 'hi'", "must be above 'lo'"]),
    ("duplicate_pair", append('\n[[pair]]\nmaterials = ["steel", "rock"]\nfriction = 0.2\n'), 'materials = ["steel", "rock"]',
     ["pair steel – rock is defined twice"]),
    ("negative_friction", rep("friction = 0.3", "friction = -0.3"), "friction = -0.3",
     ["'friction' must be >= 0, found -0.3"]),
    ("periodic_axis_unknown", rep("hi = [0.1, 0.1, 0.3]", 'hi = [0.1, 0.1, 0.3]\nperiodic = ["x", "w"]'), '"w"',
     ["invalid value \"w\" for 'periodic' in [domain]", '"x", "y", "z"']),
    ("output_every_both", rep("thermo = { every_steps = 100 }", "thermo = { every = 0.01, every_steps = 100 }"), "thermo =",
     ["give either 'every' (s) or 'every_steps', not both"]),
    ("trajectory_body_zero", append("trajectory = { bodies = [0, 5] }\n"), "trajectory",
     ["body ids start at 1"]),
    ("wall_type_missing", rep('type = "plane"\n', ''), '[[wall]]',
     ["missing key 'type' in [[wall]]", "type = \"plane\""]),
    ("simulation_duration_with_stages", rep('dt = "auto"', 'dt = "auto"\nduration = 1.0'), "duration = 1.0",
     ["'duration' in [simulation] conflicts with the [[stage]] list"]),
    ("negative_dt", rep('dt = "auto"', 'dt = -1e-5'), "dt = -1e-5",
     ["'dt' must be > 0 s, found -0.00001"]),
    ("dt_bad_string", rep('dt = "auto"', 'dt = "fast"'), '"fast"',
     ["wrong type for 'dt' in [simulation]", "\"auto\""]),
    ("mesh_file_missing", append(MESH % 'file = "no_such_hopper.stl"'), "no_such_hopper.stl",
     ["cannot read mesh file 'no_such_hopper.stl'", "relative to the scenario file"]),
    ("mesh_file_malformed", append(MESH % 'file = "data_bad_mesh.stl"'), "data_bad_mesh.stl",
     ["mesh file 'data_bad_mesh.stl' is invalid", "data_bad_mesh.stl:5"]),
    ("mesh_file_unknown_format", append(MESH % 'file = "data_bad_template.txt"'), 'data_bad_template.txt',
     ["unknown mesh format (expected a .stl or .obj file)"]),
    ("mesh_without_file", append(MESH % 'scale = 0.001'), "[[wall]]",
     ["missing key 'file' in [[wall]] of type \"mesh\""], 3),
    ("mesh_unknown_key", append(MESH % 'file = "data_floor.obj"\nrotaton = { axis = [1, 0, 0], angle = 90 }'), "rotaton",
     ["unknown key 'rotaton' in [[wall]]", "did you mean 'rotation'?", "torque_point"]),
    ("mesh_with_radius", append(MESH % 'file = "data_floor.obj"\nradius = 0.1'), "radius = 0.1",
     ["'radius' does not apply to a wall of type \"mesh\"", "file, scale, rotation, offset, merge_angle"]),
    ("mesh_rotation_without_angle", append(MESH % 'file = "data_floor.obj"\nrotation = { axis = [1, 0, 0] }'), "rotation =",
     ["missing key 'angle' in 'rotation' of a [[wall]] of type \"mesh\"", "degrees"]),
    ("mesh_rotation_unknown_key", append(MESH % 'file = "data_floor.obj"\nrotation = { axis = [1, 0, 0], degrees = 90 }'), "degrees",
     ["unknown key 'degrees'", "allowed keys: axis, angle"]),
    ("mesh_rotation_zero_axis", append(MESH % 'file = "data_floor.obj"\nrotation = { axis = [0, 0, 0], angle = 90 }'), "axis = [0, 0, 0]",
     ["'axis' must be a non-zero direction vector"]),
    ("mesh_negative_scale", append(MESH % 'file = "data_floor.obj"\nscale = -0.001'), "scale = -0.001",
     ["'scale' must be > 0, found -0.001"]),
    ("mesh_merge_angle_out_of_range", append(MESH % 'file = "data_floor.obj"\nmerge_angle = 120'), "merge_angle",
     ["'merge_angle' must be in [0, 90) degrees, found 120"]),
    ("plane_with_file", rep('normal = [0.0, 0.0, 1.0]\n', 'normal = [0.0, 0.0, 1.0]\nfile = "data_floor.obj"\n'), 'file = "data_floor.obj"',
     ["'file' does not apply to a wall of type \"plane\""]),
    ("tensile_not_bool", rep("friction = 0.5", 'friction = 0.5\ntensile = "yes"'), 'tensile = "yes"',
     ["wrong type for 'tensile' in [contact]: expected true or false", "found string"]),
    # bounds: step counts that would overflow or never end, zero steps
    ("dt_tiny_steps_overflow", rep('dt = "auto"', 'dt = 1e-300'), "duration = 0.1",
     ["duration = 1e-1 s is 1.000e299 steps of dt = 1e-300 s", "at most 1e12 steps are allowed"]),
    ("duration_huge", rep("duration = 0.1", "duration = 1e308"), "duration = 1e308",
     ["duration = 1e308 s is", "at most 1e12 steps are allowed"]),
    ("steps_zero", rep("duration = 0.1", "steps = 0"), "steps = 0",
     ["'steps' must be at least 1, found 0"]),
    ("steps_huge", rep("duration = 0.1", "steps = 9223372036854775807"), "steps = 9223372036854775807",
     ["steps = 9223372036854775807", "at most 1e12 steps are allowed"]),
    ("rigid_particle_material", rep("youngs_modulus = 5e6", "youngs_modulus = inf"), 'material = "rock"',
     ["template 'pebble' uses material 'rock' with youngs_modulus = inf", "particles need a finite Young's modulus"]),
    ("periodic_box_too_short", rep("hi = [0.1, 0.1, 0.3]", 'hi = [-0.095, 0.1, 0.3]\nperiodic = ["x"]'), "periodic = ",
     ["periodic axis x is 5.0000e-3 m long, shorter than 3 neighbour cells"]),
    # no body lost without a word
    ("pack_region_outside_domain", rep("lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1]", "lo = [-0.05, -0.05, 0.4], hi = [0.05, 0.05, 0.5]"), "region = ",
     ["the region lies outside the domain along z (region 0.4000 .. 0.5000 m, domain -0.0100 .. 0.3000 m)"]),
    ("body_file_row_outside_domain", rep(PACK, 'kind = "file"\nfile = "data_bodies_outside.csv"'), "data_bodies_outside",
     ["1 of 2 bodies in the body file lie outside the domain", "body 2 at [0.0000, 0.0000, 0.5000]"]),
    ("body_file_coincident_rows", rep(PACK, 'kind = "file"\nfile = "data_bodies_coincident.csv"'), "data_bodies_coincident",
     ["bodies 1 and 3 of the body file are at the same point", "overlapping placement"]),
    # values shortened in messages
    ("tiny_negative_dt_printed_short", rep('dt = "auto"', 'dt = -1e-300'), "dt = -1e-300",
     ["'dt' must be > 0 s, found -1e-300"]),
    ("huge_line_excerpt", rep('name = "fill"', 'name = "fill"\nbogus = "' + "x" * 5000 + '"'), "bogus",
     ["unknown key 'bogus' in [[stage]]", "…"]),
    # several errors in one section are reported together
    ("two_bad_templates", chain(rep("radius = 0.002", "radius = -0.002"),
        append('\n[[template]]\nname = "grain"\nmaterial = "rock"\nshape = "sphere"\nradius = 0.0\n')), "radius = 0.0",
     ["'radius' must be > 0 m, found -0.002", "two_bad_templates.toml:35:", "'radius' must be > 0 m, found 0"]),
    ("two_bad_inserts", chain(rep("lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1]", "lo = [-0.05, -0.05, 0.4], hi = [0.05, 0.05, 0.5]"),
        append('\n[[insert]]\nkind = "pack"\nstage = "fill"\nmix = "pebbles"\ncount = 10\nregion = { type = "box", lo = [0.2, -0.05, 0.01], hi = [0.3, 0.05, 0.1] }\n')), "lo = [0.2, -0.05",
     ["the region lies outside the domain along z", "the region lies outside the domain along x (region 0.2000 .. 0.3000 m"]),
    # contact sub-models
    ("tangential_typo", rep("friction = 0.3", 'friction = 0.3\ntangential = "ligghts"'), '"ligghts"',
     ["invalid value \"ligghts\" for 'tangential' in [[pair]]", 'did you mean "liggghts"?', '"clump", "liggghts"']),
    ("sjkr_without_density", rep("friction = 0.3", 'friction = 0.3\ncohesion = "sjkr"'), None,
     ["missing key 'cohesion_energy_density' in [[pair]]", "cohesionEnergyDensity"]),
    ("surface_energy_without_jkr", rep("friction = 0.5", 'friction = 0.5\ncohesion = "sjkr"\nsurface_energy = 0.05'), "surface_energy",
     ["'surface_energy' is only used with cohesion = \"jkr\"", "this [contact] has cohesion = \"sjkr\""]),
    ("negative_cohesion", rep("friction = 0.5", 'friction = 0.5\ncohesion = "jkr"\nsurface_energy = -0.05'), "surface_energy",
     ["'surface_energy' must be >= 0 J/m^2, found -0.05"]),
    ("jkr_linear", rep("friction = 0.3", 'friction = 0.3\nlaw = "linear"\nkn = 1e4\ncohesion = "jkr"\nsurface_energy = 0.05'), 'cohesion = "jkr"',
     ["cohesion = \"jkr\" needs the Hertz normal law (this [[pair]] uses law = \"linear\")"]),
    ("micro_slip_twisting", rep("friction = 0.3", 'friction = 0.3\ntangential = "mindlin_deresiewicz"\ntwisting = "marshall"'), 'tangential = "mindlin_deresiewicz"',
     ["tangential = \"mindlin_deresiewicz\" cannot be combined with twisting resistance (this [[pair]])", "help: remove 'twisting'"]),
    ("fluid_negative_viscosity", append('\n[fluid]\ndensity = 1000\nviscosity = -1e-3\n'), "viscosity = -1e-3",
     ["'viscosity' must be > 0 Pa s, found -0.001"]),
    ("fluid_unknown_drag", append('\n[fluid]\ndensity = 1000\nviscosity = 1e-3\ndrag = "difelice"\n'), 'drag = "difelice"',
     ["unknown drag law 'difelice'", "did you mean 'di_felice'?", "'stokes', 'schiller_naumann'"]),
    ("fluid_missing_density", append('\n[fluid]\nviscosity = 1e-3\n'), "[fluid]",
     ["missing key 'density' in [fluid]"]),
    # issue 61: exact vector lengths, contradictions, long numbers
    ("gravity_four_components", rep("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81, 7.0]"), "gravity",
     ["'gravity' in [simulation]: expected an array of 3 numbers [x, y, z] in m/s^2", "found 4 elements"]),
    ("wall_point_four_components", rep("point = [0.0, 0.0, 0.0]", "point = [0.0, 0.0, 0.0, 1.0]"), "point = [0.0, 0.0, 0.0, 1.0]",
     ["'point' in [[wall]]: expected an array of 3 numbers", "found 4 elements"]),
    ("sphere_row_five", rep('shape = "tetrahedron"\nradius = 0.002\nedge = 0.0025', "spheres = [[0.0, 0.0, 0.0, 0.002, 1.0]]"), "spheres",
     ["'spheres' in [[template]]: expected an array of 4 numbers [x, y, z, r] in m", "found 5 elements"]),
    ("periodic_twice", rep("hi = [0.1, 0.1, 0.3]", 'hi = [0.1, 0.1, 0.3]\nperiodic = ["x", "x"]'), "periodic",
     ['axis "x" is listed twice in periodic']),
    ("plane_normal_periodic", rep("hi = [0.1, 0.1, 0.3]", 'hi = [0.1, 0.1, 0.3]\nperiodic = ["z"]'), "normal = [0.0, 0.0, 1.0]",
     ["plane wall 'floor' has a normal with a component along the periodic axis z"]),
    ("stream_starts_after_stage", rep(PACK, 'kind = "stream"\nstage = "fill"\nmix = "pebbles"\nbodies_per_second = 100\nstart = 0.5\nregion = { type = "box", lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1] }'), "start = 0.5",
     ["the stream starts 0.5 s into stage 'fill', which lasts", "it would insert nothing"]),
    ("stream_rate_absurd", rep(PACK, 'kind = "stream"\nstage = "fill"\nmix = "pebbles"\nbodies_per_second = 1e308\nregion = { type = "box", lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1] }'), "bodies_per_second",
     ["the stream would insert 1.000e307 bodies", "above the limit of 1e9"]),
    ("sphere_radius_huge", rep('shape = "tetrahedron"\nradius = 0.002\nedge = 0.0025', "spheres = [[0.0, 0.0, 0.0, 1e308]]"), "spheres",
     ["template 'pebble': sphere 0 has radius 1e308 m (after scale), outside the range [1e-9, 1e6] m"]),
    ("sphere_radius_tiny", rep('shape = "tetrahedron"\nradius = 0.002\nedge = 0.0025', "spheres = [[0.0, 0.0, 0.0, 1e-300]]"), "spheres",
     ["template 'pebble': sphere 0 has radius 1e-300 m (after scale)"]),
    ("long_number_shortened", rep("youngs_modulus = 5e6", "youngs_modulus = -1" + "0" * 300 + ".0"), "youngs_modulus = -1",
     ["youngs_modulus must be > 0 Pa", "found -1e300"]),
    ("fluid_grid_missing", append('\n[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = "data_no_such_grid.csv"\n'), "data_no_such_grid",
     ["cannot read velocity grid file 'data_no_such_grid.csv'"]),
    ("fluid_grid_bad_header", append('\n[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = "data_fluid_grid_bad_header.csv"\n'), "data_fluid_grid_bad_header",
     ["velocity grid file 'data_fluid_grid_bad_header.csv', line 1: the header must be x,y,z,ux,uy,uz"]),
    ("fluid_grid_bad_row", append('\n[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = "data_fluid_grid_bad_row.csv"\n'), "data_fluid_grid_bad_row",
     ["velocity grid file 'data_fluid_grid_bad_row.csv', line 3:", "has 5 values, 6 are needed"]),
    ("fluid_grid_irregular", append('\n[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = "data_fluid_grid_irregular.csv"\n'), "data_fluid_grid_irregular",
     ["velocity grid file 'data_fluid_grid_irregular.csv': not a regular grid"]),
    ("fluid_grid_short", append('\n[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = "data_fluid_grid_short.csv"\n'), "data_fluid_grid_short",
     ["grid does not cover the domain", "its lower z is 0 m, above the domain's -0.01 m"]),
    ("fluid_velocity_two_numbers", append('\n[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = [0, 1]\n'), "velocity = [0, 1]",
     ["'velocity' needs 3 numbers [ux, uy, uz], found 2"]),
]

# the invalid-UTF-8 case is written as bytes
BAD_UTF8 = ("invalid_utf8", "gravity = [0.0, 0.0, -9.81]", ["is not valid UTF-8 text: invalid byte at line 4, column 15"])


def main():
    for f in os.listdir(HERE):
        if f[:2].isdigit() and (f.endswith(".toml") or f.endswith(".expected")):
            os.remove(os.path.join(HERE, f))
    for k, case in enumerate(CASES, start=1):
        name, fn, marker, subs = case[:4]
        nth = case[4] if len(case) > 4 else 1
        text = fn(BASE)
        stem = f"{k:02d}_{name}"
        with open(os.path.join(HERE, stem + ".toml"), "w") as f:
            f.write(text)
        lines = list(subs)
        if marker is not None:
            lines.append(f"{stem}.toml:{line_of(text, marker, nth)}:")
        with open(os.path.join(HERE, stem + ".expected"), "w") as f:
            f.write("\n".join(lines) + "\n")
    k = len(CASES) + 1
    name, marker, subs = BAD_UTF8
    stem = f"{k:02d}_{name}"
    data = BASE.replace(marker, "gravity = [0.0\xff, 0.0, -9.81]").encode("utf-8").replace(b"\xc3\xbf", b"\xff")
    with open(os.path.join(HERE, stem + ".toml"), "wb") as f:
        f.write(data)
    with open(os.path.join(HERE, stem + ".expected"), "w") as f:
        f.write("\n".join(subs) + "\n")
    print(k, "cases")


if __name__ == "__main__":
    main()

//! Values are validated before use: rigid wall materials of density 0, the
//! global `multi_contact` as the walls' default, `rolling_friction` without
//! a rolling model, template coordinates whose mass properties overflow.

use clump_core::multi_contact::MultiContact;
use clump_io::scenario::{self, Files, Scenario};
use std::collections::BTreeMap;
use std::path::Path;

fn parse(
    extra_sim: &str,
    wall_extra: &str,
    contact: &str,
    spheres: &str,
) -> Result<Scenario, String> {
    let text = format!(
        r#"
[simulation]
dt = 1e-5
steps = 10
{extra_sim}
[domain]
lo = [-1.0, -1.0, -1.0]
hi = [1.0, 1.0, 1.0]
[[material]]
name = "rock"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2000
[[material]]
name = "rigid"
youngs_modulus = inf
poisson_ratio = 0.3
density = 0
[contact]
restitution = 0.5
friction = 0.5
{contact}
[[template]]
name = "lump"
material = "rock"
spheres = [{spheres}]
[[wall]]
name = "floor"
material = "rigid"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
{wall_extra}
[[wall]]
name = "roof"
material = "rigid"
type = "plane"
point = [0.0, 0.0, 0.5]
normal = [0.0, 0.0, -1.0]
"#
    );
    scenario::parse(Path::new("v.toml"), text, Files::embedded(BTreeMap::new()))
        .map_err(|e| e.to_string())
}

const LUMP: &str = "[0.0, 0.0, 0.0, 0.01], [0.01, 0.0, 0.0, 0.01]";

/// Two rigid wall materials of density 0 (docs/scenario.md allows it) build
/// a world: the rigid–rigid table entry is never used.
#[test]
fn rigid_walls_with_density_zero_are_accepted() {
    let sc = parse("", "", "", LUMP).unwrap();
    sc.build_world().unwrap_or_else(|e| panic!("{e}"));
}

/// `[simulation] multi_contact` is the default of every wall; a wall's own
/// key overrides it.
#[test]
fn global_multi_contact_is_the_walls_default() {
    let sc = parse(
        "multi_contact = \"average\"",
        "multi_contact = \"sum\"",
        "",
        LUMP,
    )
    .unwrap();
    assert_eq!(sc.config.multi_contact, MultiContact::Average);
    assert_eq!(sc.walls[0].multi_contact, MultiContact::Sum);
    assert_eq!(sc.walls[1].multi_contact, MultiContact::Average);
    let sc = parse("", "", "", LUMP).unwrap();
    assert_eq!(sc.walls[1].multi_contact, MultiContact::Sum);
}

/// `rolling_friction` without `rolling` has no effect: a warning at the key.
#[test]
fn rolling_friction_without_a_rolling_model_is_warned_about() {
    let sc = parse("", "", "rolling_friction = 0.1", LUMP).unwrap();
    let w: Vec<String> = sc.warnings.iter().map(|d| d.to_string()).collect();
    assert!(
        w.iter().any(|m| m
            .contains("warning: rolling_friction = 0.1 has no effect without a rolling model")
            && m.contains("v.toml:")),
        "{w:?}"
    );
    let sc = parse("", "", "rolling_friction = 0.1\nrolling = \"epsd\"", LUMP).unwrap();
    assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
}

/// Sphere centres at ±1e160 m: the inertia overflows; the error names the
/// template instead of passing NaN on.
#[test]
fn overflowing_mass_properties_name_the_template() {
    let e = parse(
        "",
        "",
        "",
        "[1e160, 0.0, 0.0, 1.0], [-1e160, 0.0, 0.0, 1.0]",
    )
    .unwrap_err();
    assert!(
        e.contains("template 'lump': invalid template: the mass properties are not finite"),
        "{e}"
    );
}

/// The contact sub-model keys reach the material pairs: `[contact]` sets
/// JKR, twisting and LIGGGHTS' tangential rule for every pair, a
/// `[[pair]]` switches its pair to SJKR and keeps the rest.
#[test]
fn contact_sub_models_reach_the_pairs() {
    use clump_core::contact::{CohesionLaw, TangentialLaw, TwistingLaw};
    let contact = "tangential = \"liggghts\"\ntwisting = \"marshall\"\ncohesion = \"jkr\"\nsurface_energy = 0.05\n\
                   [[pair]]\nmaterials = [\"rock\", \"rigid\"]\ncohesion = \"sjkr\"\ncohesion_energy_density = 1e5\n";
    let sc = parse("", "", contact, LUMP).unwrap();
    let w = sc.build_world().unwrap_or_else(|e| panic!("{e}"));
    let rock = w.contact_table.get(0, 0).properties();
    assert_eq!(
        rock.cohesion,
        CohesionLaw::Jkr {
            surface_energy: 0.05
        }
    );
    assert_eq!(rock.twisting, TwistingLaw::Marshall);
    assert_eq!(rock.tangential, TangentialLaw::Liggghts);
    let wall = w.contact_table.get(0, 1).properties();
    assert_eq!(
        wall.cohesion,
        CohesionLaw::Sjkr {
            energy_density: 1e5
        }
    );
    assert_eq!(wall.twisting, TwistingLaw::Marshall);
    assert!(w.contact_table.get(0, 0).is_extended() && w.contact_table.any_reach());
    // the skin covers JKR's critical separation
    assert!(w.skin() >= 2.0 * w.contact_table.get(0, 0).reach(0.005));
}

/// `tangential = "mindlin_deresiewicz"` reaches its pair (an extended pair,
/// on the scalar path); a `[[pair]]` that adds twisting to it is refused at
/// the key, with the reason.
#[test]
fn micro_slip_key_reaches_the_pair() {
    use clump_core::contact::TangentialLaw;
    let contact =
        "[[pair]]\nmaterials = [\"rock\", \"rigid\"]\ntangential = \"mindlin_deresiewicz\"\n";
    let sc = parse("", "", contact, LUMP).unwrap();
    let w = sc.build_world().unwrap_or_else(|e| panic!("{e}"));
    let wall = w.contact_table.get(0, 1);
    assert_eq!(
        wall.properties().tangential,
        TangentialLaw::MindlinDeresiewicz
    );
    assert!(wall.is_extended());
    assert_eq!(
        w.contact_table.get(0, 0).properties().tangential,
        TangentialLaw::Clump
    );
    let e = parse(
        "",
        "",
        &format!("{contact}rolling = \"epsd\"\nrolling_friction = 0.1\n"),
        LUMP,
    )
    .unwrap_err();
    assert!(
        e.contains("cannot be combined with rolling = \"epsd\"") && e.contains("history slot"),
        "{e}"
    );
}

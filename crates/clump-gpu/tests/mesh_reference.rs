//! Mesh walls on the device (mesh.rs, shaders/mesh.wgsl) against the CPU
//! path, their reference: beds with static and moving triangle-mesh walls,
//! with `sum` and `average` multi-contact. The criterion is
//! cpu_reference.rs's: 1e-9 of the domain size after 3000 steps.

mod common;

use clump_core::multi_contact::MultiContact;
use clump_core::world::World;
use common::{compare_at, cpu_apart};

/// Per mesh wall of `w`, the CPU path's contacts of its spheres now
/// (`TriMesh::sphere_contacts` in the mesh frame, as `WallShape::contacts`
/// calls it): face, edge and vertex contacts, and spheres whose contacts
/// the merge rule cut (fewer than with the merge angle zero).
fn mesh_features(w: &World) -> Vec<[usize; 4]> {
    use clump_core::wall::mesh::closest::Feature;
    use clump_core::wall::mesh::{MeshContact, MAX_MESH_CONTACTS};
    let sp = w.spheres();
    let mut out = Vec::new();
    for wall in w.walls.iter() {
        let Some((m, pos, q)) = wall.shape.mesh_pose() else {
            continue;
        };
        let mesh = &w.walls.meshes()[m as usize];
        let mut unmerged = mesh.clone();
        unmerged.merge_angle = 0.0;
        let mut count = [0usize; 4];
        for s in 0..sp.state.len() {
            let mut buf = [MeshContact::default(); MAX_MESH_CONTACTS];
            let xl = q.inverse() * (sp.position(s) - pos);
            let k = mesh.sphere_contacts(xl, sp.state[s].radius, 0.0, &mut buf);
            for c in &buf[..k] {
                count[match c.feature {
                    Feature::Face => 0,
                    Feature::Edge(_) => 1,
                    Feature::Vertex(_) => 2,
                }] += 1;
            }
            let all = unmerged.sphere_contacts(xl, sp.state[s].radius, 0.0, &mut buf);
            count[3] += (all > k) as usize;
        }
        out.push(count);
    }
    out
}

/// `bed` on both paths for 3000 steps, compared every 250: the largest
/// difference relative to the box (criterion 1e-9), and per mesh wall its
/// contacts summed over the checkpoints ([`mesh_features`]).
fn mesh_compare(bed: World) -> (f64, Vec<[usize; 4]>, World) {
    let at: Vec<u64> = [1, 10, 100]
        .into_iter()
        .chain((1..=12).map(|k| 250 * k))
        .collect();
    let mut seen: Vec<[usize; 4]> = Vec::new();
    let (worst, _, cpu) = compare_at(bed, &at, |w| {
        let f = mesh_features(w);
        seen.resize(f.len(), [0; 4]);
        for (a, b) in seen.iter_mut().zip(&f) {
            (0..4).for_each(|k| a[k] += b[k]);
        }
    });
    eprintln!("mesh contacts (face, edge, vertex, spheres on several) per mesh wall: {seen:?}");
    (worst, seen, cpu)
}

/// A bed poured onto a static mesh floor (an inverted eight-facet cone:
/// concave seams, its apex a vertex) around a static cuboid mesh post
/// turned by 30° (convex edges and corners, a pose that is not the
/// identity). The CPU run meets spheres on a floor seam (two facets'
/// contacts merged into one) and edge or vertex contacts on the post; the device agrees within 1e-9 of the
/// box. The rule for several triangles matters here: the same bed with
/// the merge angle zero (every near-duplicate edge or vertex contact of
/// the neighbouring triangles kept) ends far from it on the CPU path.
#[test]
fn device_step_agrees_with_the_cpu_path_on_a_static_mesh_floor() {
    let merge = clump_core::wall::mesh::DEFAULT_MERGE_ANGLE;
    let (worst, seen, cpu) = mesh_compare(clump_gpu::bed::mesh_floor_bed(merge));
    assert!(worst < 1e-9, "mesh floor: {worst:e} of the box");
    // the floor's facets meet at 14° (merged into one patch at a seam),
    // the post's edges and corners are convex (edge and vertex contacts)
    assert!(
        seen[0][0] > 0 && seen[0][3] > 0 && seen[1][0] > 0 && seen[1][1] + seen[1][2] > 0,
        "the floor needs contacts merged at its seams, the post edge or vertex contacts: {seen:?}"
    );
    let size = cpu.config.domain.size().max_element();
    let unmerged = clump_gpu::bed::mesh_floor_bed(0.0);
    let moved = cpu_apart(clump_gpu::bed::mesh_floor_bed(merge), unmerged, 3000) / size;
    eprintln!("merge angle 0 instead of 15°: the CPU run moves by {moved:.3e} of the box");
    assert!(
        moved > 1e-6,
        "the merge rule changed the run by only {moved:e}"
    );
}

/// A turning mesh drum (36 facets 10° apart; end caps) and a mesh bar that moves down into the bed while
/// it turns: the device takes the walls' poses from the host (the CPU
/// path's `Wall::advance`), its slots follow the contacts by normal, and
/// it agrees with the CPU path within 1e-9 of the box. Both meshes are
/// touched; the bar by its edges and corners, each found on two or more
/// triangles and merged into one contact.
#[test]
fn device_step_agrees_with_the_cpu_path_with_a_turning_mesh_drum() {
    let (worst, seen, cpu) = mesh_compare(clump_gpu::bed::mesh_drum_bed());
    assert!(worst < 1e-9, "mesh drum: {worst:e} of the box");
    assert!(
        seen.iter().all(|f| f[0] > 0) && seen[1][1] + seen[1][2] > 0 && seen[1][3] > 0,
        "both meshes touched, the bar by edges or corners (each found on two triangles, merged): {seen:?}"
    );
    assert!(cpu.stats.wall_contacts > 0);
}

/// `w` with every mesh wall's `multi_contact` set to `mc` (the other
/// walls and the pairs keep theirs, "sum").
fn mesh_multi(mut w: World, mc: MultiContact) -> World {
    for wall in &mut w.walls {
        if wall.shape.mesh_pose().is_some() {
            wall.multi_contact = mc;
        }
    }
    w
}

/// `average` mesh walls (T-34): a body's touches with one mesh are
/// counted as the CPU path's `count_touches` counts them (each sphere's
/// merged contacts, `WallShape::contacts` with margin 0, summed over the
/// body's spheres), and every touch's load is divided by the count. On
/// the static mesh floor and the turning drum with its moving bar, the
/// switch changes the CPU run (clumps touch a mesh at several spheres at
/// once), and the device agrees with the CPU path within 1e-9 of the box.
#[test]
fn device_step_agrees_with_the_cpu_path_with_average_mesh_walls() {
    let beds: [(&str, fn() -> World); 2] = [
        ("mesh floor", || {
            clump_gpu::bed::mesh_floor_bed(clump_core::wall::mesh::DEFAULT_MERGE_ANGLE)
        }),
        ("mesh drum", clump_gpu::bed::mesh_drum_bed),
    ];
    for (name, bed) in beds {
        let size = bed().config.domain.size().max_element();
        let matters = cpu_apart(
            mesh_multi(bed(), MultiContact::Average),
            mesh_multi(bed(), MultiContact::Sum),
            3000,
        ) / size;
        eprintln!(
            "{name}: average mesh walls against sum on the CPU path: {matters:.3e} of the box"
        );
        assert!(
            matters > 1e-6,
            "{name}: average mesh walls changed the CPU run by only {matters:e}"
        );
        let (worst, seen, _) = mesh_compare(mesh_multi(bed(), MultiContact::Average));
        assert!(worst < 1e-9, "{name}, average: {worst:e} of the box");
        assert!(
            seen.iter().all(|f| f[0] > 0),
            "{name}: every mesh touched: {seen:?}"
        );
    }
}

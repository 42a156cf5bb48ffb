//! What the device path refuses, by scenario key (no device needed).

use clump_core::rotation::RotationScheme;
use clump_gpu::bed::box_bed;
use clump_gpu::support::unsupported;

#[test]
fn the_box_bed_runs_whole_on_the_device() {
    assert_eq!(
        unsupported(&box_bed(3, 2, RotationScheme::NoSquish)),
        vec![]
    );
}

#[test]
fn the_periodic_no_squish_bed_is_refused_at_its_keys() {
    // the shared tetra bed: periodic in x and y
    let w = clump_core::testbed::tetra_lattice_bed(3, 3, 2, None);
    let keys: Vec<String> = unsupported(&w).iter().map(|u| u.key()).collect();
    assert_eq!(keys, vec!["domain.periodic"]);
}

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
fn the_periodic_tetra_lattice_bed_runs_whole_on_the_device() {
    // the library's tetra bed: periodic in x and y
    let w = clump_core::testbed::tetra_lattice_bed(3, 3, 2, None);
    assert_eq!(unsupported(&w), vec![]);
}

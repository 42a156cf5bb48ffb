//! Order of accuracy of every rotation scheme inside the DEM step against a
//! dt → 0 reference (the study lives in `clump_validate::dem_order`, which
//! also puts it in the validation report): (a) an asymmetric clump bouncing
//! and rocking on a plane, (b) a clump–clump collision. Theory: 2 for the
//! velocity-Verlet schemes, 1 for zhao_van_wachem inside the step (torque
//! held over the step). Table: docs/rotation_schemes.md.

use clump_validate::dem_order::{orders, theory, CASES};

#[test]
fn order_of_accuracy_inside_the_dem_step() {
    for (case, what, t_end) in CASES {
        for o in orders(case, 1e-4, t_end).unwrap() {
            eprintln!(
                "case ({case}) {what}, {:?}: errors {:.3e} {:.3e} {:.3e}, orders {:.2} {:.2}",
                o.scheme, o.errors[0], o.errors[1], o.errors[2], o.orders[0], o.orders[1]
            );
            let want = theory(o.scheme);
            assert!(
                (o.orders[1] - want).abs() < 0.3,
                "{:?}: order {} (theory {want})",
                o.scheme,
                o.orders[1]
            );
        }
    }
}

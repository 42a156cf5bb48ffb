//! How the step reads each body's mass, principal moments, added-mass
//! factor and degrees of freedom (force and torque flags, start step): from
//! its template's row of [`PropsTable`] when every body takes its own from
//! there (`PropsTable::uniform`), else from the body arrays. Both give the
//! same values, so the same bits (see `crate::world::props`).

use crate::body::{AxisFlags, Bodies};
use crate::par::shared::SharedMut;
use crate::world::props::{PropsTable, TemplateProps, FREE};
use glam::DVec3;

/// A body's mass properties and degrees of freedom as the step reads them
/// (pointers into the table and the body arrays, which it never writes).
#[derive(Clone, Copy)]
pub(crate) struct BodyProps {
    uniform: bool,
    rows: SharedMut<TemplateProps>,
    tmpl: SharedMut<u32>,
    mass: SharedMut<f64>,
    inertia: SharedMut<DVec3>,
    ff: SharedMut<AxisFlags>,
    tf: SharedMut<AxisFlags>,
    start: SharedMut<u64>,
}

impl BodyProps {
    /// # Safety
    /// `table` was refreshed for `b` as they are, and neither is resized,
    /// moved or written while the result is in use.
    pub(crate) unsafe fn new(table: &mut PropsTable, b: &mut Bodies) -> Self {
        BodyProps {
            uniform: table.uniform,
            rows: SharedMut::new(&mut table.rows),
            tmpl: SharedMut::new(&mut b.template),
            mass: SharedMut::new(&mut b.mass),
            inertia: SharedMut::new(&mut b.inertia),
            ff: SharedMut::new(&mut b.force_flag),
            tf: SharedMut::new(&mut b.torque_flag),
            start: SharedMut::new(&mut b.start_step),
        }
    }

    /// Body `i`'s template index.
    ///
    /// # Safety
    /// `i` is a body index (for this and every method below).
    #[inline(always)]
    pub(crate) unsafe fn template(&self, i: usize) -> usize {
        self.tmpl.read(i) as usize
    }

    /// Body `i`'s template row.
    #[inline(always)]
    unsafe fn row(&self, i: usize) -> TemplateProps {
        self.rows.read(self.template(i))
    }

    /// Body `i`'s mass, kg.
    #[inline(always)]
    pub(crate) unsafe fn mass(&self, i: usize) -> f64 {
        if self.uniform {
            self.row(i).mass
        } else {
            self.mass.read(i)
        }
    }

    /// Body `i`'s half-kick quotients `dt/(2 m f_a)` (s/kg) and
    /// `dt/(2 f_a)` (s) from its template row, when every body takes its
    /// own from there (the same bits as computing them); else None.
    #[inline(always)]
    pub(crate) unsafe fn row_kick(&self, i: usize) -> Option<(f64, f64)> {
        if self.uniform {
            Some(self.row(i).kick)
        } else {
            None
        }
    }

    /// Body `i`'s own mass, kg, from the body arrays.
    #[inline(always)]
    pub(crate) unsafe fn own_mass(&self, i: usize) -> f64 {
        self.mass.read(i)
    }

    /// Body `i`'s added-mass factor.
    #[inline(always)]
    pub(crate) unsafe fn factor(&self, i: usize) -> f64 {
        self.row(i).factor
    }

    /// Body `i`'s principal moments of inertia, kg m².
    #[inline(always)]
    pub(crate) unsafe fn inertia(&self, i: usize) -> DVec3 {
        if self.uniform {
            self.row(i).inertia
        } else {
            self.inertia.read(i)
        }
    }

    /// The inverses of body `i`'s principal moments, 1/(kg m²)
    /// ([`crate::rotation::inverse_inertia`]): its template row's (the same
    /// bits), else computed.
    #[inline(always)]
    pub(crate) unsafe fn inverse_inertia(&self, i: usize) -> DVec3 {
        if self.uniform {
            self.row(i).inv_inertia
        } else {
            crate::rotation::inverse_inertia(self.inertia(i))
        }
    }

    /// Whether body `i` has started by step `step` (else it moves
    /// ballistically, see [`crate::dof`]).
    #[inline(always)]
    pub(crate) unsafe fn started(&self, step: u64, i: usize) -> bool {
        self.uniform || step >= self.start.read(i)
    }

    /// Body `i`'s start step.
    #[inline(always)]
    pub(crate) unsafe fn start(&self, i: usize) -> u64 {
        self.start.read(i)
    }

    /// Body `i`'s force and torque flags (per world axis: kicked by the
    /// force, by the torque).
    #[inline(always)]
    pub(crate) unsafe fn flags(&self, i: usize) -> (AxisFlags, AxisFlags) {
        if self.uniform {
            (FREE, FREE)
        } else {
            (self.ff.read(i), self.tf.read(i))
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::world::props::PER_BODY;
    use glam::DVec3;
    use std::sync::atomic::Ordering;

    /// Held by the tests that set [`PER_BODY`], a global, or read what it
    /// decides, so that they do not run at once.
    static PER_BODY_USERS: std::sync::Mutex<()> = std::sync::Mutex::new(());

    /// A settling tetra bed, whose bodies all carry their template's mass
    /// properties and are free: read from the template table, the state
    /// after 800 steps (with rebuilds) is the same bits as read from the
    /// body arrays.
    #[test]
    fn template_reads_give_the_same_bits_as_per_body_reads() {
        let _only = PER_BODY_USERS.lock().unwrap_or_else(|e| e.into_inner());
        let run = |per_body: bool| {
            let mut w = crate::testbed::tetra_lattice_bed(6, 6, 3, None);
            PER_BODY.store(per_body, Ordering::SeqCst);
            w.run(800).unwrap();
            PER_BODY.store(false, Ordering::SeqCst);
            (
                crate::testbed::state_bits(&w),
                w.rebuilds,
                w.scratch.props.uniform,
            )
        };
        let (table, rebuilds, uniform) = run(false);
        let (arrays, _, _) = run(true);
        assert!(uniform, "the bed's bodies were not read from the table");
        assert!(rebuilds > 2, "only {rebuilds} rebuilds");
        assert!(table == arrays, "the template table changed the bits");
    }

    /// A time step changed between two runs takes effect in the kicks
    /// read from the template table: after 300 steps at dt and 300 at
    /// dt/2, the state is the same bits as with every body read from the
    /// body arrays (whose kicks are computed every step), and not that of
    /// 600 steps at dt.
    #[test]
    fn a_new_time_step_reaches_the_table_kicks() {
        let _only = PER_BODY_USERS.lock().unwrap_or_else(|e| e.into_inner());
        let run = |per_body: bool, halve: bool| {
            let mut w = crate::testbed::tetra_lattice_bed(6, 6, 3, None);
            PER_BODY.store(per_body, Ordering::SeqCst);
            w.run(300).unwrap();
            if halve {
                w.config.dt *= 0.5;
            }
            w.run(300).unwrap();
            PER_BODY.store(false, Ordering::SeqCst);
            (crate::testbed::state_bits(&w), w.scratch.props.uniform)
        };
        let (table, uniform) = run(false, true);
        let (arrays, _) = run(true, true);
        let (same_dt, _) = run(false, false);
        assert!(uniform, "the bed's bodies were not read from the table");
        assert!(table == arrays, "the table's kicks kept the old time step");
        assert!(table != same_dt, "halving the time step changed nothing");
    }

    /// Edits of the body arrays between two runs take effect: a body whose
    /// force and torque flags are all cleared keeps its velocity and
    /// angular momentum exactly (no kick touches them) while it drifts, and
    /// a body given a start step ahead moves ballistically (its velocity
    /// unchanged) until then, although the first run read every body from
    /// the template table.
    #[test]
    fn edits_between_runs_take_effect() {
        // it reads the table's check, which a run with PER_BODY set clears
        let _only = PER_BODY_USERS.lock().unwrap_or_else(|e| e.into_inner());
        let mut w = crate::testbed::tetra_lattice_bed(6, 6, 3, None);
        w.run(300).unwrap();
        assert!(w.scratch.props.uniform);
        let (locked, late) = (5, 9);
        let v = DVec3::new(0.01, -0.02, 0.03);
        let l = DVec3::new(1e-12, 2e-12, -3e-12);
        w.bodies.force_flag[locked] = [false; 3];
        w.bodies.torque_flag[locked] = [false; 3];
        w.bodies.velocity[locked] = v;
        w.bodies.angular_momentum[locked] = l;
        let x0 = w.bodies.position[locked];
        w.bodies.start_step[late] = w.step + 10_000;
        let v_late = DVec3::new(0.0, 0.0, -0.05);
        w.bodies.velocity[late] = v_late;
        let (id_locked, id_late) = (w.bodies.id[locked], w.bodies.id[late]);
        let steps = 400;
        w.run(steps).unwrap();
        let i = w.body_index(id_locked).unwrap();
        assert_eq!(w.bodies.velocity[i], v);
        assert_eq!(w.bodies.angular_momentum[i], l);
        let drift = v * (steps as f64 * w.config.dt);
        assert!((w.bodies.position[i] - x0 - drift).length() < 1e-12 * (1.0 + x0.length()));
        let j = w.body_index(id_late).unwrap();
        assert_eq!(w.bodies.velocity[j], v_late);
        assert!(!w.scratch.props.uniform);
    }
}

//! One contact's law as the engine runs it: the vectorised composition
//! (`SlidingLaw` and the rolling couple) for most pairs, the scalar
//! composition ([`super::extended`]) for a pair whose sub-models only it
//! has. The one place that chooses between them.

use super::model::ContactModel;
use super::{ContactHistory, ContactInput, ContactOutput};

impl ContactModel {
    /// Evaluates one contact (see the [module docs](super) for conventions):
    /// returns the force on `i` (N, world), the rolling couple on `i` (N m,
    /// world), the stored elastic energy (J) and the signed normal force (N),
    /// and updates the history springs in `h`. Requires `c.overlap > 0`; no
    /// allocation. The normal and tangential part is [`super::SlidingLaw::evaluate`],
    /// the rolling part [`Self::rolling_couple`].
    #[inline(always)]
    pub fn evaluate(&self, c: &ContactInput, h: &mut ContactHistory) -> ContactOutput {
        if self.is_extended() {
            return super::extended::evaluate(self, c, h, None);
        }
        let out = self.sliding_law().evaluate(
            c.normal,
            c.overlap,
            c.rel_velocity,
            c.radius,
            c.mass,
            c.dt,
            &mut h.tangential,
        );
        let (torque, e_r) = self.rolling_couple(c, out.normal_force, out.kn, &mut h.rolling);
        ContactOutput {
            force: out.force,
            torque,
            elastic_energy: e_r.map_or(out.energy, |e| out.energy + e),
            normal_force: out.normal_force,
        }
    }

    /// [`Self::evaluate`] with the contact's MDR profile, which a pair of
    /// `tangential = "mdr"` ([`super::mdr`]) reads and updates (the other
    /// laws leave it alone). [`Self::evaluate`] runs such a pair as a new
    /// contact every call (no profile); the engine calls this.
    #[inline]
    pub fn evaluate_slip(
        &self,
        c: &ContactInput,
        h: &mut ContactHistory,
        slip: &mut super::mdr::SlipProfile,
    ) -> ContactOutput {
        if self.is_extended() {
            return super::extended::evaluate(self, c, h, Some(slip));
        }
        self.evaluate(c, h)
    }
}

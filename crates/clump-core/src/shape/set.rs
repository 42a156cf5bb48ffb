//! The templates of a world: each clump template (body frame) with the
//! material of its spheres, and the flat per-sphere tables the step reads.

use super::ClumpTemplate;
use glam::DVec3;

/// The clump templates of a world, in the order they were added (a body's
/// `template` indexes it). Reads like a slice of templates; templates are
/// added through `World::add_template` and never change.
#[derive(Debug, Clone)]
pub struct TemplateSet {
    list: Vec<ClumpTemplate>,
    material: Vec<u16>,
    /// First sphere of each template in [`Self::offset`] and
    /// [`Self::radius`]; `first[n_templates]` = all spheres.
    pub(crate) first: Vec<u32>,
    /// Body-frame offset of each template sphere from its template's centre
    /// of mass, m.
    pub(crate) offset: Vec<DVec3>,
    /// Radius of each template sphere, m.
    pub(crate) radius: Vec<f64>,
    /// Per template: the distance of its farthest sphere centre from its
    /// centre of mass, m (the lever of the skin check's body bound,
    /// [`crate::neighbor::skin::body_displacement_bound`]).
    pub(crate) centre_reach: Vec<f64>,
    /// Most spheres in any template (1 while there is none).
    max_spheres: usize,
}

impl Default for TemplateSet {
    fn default() -> Self {
        TemplateSet {
            list: Vec::new(),
            material: Vec::new(),
            first: vec![0],
            offset: Vec::new(),
            radius: Vec::new(),
            centre_reach: Vec::new(),
            max_spheres: 1,
        }
    }
}

impl TemplateSet {
    /// Material index of template `t`'s spheres.
    pub fn material(&self, t: usize) -> u16 {
        self.material[t]
    }

    /// Materials of all templates, in template order.
    pub fn materials(&self) -> &[u16] {
        &self.material
    }

    /// Appends a template (its material checked by the caller); returns its index.
    pub(crate) fn push(&mut self, template: ClumpTemplate, material: u16) -> u32 {
        self.max_spheres = self.max_spheres.max(template.spheres.len());
        for s in &template.spheres {
            self.offset.push(s.center);
            self.radius.push(s.radius);
        }
        self.first.push(self.offset.len() as u32);
        let reach = template.spheres.iter().map(|s| s.center.length());
        self.centre_reach.push(reach.fold(0.0, f64::max));
        self.list.push(template);
        self.material.push(material);
        self.list.len() as u32 - 1
    }

    /// Most spheres in any template (1 while there is none).
    pub fn max_spheres(&self) -> usize {
        self.max_spheres
    }
}

impl std::ops::Deref for TemplateSet {
    type Target = [ClumpTemplate];
    fn deref(&self) -> &[ClumpTemplate] {
        &self.list
    }
}

impl<'a> IntoIterator for &'a TemplateSet {
    type Item = &'a ClumpTemplate;
    type IntoIter = std::slice::Iter<'a, ClumpTemplate>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.iter()
    }
}

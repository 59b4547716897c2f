//! What a simulator needs beyond the visual meshes, computed once per object and written
//! into every format (URDF, MJCF, USD): each link's collision hulls ([`crate::collision`])
//! and mass properties ([`crate::inertia`]).

use rayon::prelude::*;
use serde::Serialize;

use crate::collision::{decompose, Budget, LinkCollision};
use crate::inertia::{inertial, Inertial, DEFAULT_DENSITY};
use articulated::objects::ArticulatedObject;

/// Settings of the physical properties.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhysicsOptions {
    /// Density, kilograms per cubic object unit.
    pub density: f64,
    /// Collision budget per link.
    pub budget: Budget,
}

impl Default for PhysicsOptions {
    fn default() -> Self {
        Self { density: DEFAULT_DENSITY, budget: Budget::default() }
    }
}

/// One link's collision geometry and mass properties.
#[derive(Debug, Clone)]
pub struct LinkPhysics {
    /// Collision hulls and their fit.
    pub collision: LinkCollision,
    /// Mass properties.
    pub inertial: Inertial,
}

/// The physical properties of every link of `object`, in link order.
pub fn object_physics(object: &ArticulatedObject, options: &PhysicsOptions) -> Vec<LinkPhysics> {
    object
        .links
        .par_iter()
        .map(|link| {
            let collision = decompose(&link.mesh, options.budget);
            let inertial =
                inertial(&link.mesh, collision.closed, &collision.hulls, options.density);
            LinkPhysics { collision, inertial }
        })
        .collect()
}

/// A summary of an object's collision geometry, for `objects.json` and the export report.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CollisionSummary {
    /// Hulls over all links.
    pub hulls: usize,
    /// Most hulls of one link.
    pub max_hulls_per_link: usize,
    /// Largest Hausdorff distance between a link's visual surface and its hulls.
    pub max_hausdorff: f64,
    /// Sum of the hulls' volumes over the sum of the visual meshes' volumes.
    pub volume_ratio: f64,
    /// Total mass, kilograms.
    pub mass: f64,
    /// Links whose mass came from their hulls (open visual mesh).
    pub links_massed_by_hulls: usize,
    /// Links with a fallback (see `meta.json`).
    pub links_with_notes: usize,
}

/// The summary of `links`.
pub fn summary(links: &[LinkPhysics]) -> CollisionSummary {
    let visual: f64 = links.iter().map(|l| l.collision.fit.visual_volume).sum();
    let hull: f64 = links.iter().map(|l| l.collision.fit.hull_volume).sum();
    CollisionSummary {
        hulls: links.iter().map(|l| l.collision.hulls.len()).sum(),
        max_hulls_per_link: links.iter().map(|l| l.collision.hulls.len()).max().unwrap_or(0),
        max_hausdorff: links.iter().map(|l| l.collision.fit.hausdorff).fold(0.0, f64::max),
        volume_ratio: if visual > 0.0 { hull / visual } else { f64::NAN },
        mass: links.iter().map(|l| l.inertial.mass).sum(),
        links_massed_by_hulls: links
            .iter()
            .filter(|l| l.inertial.source == crate::inertia::MassSource::Hulls)
            .count(),
        links_with_notes: links.iter().filter(|l| !l.collision.notes.is_empty()).count(),
    }
}

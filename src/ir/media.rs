//! Participating media as the integrators meet them: which medium a ray
//! segment crosses, the atmosphere's ball, the media around the camera, and
//! the transmittance of a shadow ray through null boundaries and media.
//!
//! The rule for which medium fills a segment (docs/language.md, "Media"):
//! a segment that ends on the inside of a surface with an inside (a
//! transparent object or a `type none` boundary) is in that object's
//! medium (or empty, if it has none); any other segment is in the medium of
//! the innermost object the path entered and has not left ([`MediumStack`]),
//! or in the atmosphere when it is in none. Properly nested objects (a glass
//! of liquid in a foggy box) are thus each filled with their own medium; a
//! path that starts inside objects (the camera in the fog) finds them by a
//! probe ray at the start ([`media_around`]). Overlapping media are not
//! added: where two objects with media overlap, the one entered last fills
//! the overlap (leaving an object removes it from the stack wherever it
//! stands).

use super::{Hit, Scene};
use crate::geometry::{offset_origin, Ray};
use crate::material::medium::Medium;
use crate::material::Material;
use glam::Vec3;

/// The medium around the objects (`atmosphere { }`), filling a ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    /// Its coefficients.
    pub medium: Medium,
    /// The ball's centre.
    pub center: Vec3,
    /// The ball's radius.
    pub radius: f32,
}

impl Atmosphere {
    /// The part `[t0, t1]` of the ray's `[0, t_max]` inside the ball, if
    /// any.
    pub fn clip(&self, ray: &Ray, t_max: f32) -> Option<(f32, f32)> {
        let oc = ray.o - self.center;
        let b = oc.dot(ray.d);
        let c = oc.length_squared() - self.radius * self.radius;
        let disc = b * b - c;
        if disc <= 0.0 {
            return None;
        }
        let root = disc.sqrt();
        let (t0, t1) = ((-b - root).max(0.0), (-b + root).min(t_max));
        (t0 < t1).then_some((t0, t1))
    }
}

/// How deep [`MediumStack`] keeps nested objects (deeper, the outermost are
/// forgotten).
const NESTING: usize = 4;

/// The insides a path has entered and not left, innermost last: the
/// object entered (its [`Scene::inside_key`]) and its medium (`None`: a
/// transparent object without one, empty inside).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MediumStack {
    items: [(u64, Option<Medium>); NESTING],
    len: u8,
}

/// The medium of one segment of a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SegmentMedium {
    /// Inside an object: its medium, if it has one.
    Inside(Option<Medium>),
    /// Outside every object: the atmosphere, if the scene has one.
    Outside,
}

impl MediumStack {
    /// The medium of the innermost object entered, if any was.
    #[inline]
    pub fn innermost(&self) -> SegmentMedium {
        match self.len {
            0 => SegmentMedium::Outside,
            n => SegmentMedium::Inside(self.items[n as usize - 1].1),
        }
    }

    /// Where in the stack the object `key` is, if the path entered it.
    fn find(&self, key: u64) -> Option<usize> {
        self.items[..self.len as usize]
            .iter()
            .rposition(|(k, _)| *k == key)
    }

    /// The medium of a segment along `d` that ends at `hit` on a surface of
    /// `material` (`None`: it leaves the scene): the innermost object's;
    /// at the inside of an object the path did not enter (it started
    /// there), that object's.
    #[inline]
    pub fn segment(&self, scene: &Scene, d: Vec3, end: Option<(&Hit, &Material)>) -> SegmentMedium {
        match end {
            Some((hit, m)) if m.has_inside() && d.dot(hit.n_geo) > 0.0 => {
                match self.find(scene.inside_key(hit)) {
                    Some(_) => self.innermost(),
                    None => SegmentMedium::Inside(m.interior()),
                }
            }
            _ => self.innermost(),
        }
    }

    /// Updates the stack for light crossing the surface of `material` at
    /// `hit` along `d` (entering or leaving its inside): leaving removes
    /// the object left, wherever it stands (overlapping objects are not
    /// left in the order they were entered).
    #[inline]
    pub fn cross(&mut self, scene: &Scene, d: Vec3, hit: &Hit, material: &Material) {
        if !material.has_inside() {
            return;
        }
        let key = scene.inside_key(hit);
        if d.dot(hit.n_geo) < 0.0 {
            self.push(key, material.interior());
        } else if let Some(i) = self.find(key) {
            self.items.copy_within(i + 1..self.len as usize, i);
            self.len -= 1;
        }
    }

    /// The media a ray leaving `hit` along `wi` starts among, for a path
    /// that arrived along `-wo` among these: these, or, where `wi` goes
    /// through the surface (a refraction, a light sampled through rough
    /// glass), those across it.
    #[inline]
    pub fn towards(
        mut self,
        scene: &Scene,
        (hit, material): (&Hit, &Material),
        wo: Vec3,
        wi: Vec3,
    ) -> MediumStack {
        if (wi.dot(hit.n_geo) > 0.0) != (wo.dot(hit.n_geo) > 0.0) {
            self.cross(scene, wi, hit, material);
        }
        self
    }

    fn push(&mut self, key: u64, m: Option<Medium>) {
        if self.len as usize == NESTING {
            self.items.copy_within(1.., 0);
            self.len -= 1;
        }
        self.items[self.len as usize] = (key, m);
        self.len += 1;
    }
}

impl Scene {
    /// Which object a hit's surface bounds, for [`MediumStack`]: the
    /// object of the scene's own primitives (a mesh's triangles are one);
    /// a placed group's primitive with its placement.
    #[inline]
    pub fn inside_key(&self, hit: &Hit) -> u64 {
        if hit.instance == super::instance::NO_INSTANCE {
            self.prim_object
                .get(hit.prim as usize)
                .copied()
                .unwrap_or(hit.prim) as u64
        } else {
            (1 << 63) | ((hit.instance as u64) << 32) | hit.prim as u64
        }
    }
}

/// Null boundaries a shadow ray or a probe crosses at most (a safeguard
/// against a degenerate scene: beyond it, the light counts as blocked).
pub const MAX_CROSSINGS: u32 = 256;

impl Scene {
    /// The part of `ray`'s `[0, t_max]` in a medium of `segment`, and that
    /// medium.
    #[inline]
    pub fn medium_span(
        &self,
        segment: SegmentMedium,
        ray: &Ray,
        t_max: f32,
    ) -> Option<(Medium, f32, f32)> {
        match segment {
            SegmentMedium::Inside(m) => m.map(|m| (m, 0.0, t_max)),
            SegmentMedium::Outside => {
                let a = self.atmosphere.as_ref()?;
                let (t0, t1) = a.clip(ray, t_max)?;
                Some((a.medium, t0, t1))
            }
        }
    }

    /// The fraction of light that arrives along `ray` from distance `t_max`
    /// (a point on a light), through null boundaries and the media between,
    /// starting among `media`; zero when a surface blocks it.
    pub fn transmittance(&self, ray: &Ray, t_max: f32, mut media: MediumStack) -> Vec3 {
        let mut tr = Vec3::ONE;
        let mut ray = *ray;
        let mut left = t_max;
        for _ in 0..MAX_CROSSINGS {
            crate::accel::ray_count::shadow();
            let Some(mut hit) = self.closest_hit(&ray, crate::geometry::T_MIN, left) else {
                if let Some((m, t0, t1)) = self.medium_span(media.innermost(), &ray, left) {
                    tr *= m.transmittance(t1 - t0);
                }
                return tr;
            };
            let mut slot = None;
            let material = self.material_at(&mut hit, -ray.d, ray.time, &mut slot);
            if !material.is_null() {
                return Vec3::ZERO;
            }
            let segment = media.segment(self, ray.d, Some((&hit, material)));
            if let Some((m, t0, t1)) = self.medium_span(segment, &ray, hit.t) {
                tr *= m.transmittance(t1 - t0);
            }
            if tr == Vec3::ZERO {
                return tr;
            }
            media.cross(self, ray.d, &hit, material);
            left -= hit.t;
            ray = Ray::new(offset_origin(hit.p, hit.n_geo, ray.d), ray.d, ray.time);
        }
        Vec3::ZERO
    }
}

/// The insides that hold `point` (the camera), found by walking a probe
/// ray from it through every surface: an object whose surface the probe
/// first meets from inside holds the point. Objects that are not closed
/// may answer wrongly, as for any inside test.
pub fn media_around(scene: &Scene, point: Vec3) -> MediumStack {
    // A direction along no axis, so that it does not run along walls.
    let d = Vec3::new(0.352, 0.613, 0.707).normalize();
    let mut ray = Ray::new(point, d, 0.0);
    let mut entered: Vec<u64> = Vec::new();
    let mut holding: Vec<(u64, Option<Medium>)> = Vec::new();
    for _ in 0..MAX_CROSSINGS {
        let Some(mut hit) = scene.intersect(&ray, crate::geometry::T_MIN, f32::INFINITY) else {
            break;
        };
        let mut slot = None;
        let material = scene.material_at(&mut hit, -d, 0.0, &mut slot);
        if material.has_inside() {
            let key = scene.inside_key(&hit);
            if d.dot(hit.n_geo) < 0.0 {
                entered.push(key);
            } else if let Some(i) = entered.iter().rposition(|&k| k == key) {
                entered.remove(i);
            } else {
                holding.push((key, material.interior()));
            }
        }
        ray = Ray::new(offset_origin(hit.p, hit.n_geo, d), d, 0.0);
    }
    // Met innermost first; the stack keeps the outermost first.
    let mut stack = MediumStack::default();
    for (key, m) in holding.into_iter().rev() {
        stack.push(key, m);
    }
    stack
}

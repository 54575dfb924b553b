//! Choosing the light a shadow ray goes to (next-event estimation), and the
//! probability of that choice for multiple importance sampling.
//!
//! The default rule (`auto`): every light by its estimated contribution at
//! the shading point. A bounded light's is [`LightBounds::importance`]
//! (pbrt-v4's `BVHLightSampler`): its power, from a textured emitter's mean
//! emission over its surface, over the squared distance and by the angles
//! between its emission, the direction and the surface; a light at infinity
//! (background, environment map, sky, directional light) brings an
//! estimate of its irradiance in the same units ([`Selectable::Infinite`]).
//! The lights at infinity and the bounded set as a whole share the choices
//! by those estimates; within the bounded set a light is chosen exactly, by
//! evaluating every light, up to [`EXHAUSTIVE_UP_TO`] lights, and by a
//! light tree above. An estimate can be wrong (a sun whose map is dim on
//! average, a lamp behind a wall): a [`FLOOR`] of the choices is spread
//! evenly over the shares, so that none is starved; every bounded light
//! that can reach a point has a positive estimate there. `power` is the
//! earlier rule (in proportion to power, the power of lights at infinity
//! growing with the scene's extent) and `uniform` is Mitsuba 3's; both are
//! kept for comparison. The measurements behind the choice are in
//! docs/performance.md ("Light selection").

use super::bounds::{CompactLightBounds, LightBounds};
use super::tree::LightTree;
use glam::Vec3;

/// How lights are chosen for shadow rays (`render { light_selection … }`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightSelection {
    /// Lights at infinity and the bounded set share equally; bounded lights
    /// by importance, exhaustively for a few, by the tree for many.
    Auto,
    /// As `Auto`, always through the light tree.
    Bvh,
    /// As `Auto`, always evaluating every bounded light.
    Exhaustive,
    /// In proportion to each light's power (lights at infinity by their
    /// power over the scene's bounding sphere).
    Power,
    /// Every light alike (Mitsuba 3's rule).
    Uniform,
}

named_values!(LightSelection {
    "auto" => Auto,
    "bvh" => Bvh,
    "exhaustive" => Exhaustive,
    "power" => Power,
    "uniform" => Uniform,
});

/// Bounded lights up to which `auto` evaluates every light rather than
/// walking the tree. Measured on a grid of N lamps over a floor (equal-time
/// efficiency, 1 / (time × MAE²)): every light's own estimate beats the
/// tree's up to N = 128 (1.9× at 128), the tree wins from about 200 (1.24×
/// at 256, 2.8× at 512); docs/performance.md, "Light selection".
pub const EXHAUSTIVE_UP_TO: usize = 128;

/// The fraction of the choices spread evenly between the shares (a
/// defensive mixture, Hesterberg 1995): each light at infinity and the
/// bounded set keep at least `FLOOR / k` of the choices (k shares that can
/// reach the point), however small their estimates. Within the bounded set
/// no floor is needed, and one costs much: every light that can reach a
/// point has a positive estimate there (its bounds are conservative), and
/// spreading even 1 % of the choices over a grid of 64 lamps raised the
/// noise by 6 % (docs/performance.md, "Light selection").
pub const FLOOR: f64 = 0.1;

/// What a light is for the selection.
#[derive(Debug, Clone, Copy)]
pub enum Selectable {
    /// At infinity: its estimated contribution at any point is `weight`,
    /// times |n · axis| at a surface of normal n for light arriving along
    /// one direction (`axis` zero: from every direction).
    Infinite {
        /// The estimate (in the units of [`LightBounds::importance`]).
        weight: f64,
        /// The direction its light travels, or zero.
        axis: Vec3,
    },
    /// Bounded, with its bounds.
    Bounded(LightBounds),
}

/// How the bounded lights are chosen among themselves.
#[derive(Debug, Clone)]
enum Bounded {
    /// None.
    Empty,
    /// By importance, evaluating each.
    Exhaustive(Vec<CompactLightBounds>),
    /// By importance, through the tree.
    Tree(LightTree),
}

/// The light selector of a scene.
#[derive(Debug, Clone)]
pub struct LightSampler {
    kind: Kind,
    /// Whether there is exactly one light to choose (checked inline before
    /// anything else: most scenes have one lamp or one sky).
    single: bool,
}

#[derive(Debug, Clone)]
enum Kind {
    /// No lights.
    None,
    /// Probabilities that do not depend on the shading point.
    Table { pmf: Vec<f32>, cdf: Vec<f64> },
    /// Shares for the lights at infinity and the bounded set.
    Importance {
        /// The lights at infinity (indices into the scene's lights), with
        /// their weight and axis (see [`Selectable::Infinite`]).
        infinite: Vec<(u32, f64, Vec3)>,
        /// The bounded lights' indices, in the order of `bounded`.
        bounded_lights: Vec<u32>,
        /// Each light's place in `infinite` or `bounded_lights`.
        slot: Vec<u32>,
        bounded: Bounded,
    },
}

impl Default for LightSampler {
    fn default() -> Self {
        LightSampler {
            kind: Kind::None,
            single: false,
        }
    }
}

impl LightSampler {
    /// The selector for lights described by `selectable`, with `power` the
    /// power of each (used by the `power` rule; its lights at infinity
    /// measured over the scene's extent). `None` when no light has power.
    pub fn new(rule: LightSelection, selectable: &[Selectable], power: &[f64]) -> Option<Self> {
        let count = selectable.len();
        let clean = |p: f64| if p.is_finite() && p > 0.0 { p } else { 0.0 };
        let weights: Vec<f64> = match rule {
            LightSelection::Power => power.iter().map(|&p| clean(p)).collect(),
            _ => power
                .iter()
                .map(|&p| if clean(p) > 0.0 { 1.0 } else { 0.0 })
                .collect(),
        };
        let kind = match rule {
            LightSelection::Power | LightSelection::Uniform => {
                let (pmf, cdf) = table(&weights)?;
                Kind::Table { pmf, cdf }
            }
            LightSelection::Auto | LightSelection::Bvh | LightSelection::Exhaustive => {
                let mut infinite = Vec::new();
                let mut bounded_lights = Vec::new();
                let mut bounds = Vec::new();
                let mut slot = vec![u32::MAX; count];
                for (i, s) in selectable.iter().enumerate() {
                    if weights[i] == 0.0 {
                        continue;
                    }
                    match *s {
                        Selectable::Infinite { weight, axis } => {
                            slot[i] = infinite.len() as u32;
                            // A light that emits but is estimated at nothing
                            // still gets a share (as at infinity, below).
                            let weight = if weight > 0.0 && weight.is_finite() {
                                weight
                            } else {
                                f64::MIN_POSITIVE
                            };
                            infinite.push((i as u32, weight, axis));
                        }
                        Selectable::Bounded(b) if b.phi > 0.0 && b.phi.is_finite() => {
                            slot[i] = bounded_lights.len() as u32;
                            bounded_lights.push(i as u32);
                            bounds.push(b);
                        }
                        // A light with power but no estimate: treated as at
                        // infinity, with its share of the floor.
                        Selectable::Bounded(_) => {
                            slot[i] = infinite.len() as u32;
                            infinite.push((i as u32, f64::MIN_POSITIVE, Vec3::ZERO));
                        }
                    }
                }
                if infinite.is_empty() && bounds.is_empty() {
                    return None;
                }
                let tree = match rule {
                    LightSelection::Bvh => true,
                    LightSelection::Exhaustive => false,
                    _ => bounds.len() > EXHAUSTIVE_UP_TO,
                };
                let bounded = if bounds.is_empty() {
                    Bounded::Empty
                } else if tree {
                    Bounded::Tree(LightTree::build(&bounds))
                } else {
                    Bounded::Exhaustive(bounds.iter().map(CompactLightBounds::from).collect())
                };
                Kind::Importance {
                    infinite,
                    bounded_lights,
                    slot,
                    bounded,
                }
            }
        };
        Some(LightSampler {
            kind,
            single: count == 1,
        })
    }

    /// Whether there is no light to choose.
    pub fn is_empty(&self) -> bool {
        matches!(self.kind, Kind::None)
    }

    /// Chooses a light for the point `p` with normal `n` (zero: none) from
    /// `u` in [0, 1): its index and the probability of the choice; `None`
    /// when no light can reach `p`.
    #[inline(always)]
    pub fn sample(&self, p: Vec3, n: Vec3, u: f64) -> Option<(u32, f32)> {
        if self.single {
            // One light: no estimate needed (a light that cannot reach `p`
            // gives no light when sampled).
            return Some((0, 1.0));
        }
        self.sample_among(p, n, u)
    }

    /// [`LightSampler::sample`] among several lights.
    fn sample_among(&self, p: Vec3, n: Vec3, u: f64) -> Option<(u32, f32)> {
        match &self.kind {
            Kind::None => None,
            Kind::Table { pmf, cdf } => {
                let i = cdf.partition_point(|&c| c <= u).min(pmf.len() - 1);
                Some((i as u32, pmf[i]))
            }
            Kind::Importance {
                infinite,
                bounded_lights,
                bounded,
                ..
            } => {
                let set = bounded_weight(bounded, p, n);
                let split = Split::of(infinite, set, n)?;
                // The shares in turn: the lights at infinity, then the
                // bounded set; rounding past the last goes to the last.
                let mut acc = 0.0;
                let mut chosen = None;
                for (k, &(light, own, axis)) in infinite.iter().enumerate() {
                    let share = split.probability(at_infinity(own, axis, n));
                    if share > 0.0 {
                        chosen = Some((k, share));
                        if u < acc + share {
                            return Some((light, share as f32));
                        }
                        acc += share;
                    }
                }
                let share = split.probability(set);
                if share <= 0.0 {
                    let (k, share) = chosen?;
                    return Some((infinite[k].0, share as f32));
                }
                let u = ((u - acc) / share).clamp(0.0, 1.0 - f64::EPSILON / 2.0);
                let (i, pmf) = match bounded {
                    Bounded::Empty => return None,
                    Bounded::Exhaustive(bounds) => sample_exhaustive(bounds, set, p, n, u)?,
                    Bounded::Tree(tree) => tree.sample(p, n, u)?,
                };
                Some((bounded_lights[i as usize], (pmf * share) as f32))
            }
        }
    }

    /// The probability that [`LightSampler::sample`] at `p`, `n` chooses
    /// `light`.
    #[inline(always)]
    pub fn pmf(&self, p: Vec3, n: Vec3, light: u32) -> f32 {
        if self.single {
            return 1.0;
        }
        self.pmf_among(p, n, light)
    }

    /// [`LightSampler::pmf`] among several lights.
    fn pmf_among(&self, p: Vec3, n: Vec3, light: u32) -> f32 {
        match &self.kind {
            Kind::None => 0.0,
            Kind::Table { pmf, .. } => pmf.get(light as usize).copied().unwrap_or(0.0),
            Kind::Importance {
                infinite,
                slot,
                bounded,
                bounded_lights,
            } => {
                let Some(&s) = slot.get(light as usize) else {
                    return 0.0;
                };
                if s == u32::MAX {
                    return 0.0;
                }
                let set = bounded_weight(bounded, p, n);
                let Some(split) = Split::of(infinite, set, n) else {
                    return 0.0;
                };
                if let Some(&(l, own, axis)) = infinite.get(s as usize) {
                    if l == light {
                        return split.probability(at_infinity(own, axis, n)) as f32;
                    }
                }
                debug_assert_eq!(bounded_lights[s as usize], light);
                let pmf = match bounded {
                    Bounded::Empty => 0.0,
                    Bounded::Exhaustive(bounds) => pmf_exhaustive(bounds, set, p, n, s),
                    Bounded::Tree(tree) => tree.pmf(p, n, s),
                };
                (pmf * split.probability(set)) as f32
            }
        }
    }
}

/// The estimate of a light at infinity at a surface of normal `n` (zero:
/// none): see [`Selectable::Infinite`].
#[inline]
fn at_infinity(weight: f64, axis: Vec3, n: Vec3) -> f64 {
    if axis == Vec3::ZERO || n == Vec3::ZERO {
        weight
    } else {
        weight * n.dot(axis).abs() as f64
    }
}

/// The bounded set's estimate at `p`, `n`: the sum of its lights' (every
/// one evaluated), or the tree's at its root.
fn bounded_weight(bounded: &Bounded, p: Vec3, n: Vec3) -> f64 {
    match bounded {
        Bounded::Empty => 0.0,
        Bounded::Exhaustive(bounds) => bounds.iter().map(|b| b.importance(p, n)).sum(),
        Bounded::Tree(tree) => tree.weight(p, n),
    }
}

/// How the choices split between the shares at a point: the sum of their
/// estimates and how many have one.
struct Split {
    total: f64,
    shares: f64,
}

impl Split {
    /// The split between the lights at infinity and the bounded set at a
    /// surface of normal `n`; `None` when no share can reach it.
    fn of(infinite: &[(u32, f64, Vec3)], bounded: f64, n: Vec3) -> Option<Split> {
        let mut split = Split {
            total: 0.0,
            shares: 0.0,
        };
        let weights = (infinite.iter())
            .map(|&(_, w, axis)| at_infinity(w, axis, n))
            .chain([bounded]);
        for w in weights {
            if w > 0.0 {
                split.total += w;
                split.shares += 1.0;
            }
        }
        (split.shares > 0.0 && split.total.is_finite()).then_some(split)
    }

    /// The probability of the share of estimate `weight`: in proportion to
    /// it, but at least its part of the [`FLOOR`].
    #[inline]
    fn probability(&self, weight: f64) -> f64 {
        if weight > 0.0 {
            (1.0 - FLOOR) * weight / self.total + FLOOR / self.shares
        } else {
            0.0
        }
    }
}

/// Chooses among `bounds` in proportion to importance at `p` (summing to
/// `total` there).
fn sample_exhaustive(
    bounds: &[CompactLightBounds],
    total: f64,
    p: Vec3,
    n: Vec3,
    u: f64,
) -> Option<(u32, f64)> {
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let mut acc = 0.0;
    let mut last = None;
    for (i, b) in bounds.iter().enumerate() {
        let w = b.importance(p, n);
        if w > 0.0 {
            let pmf = w / total;
            acc += pmf;
            last = Some((i as u32, pmf));
            if u < acc {
                break;
            }
        }
    }
    last
}

/// The probability of `light` in [`sample_exhaustive`].
fn pmf_exhaustive(bounds: &[CompactLightBounds], total: f64, p: Vec3, n: Vec3, light: u32) -> f64 {
    if !(total > 0.0 && total.is_finite()) {
        return 0.0;
    }
    bounds[light as usize].importance(p, n) / total
}

/// The probability of choosing each light (its share of the total weight)
/// and the running sums, the last exactly 1; `None` when nothing has
/// weight. Summed in f64, so that no light's power, however large,
/// overflows the table and turns every light off.
fn table(weights: &[f64]) -> Option<(Vec<f32>, Vec<f64>)> {
    let clean = |p: f64| if p.is_finite() && p > 0.0 { p } else { 0.0 };
    let weights: Vec<f64> = weights.iter().map(|&w| clean(w)).collect();
    let total: f64 = weights.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let pmf: Vec<f32> = weights.iter().map(|&p| (p / total) as f32).collect();
    let mut acc = 0.0f64;
    let mut cdf: Vec<f64> = weights
        .iter()
        .map(|&p| {
            acc += p / total;
            acc
        })
        .collect();
    *cdf.last_mut().expect("at least one light") = 1.0;
    Some((pmf, cdf))
}

#[cfg(test)]
#[path = "selection_tests.rs"]
mod tests;

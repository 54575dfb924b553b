//! The multiple-importance weight of one bidirectional strategy (Veach
//! 1997, §10.2): the power heuristic over every strategy that could have
//! sampled the same path, from the densities with which the camera's side
//! and the light's side generate each vertex (pbrt-v4 §13.4.4 writes the
//! same sum as ratios).
//!
//! A path x₀ (camera) … x_k (light) sampled with s light vertices and
//! t = k + 1 − s camera vertices has density
//! p(s) = Π_{i<t} from_camera[i] · light part, where the light part is 1
//! for s = 0 (the camera's path hit the emitter), the next-event density
//! of x_k seen from x_{k−1} for s = 1, and the emission density of x_k
//! times Π_{t≤i<k} from_light[i] for s ≥ 2. Weights need only ratios
//! p(s ± 1) / p(s), so each step swaps one vertex's density.

/// The densities of a whole path's vertices (by area, or by solid angle
/// for a vertex at infinity) and which strategies can sample it.
#[derive(Debug, Default, Clone)]
pub struct PathDensities {
    /// Density of vertex i generated from vertex i − 1 (0 after a delta
    /// lobe; the camera's own entry is unused).
    pub from_camera: Vec<f32>,
    /// Density of vertex i generated from vertex i + 1 (0 after a delta
    /// lobe; the light's own entry is unused: see `emission`).
    pub from_light: Vec<f32>,
    /// Whether the path passes vertex i through a delta lobe (no strategy
    /// may connect there).
    pub delta: Vec<bool>,
    /// Next-event density of the light vertex seen from the one before it
    /// (the light's choice included); 0 where next-event estimation cannot
    /// reach it.
    pub nee: f32,
    /// Density of the light vertex as a light path's start (the light's
    /// choice and its position); 0 for lights that start no paths.
    pub emission: f32,
    /// Whether a camera path's ray can hit the light vertex (not a point).
    pub hittable: bool,
    /// Whether light paths connect to the camera (a pinhole).
    pub camera_connects: bool,
    /// Whether inner connections (s ≥ 2 and t ≥ 2) are strategies.
    pub inner: bool,
}

/// Zero (a delta's density) counts as 1: deltas cancel in the ratios.
#[inline]
fn remap0(p: f32) -> f32 {
    if p != 0.0 && p.is_finite() {
        p
    } else {
        1.0
    }
}

impl PathDensities {
    /// Room for paths of up to `n` vertices (no allocation per strategy).
    pub fn with_capacity(n: usize) -> PathDensities {
        PathDensities {
            from_camera: Vec::with_capacity(n),
            from_light: Vec::with_capacity(n),
            delta: Vec::with_capacity(n),
            ..Default::default()
        }
    }

    /// Clears it for a path of `n` vertices.
    pub fn reset(&mut self, n: usize) {
        self.from_camera.clear();
        self.from_camera.resize(n, 0.0);
        self.from_light.clear();
        self.from_light.resize(n, 0.0);
        self.delta.clear();
        self.delta.resize(n, false);
    }

    /// The index of the light vertex.
    #[inline(always)]
    fn k(&self) -> usize {
        self.from_camera.len() - 1
    }

    /// Whether strategy `s` can sample the path.
    #[inline(always)]
    fn valid(&self, s: usize) -> bool {
        let k = self.k();
        let t = k + 1 - s;
        if t == 0 || (s == 1 && t == 1) || (!self.inner && s >= 2 && t >= 2) {
            return false;
        }
        let light_side_ok = match s {
            0 => self.hittable,
            1 => self.nee > 0.0,
            _ => self.emission > 0.0,
        };
        if !light_side_ok || (t == 1 && !self.camera_connects) {
            return false;
        }
        // A connection joins x_{t−1} and x_t: neither may be a delta.
        s == 0 || (!self.delta[t - 1] && (s == 1 || !self.delta[t]))
    }

    /// p(s + 1) / p(s).
    #[inline(always)]
    fn ratio_up(&self, s: usize) -> f32 {
        let k = self.k();
        let t = k + 1 - s;
        match s {
            0 => remap0(self.nee) / remap0(self.from_camera[k]),
            1 => {
                remap0(self.emission) * remap0(self.from_light[k - 1])
                    / (remap0(self.nee) * remap0(self.from_camera[k - 1]))
            }
            _ => remap0(self.from_light[t - 1]) / remap0(self.from_camera[t - 1]),
        }
    }

    /// The power-heuristic weight of strategy `s` (0 if it cannot sample
    /// the path).
    pub fn weight(&self, s: usize) -> f32 {
        if !self.valid(s) {
            return 0.0;
        }
        let k = self.k();
        let mut sum = 1.0f32;
        let mut r = 1.0f32;
        for up in s..k {
            // Lights that start no paths end the ladder at s = 1.
            if up >= 1 && self.emission <= 0.0 {
                break;
            }
            r *= self.ratio_up(up);
            if self.valid(up + 1) {
                sum += r * r;
            }
        }
        r = 1.0;
        for down in (0..s).rev() {
            r /= self.ratio_up(down);
            if self.valid(down) {
                sum += r * r;
            }
        }
        let w = 1.0 / sum;
        if w.is_finite() {
            w
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path of `n` vertices with densities drawn from `seed`.
    fn random_path(n: usize, seed: u64) -> PathDensities {
        let mut rng = crate::light::test_rng(seed);
        let mut d = PathDensities::default();
        d.reset(n);
        for i in 0..n {
            d.from_camera[i] = 0.1 + 4.0 * rng();
            d.from_light[i] = 0.1 + 4.0 * rng();
            d.delta[i] = i > 0 && i < n - 1 && rng() < 0.2;
        }
        d.nee = 0.1 + 4.0 * rng();
        d.emission = if rng() < 0.8 { 0.1 + 4.0 * rng() } else { 0.0 };
        d.hittable = rng() < 0.8;
        d.camera_connects = rng() < 0.8;
        d.inner = rng() < 0.7;
        d
    }

    #[test]
    fn the_weights_of_the_strategies_that_can_sample_a_path_sum_to_one() {
        for seed in 0..2000u64 {
            let n = 2 + (seed % 9) as usize;
            let d = random_path(n, seed);
            let total: f32 = (0..n).map(|s| d.weight(s)).sum();
            let any = (0..n).any(|s| d.valid(s));
            let want = if any { 1.0 } else { 0.0 };
            assert!((total - want).abs() < 1e-4, "seed {seed}: {total}");
        }
    }

    #[test]
    fn the_weights_follow_the_power_heuristic() {
        // Two vertices after the camera, all densities known: x0 camera,
        // x1 surface, x2 light. p(0) = c1 c2, p(1) = c1 nee, p(2) = e l1.
        let mut d = PathDensities::default();
        d.reset(3);
        d.from_camera = vec![1.0, 2.0, 3.0];
        d.from_light = vec![0.0, 5.0, 0.0];
        d.nee = 7.0;
        d.emission = 11.0;
        d.hittable = true;
        d.camera_connects = true;
        d.inner = true;
        let p = [2.0f32 * 3.0, 2.0 * 7.0, 11.0 * 5.0];
        let sq: f32 = p.iter().map(|x| x * x).sum();
        for (s, p) in p.iter().enumerate() {
            assert!((d.weight(s) - p * p / sq).abs() < 1e-6, "s = {s}");
        }
    }
}

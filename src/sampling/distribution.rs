//! Piecewise-constant distributions over [0, 1) and [0, 1)² (pbrt-v4's
//! `PiecewiseConstant1D` and `PiecewiseConstant2D`, §A.4): sampled by
//! inverting their cumulative sums, a sample's density being its bin's
//! value over the integral. An environment map samples its texels with the
//! 2-D one.

use glam::Vec2;

/// A distribution proportional to a step function of `n` equal bins.
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution1D {
    /// The function's value in each bin (≥ 0).
    func: Vec<f32>,
    /// Cumulative sums, normalised: `cdf[0] = 0`, `cdf[n] = 1`.
    cdf: Vec<f32>,
    /// The function's integral over [0, 1).
    integral: f64,
}

impl Distribution1D {
    /// The distribution of `func` (non-negative, finite, at least one bin);
    /// a function that is zero everywhere is sampled uniformly.
    pub fn new(func: &[f32]) -> Distribution1D {
        assert!(!func.is_empty(), "a distribution needs a bin");
        let n = func.len();
        let mut func: Vec<f32> = func
            .iter()
            .map(|&f| if f.is_finite() { f.max(0.0) } else { 0.0 })
            .collect();
        // Sums in f64: millions of texels would lose their small bins in f32.
        let mut sums = Vec::with_capacity(n + 1);
        let mut total = 0.0f64;
        sums.push(0.0);
        for &f in &func {
            total += f as f64;
            sums.push(total);
        }
        if total <= 0.0 {
            func.iter_mut().for_each(|f| *f = 1.0);
            total = n as f64;
            sums = (0..=n).map(|i| i as f64).collect();
        }
        let cdf = sums.iter().map(|&s| (s / total) as f32).collect();
        Distribution1D {
            func,
            cdf,
            integral: total / n as f64,
        }
    }

    /// The number of bins.
    pub fn len(&self) -> usize {
        self.func.len()
    }

    /// Whether it has no bins (never: see [`Distribution1D::new`]).
    pub fn is_empty(&self) -> bool {
        self.func.is_empty()
    }

    /// The bytes its values take: a bin's value and its cumulative sum,
    /// 4 bytes each.
    pub fn bytes(&self) -> u64 {
        4 * (self.func.len() + self.cdf.len()) as u64
    }

    /// The integral of the function over [0, 1).
    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// A point in [0, 1) for `u` in [0, 1), its density and its bin.
    pub fn sample(&self, u: f32) -> (f32, f32, usize) {
        let n = self.func.len();
        // The last bin whose cumulative sum is ≤ u, among bins of non-zero
        // width (an empty bin is never chosen).
        let bin = (self.cdf.partition_point(|&c| c <= u).max(1) - 1).min(n - 1);
        let (c0, c1) = (self.cdf[bin], self.cdf[bin + 1]);
        let du = if c1 > c0 { (u - c0) / (c1 - c0) } else { 0.5 };
        let mut x = (bin as f32 + du.clamp(0.0, 1.0)) / n as f32;
        // Rounding may carry x into the next bin (or to 1): keep it in its
        // own, where `pdf` will look for it.
        while x > 0.0 && ((x * n as f32) as usize).min(n) > bin {
            x = f32::from_bits(x.to_bits() - 1);
        }
        (x, self.pdf_of_bin(bin), bin)
    }

    /// The density at `x` in [0, 1).
    pub fn pdf(&self, x: f32) -> f32 {
        let n = self.func.len();
        let bin = ((x * n as f32) as usize).min(n - 1);
        self.pdf_of_bin(bin)
    }

    fn pdf_of_bin(&self, bin: usize) -> f32 {
        (self.func[bin] as f64 / self.integral) as f32
    }
}

/// A distribution over [0, 1)² proportional to a step function on a grid
/// of `nu` × `nv` cells: a marginal distribution of rows, and one
/// distribution along u per row.
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution2D {
    rows: Vec<Distribution1D>,
    marginal: Distribution1D,
}

impl Distribution2D {
    /// The distribution of `func`, `nu` values per row, rows in order of v.
    pub fn new(func: &[f32], nu: usize, nv: usize) -> Distribution2D {
        assert_eq!(func.len(), nu * nv, "a grid of nu × nv values");
        let rows: Vec<Distribution1D> = func.chunks(nu).map(Distribution1D::new).collect();
        let marginal: Vec<f32> = rows
            .iter()
            .zip(func.chunks(nu))
            // A row of zeros is uniform within, but never chosen.
            .map(|(r, f)| {
                if f.iter().any(|&x| x > 0.0) {
                    r.integral() as f32
                } else {
                    0.0
                }
            })
            .collect();
        Distribution2D {
            rows,
            marginal: Distribution1D::new(&marginal),
        }
    }

    /// The bytes its values take: 8 a cell and 8 a row
    /// ([`Distribution2D::bytes_for`]).
    pub fn bytes(&self) -> u64 {
        self.rows.iter().map(|r| r.bytes()).sum::<u64>() + self.marginal.bytes()
    }

    /// The bytes a distribution of `nu` × `nv` values takes, before it is
    /// built: each row's values and cumulative sums, and the marginal's.
    pub fn bytes_for(nu: usize, nv: usize) -> u64 {
        let (nu, nv) = (nu as u64, nv as u64);
        4 * (nv * (2 * nu + 1) + 2 * nv + 1)
    }

    /// A point of [0, 1)² for `u` and its density.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (v, pdf_v, row) = self.marginal.sample(u.y);
        let (x, pdf_u, _) = self.rows[row].sample(u.x);
        (Vec2::new(x, v), pdf_v * pdf_u)
    }

    /// The density at `p` in [0, 1)².
    pub fn pdf(&self, p: Vec2) -> f32 {
        let nv = self.rows.len();
        let row = ((p.y * nv as f32) as usize).min(nv - 1);
        self.marginal.pdf(p.y) * self.rows[row].pdf(p.x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::pearson_p_value;
    use crate::sampling::sampler::Sampler;

    #[test]
    fn one_dimension_inverts_its_cdf() {
        let d = Distribution1D::new(&[1.0, 0.0, 3.0, 0.0]);
        assert!((d.integral() - 1.0).abs() < 1e-12);
        // Half the bins hold nothing: never sampled.
        for i in 0..1000 {
            let (x, pdf, bin) = d.sample(i as f32 / 1000.0);
            assert!(bin == 0 || bin == 2, "bin {bin} at {x}");
            assert!((0.0..1.0).contains(&x));
            assert_eq!(pdf, d.pdf(x));
        }
        assert_eq!(d.sample(0.1).2, 0);
        assert_eq!(d.sample(0.3).2, 2);
        // The first quarter is bin 0, its density 1/1 (value over integral).
        assert_eq!(d.sample(0.125).0, 0.125);
        assert_eq!(d.pdf(0.1), 1.0);
        assert_eq!(d.pdf(0.6), 3.0);
        assert_eq!(d.pdf(0.3), 0.0);
        // All zero: uniform.
        let z = Distribution1D::new(&[0.0, 0.0]);
        assert_eq!(z.pdf(0.7), 1.0);
        assert!((z.sample(0.75).0 - 0.75).abs() < 1e-6);
        // The end of the range stays inside it, and every sample in the
        // bin it was drawn from.
        assert!(d.sample(1.0 - f32::EPSILON).0 < 1.0);
        let many = Distribution1D::new(&(0..1000).map(|i| (i % 7) as f32).collect::<Vec<_>>());
        for k in 0..100_000 {
            let (x, pdf, bin) = many.sample(k as f32 / 100_000.0);
            assert_eq!(((x * 1000.0) as usize, pdf), (bin, many.pdf(x)));
        }
    }

    #[test]
    fn two_dimensions_follow_their_pdf() {
        // A peaked grid with an empty row and an empty column.
        let (nu, nv) = (8, 6);
        let f: Vec<f32> = (0..nu * nv)
            .map(|i| {
                let (x, y) = (i % nu, i / nu);
                if y == 2 || x == 5 {
                    0.0
                } else {
                    1.0 + (x * y) as f32 + if (x, y) == (3, 4) { 50.0 } else { 0.0 }
                }
            })
            .collect();
        let d = Distribution2D::new(&f, nu, nv);
        assert_eq!(d.bytes(), Distribution2D::bytes_for(nu, nv));
        let total: f64 = f.iter().map(|&x| x as f64).sum();
        let n = 200_000;
        let mut observed = vec![0.0; nu * nv];
        let mut s = Sampler::new(3, 1, 0, 0);
        for _ in 0..n {
            let (p, pdf) = d.sample(s.next_2d());
            let cell = ((p.y * nv as f32) as usize) * nu + (p.x * nu as f32) as usize;
            observed[cell] += 1.0;
            assert!(
                (pdf - d.pdf(p)).abs() <= 1e-5 * pdf,
                "{pdf} vs {}",
                d.pdf(p)
            );
            // The density is the cell's value over the mean value.
            let want = f[cell] as f64 / (total / (nu * nv) as f64);
            assert!((pdf as f64 - want).abs() < 1e-4 * want);
        }
        let expected: Vec<f64> = f.iter().map(|&x| x as f64 / total * n as f64).collect();
        let p = pearson_p_value(&observed, &expected);
        assert!(p > 1e-3, "χ² p-value {p}");
    }
}

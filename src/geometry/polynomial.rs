//! Real roots of polynomials of degree up to 4 in an interval, by
//! isolating them between the roots of the derivative (each interval
//! between two critical points holds at most one root, where the sign
//! changes) and refining each by Newton's method kept inside its bracket
//! (falling back to bisection): robust where the closed-form quartic
//! (Ferrari) loses every digit, as it does for a torus seen edge-on.
//! The approach of "Ray tracing of quartic surfaces" in Graphics Gems
//! (Hanrahan's polynomial bracketing), without Sturm sequences.

/// Highest degree handled.
pub const MAX_DEGREE: usize = 4;

/// The value of the polynomial `c` (`c[i]` multiplies xⁱ) at `x` (Horner).
pub fn eval(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * x + k)
}

/// The real roots of `c` in `[lo, hi]`, ascending, in `out`; their count.
/// Double roots where the polynomial touches zero without crossing it are
/// found only when it reaches exactly zero there (a grazing ray).
pub fn roots_in(c: &[f64], lo: f64, hi: f64, out: &mut [f64; MAX_DEGREE]) -> usize {
    // The true degree: leading coefficients that vanish drop out.
    let mut n = c.len().min(MAX_DEGREE + 1);
    while n > 0 && c[n - 1] == 0.0 {
        n -= 1;
    }
    let c = &c[..n];
    match n {
        0 | 1 => 0,
        2 => {
            let x = -c[0] / c[1];
            if (lo..=hi).contains(&x) {
                out[0] = x;
                1
            } else {
                0
            }
        }
        _ => {
            let mut d = [0.0; MAX_DEGREE];
            for i in 1..n {
                d[i - 1] = c[i] * i as f64;
            }
            let mut critical = [0.0; MAX_DEGREE];
            let k = roots_in(&d[..n - 1], lo, hi, &mut critical);
            let mut count = 0;
            let mut a = lo;
            let mut fa = eval(c, a);
            for &b in critical[..k].iter().chain(std::iter::once(&hi)) {
                let fb = eval(c, b);
                if fa == 0.0 {
                    if count == 0 || out[count - 1] != a {
                        out[count] = a;
                        count += 1;
                    }
                } else if fa * fb < 0.0 {
                    out[count] = refine(c, a, b, fa);
                    count += 1;
                }
                if count == MAX_DEGREE {
                    return count;
                }
                a = b;
                fa = fb;
            }
            if fa == 0.0 && (count == 0 || out[count - 1] != a) && count < MAX_DEGREE {
                out[count] = a;
                count += 1;
            }
            count
        }
    }
}

/// The root of `c` in `[a, b]`, where it changes sign (`fa` = c(a)).
fn refine(c: &[f64], mut a: f64, mut b: f64, fa: f64) -> f64 {
    let rising = fa < 0.0;
    let mut x = 0.5 * (a + b);
    for _ in 0..100 {
        let f = eval(c, x);
        if f == 0.0 {
            return x;
        }
        // Keep the bracket: the root lies on the side where the sign differs.
        if (f < 0.0) == rising {
            a = x;
        } else {
            b = x;
        }
        let mut df = 0.0;
        for (i, &k) in c.iter().enumerate().skip(1).rev() {
            df = df * x + k * i as f64;
        }
        let newton = x - f / df;
        let next = if newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        if (next - x).abs() <= 1e-15 * x.abs().max(1e-300) || b - a <= 1e-15 * a.abs().max(b.abs())
        {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The coefficients of ∏ (x − rᵢ).
    fn from_roots(roots: &[f64]) -> Vec<f64> {
        let mut c = vec![1.0];
        for &r in roots {
            let mut next = vec![0.0; c.len() + 1];
            for (i, &k) in c.iter().enumerate() {
                next[i + 1] += k;
                next[i] -= r * k;
            }
            c = next;
        }
        c
    }

    #[test]
    fn finds_every_simple_root_in_order() {
        for roots in [
            vec![-3.0, -1.0, 0.5, 2.0],
            vec![1.0, 1.001, 5.0, 100.0],
            vec![-0.25, 0.75],
            vec![0.3, 0.31, 0.32],
            vec![2.0],
        ] {
            let c = from_roots(&roots);
            let mut out = [0.0; MAX_DEGREE];
            let n = roots_in(&c, -10.0, 1000.0, &mut out);
            assert_eq!(n, roots.len(), "{roots:?} → {:?}", &out[..n]);
            for (got, want) in out[..n].iter().zip(&roots) {
                assert!(
                    (got - want).abs() < 1e-9 * want.abs().max(1.0),
                    "{got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn only_roots_inside_the_interval() {
        let c = from_roots(&[-2.0, 1.0, 3.0, 7.0]);
        let mut out = [0.0; MAX_DEGREE];
        let n = roots_in(&c, 0.0, 5.0, &mut out);
        assert_eq!(&out[..n], &[1.0, 3.0]);
        // No real roots: x⁴ + 1.
        assert_eq!(roots_in(&[1.0, 0.0, 0.0, 0.0, 1.0], -5.0, 5.0, &mut out), 0);
        // A lower true degree (leading zeros).
        let n = roots_in(&[-4.0, 0.0, 1.0, 0.0, 0.0], -5.0, 5.0, &mut out);
        assert_eq!(&out[..n], &[-2.0, 2.0]);
    }
}

//! Colour maps: a pattern's value in [0, 1] → a colour, piecewise linear
//! between stops (POV-Ray's `color_map`, Blender's colour ramp). Two stops
//! at 0 and 1 are the plain blend of a texture's two colours; a checker's
//! or stripes' cells read the map at 0 and 1.

use glam::Vec3;

/// Colour stops, their positions non-decreasing in [0, 1] (the checker
/// keeps them so); at least one.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorMap {
    stops: Vec<(f32, Vec3)>,
    /// The colours at 0 and at 1, which two-valued patterns read at every
    /// hit (kept apart: no search).
    ends: [Vec3; 2],
}

impl ColorMap {
    /// The blend from `low` (at 0) to `high` (at 1).
    pub fn two(low: Vec3, high: Vec3) -> ColorMap {
        ColorMap {
            stops: vec![(0.0, low), (1.0, high)],
            ends: [low, high],
        }
    }

    /// A map from stops in non-decreasing order of position; `None` when
    /// there are none or they are out of order.
    pub fn new(stops: Vec<(f32, Vec3)>) -> Option<ColorMap> {
        let ordered = stops.windows(2).all(|w| w[0].0 <= w[1].0);
        if stops.is_empty() || !ordered {
            return None;
        }
        let mut map = ColorMap {
            stops,
            ends: [Vec3::ZERO; 2],
        };
        map.ends = [map.at(0.0), map.at(1.0)];
        Some(map)
    }

    /// The colour at 0 (`odd` false) or at 1 (`odd` true): a checker's or
    /// stripes' cell.
    #[inline]
    pub fn end(&self, odd: bool) -> Vec3 {
        self.ends[odd as usize]
    }

    /// The colour at `t`: the first or last stop's colour outside them, the
    /// linear blend of the two stops around `t` between them (at a repeated
    /// position, the later stop: a sharp edge).
    pub fn at(&self, t: f32) -> Vec3 {
        let s = &self.stops;
        // The first stop strictly after t.
        let i = s.partition_point(|&(x, _)| x <= t);
        if i == 0 {
            return s[0].1;
        }
        if i == s.len() {
            return s[i - 1].1;
        }
        let (x0, c0) = s[i - 1];
        let (x1, c1) = s[i];
        // x1 > t ≥ x0, so the width is positive.
        c0.lerp(c1, (t - x0) / (x1 - x0))
    }

    /// The brightest colour the map gives (by its largest component): what
    /// a textured parameter stands for in the lobes' weights and a light's
    /// power.
    pub fn brightest(&self) -> Vec3 {
        self.stops.iter().map(|s| s.1).fold(Vec3::ZERO, |a, c| {
            if c.max_element() > a.max_element() {
                c
            } else {
                a
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_stops_blend_linearly_and_clamp_outside() {
        let m = ColorMap::two(Vec3::ZERO, Vec3::new(1.0, 2.0, 4.0));
        assert_eq!(m.at(0.0), Vec3::ZERO);
        assert_eq!(m.at(1.0), Vec3::new(1.0, 2.0, 4.0));
        assert_eq!(m.at(0.25), Vec3::new(0.25, 0.5, 1.0));
        assert_eq!(m.at(-3.0), Vec3::ZERO);
        assert_eq!(m.at(7.0), Vec3::new(1.0, 2.0, 4.0));
        assert_eq!(m.brightest(), Vec3::new(1.0, 2.0, 4.0));
    }

    #[test]
    fn several_stops_and_sharp_edges() {
        let (r, g, b) = (Vec3::X, Vec3::Y, Vec3::Z);
        let m = ColorMap::new(vec![(0.2, r), (0.5, g), (0.5, b), (0.8, r)]).unwrap();
        assert_eq!(m.at(0.1), r);
        assert_eq!(m.at(0.2), r);
        assert!((m.at(0.35) - (r + g) * 0.5).length() < 1e-6);
        // At the repeated position the later stop wins: blue from 0.5 on.
        assert_eq!(m.at(0.5), b);
        assert!(m.at(0.4999).y > 0.99);
        assert!((m.at(0.65) - (b + r) * 0.5).length() < 1e-6);
        assert_eq!(m.at(0.9), r);
        assert_eq!(ColorMap::new(vec![(0.5, r)]).unwrap().at(0.0), r);
        assert_eq!((m.end(false), m.end(true)), (r, r));
        let two = ColorMap::new(vec![(0.0, g), (1.0, b)]).unwrap();
        assert_eq!((two.end(false), two.end(true)), (g, b));
    }

    #[test]
    fn unordered_or_empty_stops_are_refused() {
        assert!(ColorMap::new(vec![]).is_none());
        assert!(ColorMap::new(vec![(0.6, Vec3::X), (0.3, Vec3::Y)]).is_none());
    }
}

//! What fills a material's inside: today Beer's-law absorption in glass
//! (the seed paper's "coloured glass"), the seam where participating media
//! will attach.

use glam::Vec3;

/// The medium inside a transmissive material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Medium {
    /// Absorption coefficient per unit length, per channel.
    pub absorption: Vec3,
}

impl Medium {
    /// The fraction of light that survives `distance` inside (Beer–Lambert:
    /// T = exp(−σa d)).
    #[inline]
    pub fn transmittance(&self, distance: f32) -> Vec3 {
        (-self.absorption * distance).exp()
    }
}

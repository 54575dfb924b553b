//! The words of `type principled` that the other material types lack: its
//! checked parameters (defined apart from `scene.rs`, which re-exports
//! them, to keep that file to the scene's shape).

/// The parameters of `type principled` beyond those it shares (each in
/// [0, 1]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipledParams {
    /// `metallic`.
    pub metallic: f64,
    /// `specular`, when given instead of `ior`.
    pub specular: Option<f64>,
    /// `specular_tint`.
    pub specular_tint: f64,
    /// `anisotropic`.
    pub anisotropic: f64,
    /// `sheen`.
    pub sheen: f64,
    /// `sheen_tint`.
    pub sheen_tint: f64,
    /// `clearcoat`.
    pub clearcoat: f64,
    /// `clearcoat_roughness`.
    pub clearcoat_roughness: f64,
}

/// The parameters only `type principled` reads.
pub const PRINCIPLED_ONLY: [&str; 9] = [
    "base_color",
    "metallic",
    "specular",
    "specular_tint",
    "anisotropic",
    "sheen",
    "sheen_tint",
    "clearcoat",
    "clearcoat_roughness",
];

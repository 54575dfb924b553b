//! Which material parameter a texture gives (defined apart from
//! `scene.rs`, which re-exports it).

/// A material parameter a texture can give.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureInput {
    /// `diffuse`
    Diffuse,
    /// `reflection`
    Reflection,
    /// `gloss`
    Gloss,
    /// `transmission`
    Transmission,
    /// `absorption`
    Absorption,
    /// `emission`
    Emission,
    /// `normal_map`: a tangent-space normal map.
    NormalMap,
    /// `bump`: a height field.
    Bump,
    /// `base_color` (of `type principled`).
    BaseColor,
    /// `metallic` (of `type principled`).
    Metallic,
    /// `opacity`: where the surface is there (cutouts).
    Opacity,
}

impl TextureInput {
    /// Every input with its parameter's name.
    pub const ALL: [(&'static str, TextureInput); 11] = [
        ("diffuse", TextureInput::Diffuse),
        ("reflection", TextureInput::Reflection),
        ("gloss", TextureInput::Gloss),
        ("transmission", TextureInput::Transmission),
        ("absorption", TextureInput::Absorption),
        ("emission", TextureInput::Emission),
        ("normal_map", TextureInput::NormalMap),
        ("bump", TextureInput::Bump),
        ("base_color", TextureInput::BaseColor),
        ("metallic", TextureInput::Metallic),
        ("opacity", TextureInput::Opacity),
    ];

    /// Whether its texture holds data rather than colours: an 8-bit image
    /// given to it is read as it is, not decoded from sRGB.
    pub fn is_data(self) -> bool {
        !matches!(
            self,
            TextureInput::Diffuse
                | TextureInput::Reflection
                | TextureInput::Absorption
                | TextureInput::Emission
                | TextureInput::BaseColor
        )
    }
}

//! The checked scene: every expression evaluated, every name resolved, every
//! value in range. Lowering turns it into the render IR.

pub use super::principled::{PrincipledParams, PRINCIPLED_ONLY};
pub use super::texture_input::TextureInput;
pub use crate::geometry::round::RoundDesc;
use crate::span::Span;
use glam::{DMat4, DVec3};
use std::path::{Path, PathBuf};

/// Linear RGB triple.
pub type Rgb = [f64; 3];

pub use crate::ir::settings::{
    Adaptive, IntegratorKind, LightSelection, SamplerKind, Settings, DEFAULT_MIN_SAMPLES,
};

/// The `render { }` block, defaults filled in: the settings as the
/// renderer reads them (the checker has kept each value in its range, so
/// they are safe in f32) and the image the scene asks for.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RenderSettings {
    /// Everything the render reads.
    pub settings: Settings,
    /// Output file named in the scene, relative to the scene file.
    pub output: Option<PathBuf>,
    /// Where the scene names it.
    pub output_span: Option<crate::span::Span>,
}

/// A texture, checked: its pattern's colours, the space it reads and its
/// transforms (pattern space → the space it reads).
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// What it computes.
    pub kind: TextureKind,
    /// Its colour map: stops (position in [0, 1], colour) in order; a
    /// checker's even cells read it at 0, odd ones at 1.
    pub colors: Vec<(f64, Rgb)>,
    /// `uv`, `object` or `world`.
    pub space: TextureSpace,
    /// The texture's transforms, in the order written.
    pub transform: DMat4,
    /// Where the texture is written.
    pub span: Span,
}

/// The kinds of texture.
#[derive(Debug, Clone, PartialEq)]
pub enum TextureKind {
    /// `checker { }`
    Checker,
    /// `gradient { }`: a ramp along x.
    Gradient,
    /// `stripes { }`: bands across x.
    Stripes,
    /// `noise`, `turbulence`, `marble` or `wood { … }`.
    Noise {
        /// Which pattern.
        kind: crate::texture::noise::NoiseKind,
        /// Its octaves and bands (each in its range, safe in f32).
        params: crate::texture::noise::NoiseParams,
    },
    /// `image { file … }`
    Image {
        /// The image file (relative to the scene file once resolved).
        path: PathBuf,
        /// The file as the scene (or the mesh file naming it) writes it:
        /// what messages say, whatever folder the scene was opened from.
        named: String,
        /// Where its name is written.
        path_span: Span,
        /// `repeat`, `clamp` or `mirror`.
        wrap: crate::texture::image::Wrap,
        /// How its values are encoded, when the scene says (`None`: by the
        /// file and the parameter: 8-bit colours sRGB, the rest linear).
        color_space: Option<ColorSpace>,
        /// Whether `path` is relative to the scene file's folder yet.
        resolved: bool,
        /// Multiplies every texel (a glTF material's factor; 1 otherwise).
        factor: Rgb,
        /// The channel read where one number is wanted (`None`: the
        /// luminance).
        channel: Option<crate::texture::image::Channel>,
        /// Where a model file (an MTL library, a glTF) names the image,
        /// for its errors; `None`: the scene does.
        origin: Option<std::sync::Arc<crate::diag::NamedIn>>,
    },
}

/// How an image's values are encoded (`image { color_space … }`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ColorSpace {
    /// The sRGB curve: values are decoded to linear light.
    Srgb,
    /// Linear: values are read as they are.
    Linear,
}

named_values!(ColorSpace {
    "srgb" => Srgb,
    "linear" => Linear,
});

impl Texture {
    /// Resolves the file an image texture reads against the folder of the
    /// scene file that names it (once: a resolved path is absolute or
    /// already joined, and joining again would double a relative folder).
    pub fn resolve_path(&mut self, folder: &Path) {
        if let TextureKind::Image { path, resolved, .. } = &mut self.kind {
            if !*resolved {
                *path = folder.join(&*path);
                *resolved = true;
            }
        }
    }

    /// The brightest colour of its map (by largest component): what the
    /// parameter it gives stands for in checks and weights.
    pub fn brightest(&self) -> Rgb {
        let max = |c: &Rgb| c.iter().cloned().fold(0.0, f64::max);
        (self.colors.iter().map(|s| s.1))
            .fold([0.0; 3], |a, c| if max(&c) > max(&a) { c } else { a })
    }
}

/// The coordinates a texture reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureSpace {
    /// The surface's texture coordinates.
    Uv,
    /// The object's own frame.
    Object,
    /// The world.
    World,
}

named_values!(TextureSpace {
    "uv" => Uv,
    "object" => Object,
    "world" => World,
});

/// The `camera { }` block.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: DVec3,
    /// Point looked at.
    pub look_at: DVec3,
    /// Up direction.
    pub up: DVec3,
    /// Full vertical field of view in degrees.
    pub fov: f64,
    /// Lens radius (0 = pinhole).
    pub aperture: f64,
    /// Distance of the plane in focus.
    pub focus_distance: f64,
    /// Shutter open and close times.
    pub shutter: (f64, f64),
    /// Where the block is.
    pub span: Span,
}

/// The word of a material's `type`: which scattering model it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaterialType {
    /// The paper's weighted mix of lobes (no `type`).
    Mix,
    /// A metal.
    Conductor,
    /// `diffuse` under a dielectric coat.
    Plastic,
    /// Glass.
    Dielectric,
    /// A thin pane.
    ThinDielectric,
    /// Burley's principled model.
    Principled,
    /// No surface: the boundary of a medium.
    None,
}

named_values!(MaterialType {
    "mix" => Mix,
    "conductor" => Conductor,
    "plastic" => Plastic,
    "dielectric" => Dielectric,
    "thin_dielectric" => ThinDielectric,
    "principled" => Principled,
    "none" => None,
});

/// A material's scattering model (`type`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MaterialKind {
    /// The paper's weighted mix of lobes.
    Mix,
    /// A metal: a named one, or one of complex index `eta` + i`k`.
    Conductor {
        /// The named metal, if one is named (its constants are the
        /// renderer's).
        preset: Option<crate::material::conductor::Metal>,
        /// Real part of the index per channel.
        eta: Rgb,
        /// Extinction coefficient per channel.
        k: Rgb,
    },
    /// `diffuse` under a dielectric coat of index `ior`.
    Plastic,
    /// Glass of index `ior`, smooth or rough (`gloss`).
    Dielectric,
    /// A thin pane of index `ior`.
    ThinDielectric,
    /// Burley's principled model: its base colour is `diffuse`, its
    /// roughness `gloss`, its refracting share `transmission`.
    Principled(PrincipledParams),
    /// No surface (`type none`): light passes through; the boundary of
    /// the medium inside.
    None,
}

/// A material, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Name (`None` for inline materials).
    pub name: Option<String>,
    /// Its scattering model.
    pub kind: MaterialKind,
    /// Whether glossy reflection gets the multiple-scattering compensation.
    pub multiscatter: bool,
    /// Lambertian albedo.
    pub diffuse: Rgb,
    /// Specular (mirror or glossy) reflectance.
    pub reflection: Rgb,
    /// The parameters given textures (a textured colour or number above
    /// holds the texture's brightest value).
    pub textures: Vec<(TextureInput, Texture)>,
    /// World units of displacement per unit of the `bump` texture.
    pub bump_height: f64,
    /// Roughness of the reflection lobe, 0 = mirror.
    pub gloss: f64,
    /// Weight of the smooth dielectric lobe.
    pub transmission: f64,
    /// Index of refraction inside.
    pub ior: f64,
    /// Index of refraction of the medium outside (1: air).
    pub ior_outside: f64,
    /// A metal's GGX roughness along ∂p/∂u and ∂p/∂v, when given as such
    /// (`roughness`) rather than through `gloss`.
    pub roughness: Option<[f64; 2]>,
    /// Absorption coefficient per unit length of the medium inside
    /// (Beer's law in glass).
    pub absorption: Rgb,
    /// Scattering coefficient per unit length of the medium inside.
    pub scattering: Rgb,
    /// The medium's Henyey–Greenstein asymmetry g.
    pub anisotropy: f64,
    /// Emitted radiance.
    pub emission: Rgb,
    /// Whether emission leaves both sides.
    pub two_sided: bool,
    /// How much of the surface is there (1: all of it; a textured opacity
    /// holds its texture's brightest value here).
    pub opacity: f64,
    /// The opacity at and above which the surface is wholly there, below
    /// which it is not (`None`: fractions pass at random).
    pub opacity_cutoff: Option<f64>,
    /// Whether the diffuse colour is multiplied by the mesh's vertex
    /// colours.
    pub vertex_color: bool,
    /// The normal map's tangent and bitangent components' scale.
    pub normal_scale: f64,
    /// Where it is declared.
    pub span: Span,
}

impl Material {
    /// The default material of an object without one: grey diffuse.
    pub fn default_at(span: Span) -> Material {
        Material {
            name: None,
            kind: MaterialKind::Mix,
            multiscatter: true,
            diffuse: [0.5; 3],
            reflection: [0.0; 3],
            textures: Vec::new(),
            bump_height: 0.0,
            gloss: 0.0,
            transmission: 0.0,
            ior: 1.5,
            ior_outside: 1.0,
            roughness: None,
            absorption: [0.0; 3],
            scattering: [0.0; 3],
            anisotropy: 0.0,
            emission: [0.0; 3],
            two_sided: false,
            opacity: 1.0,
            opacity_cutoff: None,
            vertex_color: false,
            normal_scale: 1.0,
            span,
        }
    }

    /// Whether rays pass its surface anywhere (an opacity texture, or an
    /// opacity below 1 or below its cutoff).
    pub fn is_cut_out(&self) -> bool {
        let textured = (self.textures.iter()).any(|(i, _)| *i == TextureInput::Opacity);
        textured || self.opacity < self.opacity_cutoff.unwrap_or(1.0)
    }

    /// Resolves the files its textures read against the scene file's folder.
    pub fn resolve_paths(&mut self, folder: &Path) {
        for (_, t) in &mut self.textures {
            t.resolve_path(folder);
        }
    }

    /// Whether it emits light.
    pub fn is_emissive(&self) -> bool {
        self.emission.iter().any(|&c| c > 0.0)
    }
}

/// A shape before transforms.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Centre and radius.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius.
        radius: f64,
    },
    /// Infinite plane through a point.
    Plane {
        /// A point on the plane.
        point: DVec3,
        /// Normal.
        normal: DVec3,
    },
    /// Parallelogram `corner + s·edge1 + t·edge2`.
    Quad {
        /// Corner.
        corner: DVec3,
        /// First edge.
        edge1: DVec3,
        /// Second edge.
        edge2: DVec3,
    },
    /// Disk.
    Disk {
        /// Centre.
        center: DVec3,
        /// Normal.
        normal: DVec3,
        /// Radius.
        radius: f64,
    },
    /// Triangle with counter-clockwise vertices.
    Triangle {
        /// Vertices.
        v: [DVec3; 3],
    },
    /// Axis-aligned box.
    Box {
        /// Minimum corner.
        min: DVec3,
        /// Maximum corner.
        max: DVec3,
    },
    /// A curved shape of the renderer's registry (a cone or cylinder, a
    /// torus), described in the object's frame.
    Round(RoundDesc),
    /// Triangle mesh from a file.
    Mesh {
        /// Resolved path.
        path: PathBuf,
        /// The file as the scene writes it (what messages say, whatever
        /// folder the scene was opened from).
        named: String,
        /// Where the file name is written.
        path_span: Span,
        /// Interpolate vertex normals when the file has them.
        smooth: bool,
        /// A glTF file's node (by name) whose subtree alone is placed,
        /// with where the name is written.
        node: Option<(String, Span)>,
        /// Only the faces of this material of the file's own (an OBJ's
        /// `usemtl` group, by index into its libraries' materials; `u32::MAX`
        /// for the faces without one): set by lowering, which splits a mesh
        /// by the materials its file gives (`lower::obj_materials`).
        group: Option<u32>,
        /// The file's materials replaced by name (`materials { … }`).
        swaps: Vec<MaterialSwap>,
    },
}

/// One of a mesh file's materials replaced by the scene's.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialSwap {
    /// The material's name in the file.
    pub name: String,
    /// Where the name is written.
    pub span: Span,
    /// The scene's material (index into [`Scene::materials`]).
    pub material: usize,
}

impl Shape {
    /// The shape's name if it is stored exactly by centres, axes and
    /// radii, and so keeps its kind only under similarity transforms.
    pub fn round_kind(&self) -> Option<&'static str> {
        Some(match self {
            Shape::Sphere { .. } => "sphere",
            Shape::Disk { .. } => "disk",
            Shape::Round(r) => r.name(),
            _ => return None,
        })
    }
}

/// An object: a shape with a material, a transform and optional motion.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// The shape in object space.
    pub shape: Shape,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// Object-to-world transform.
    pub transform: DMat4,
    /// Linear motion per unit of shutter time.
    pub velocity: DVec3,
    /// Where the object is.
    pub span: Span,
}

/// A light that is not a shape.
#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    /// Isotropic point light with intensity in W/sr.
    Point {
        /// Position.
        position: DVec3,
        /// Radiant intensity.
        intensity: Rgb,
    },
    /// Spot light.
    Spot {
        /// Position.
        position: DVec3,
        /// Unit direction of the cone's axis.
        direction: DVec3,
        /// Radiant intensity on the axis.
        intensity: Rgb,
        /// Half-angle of the cone, degrees: no light outside it.
        angle: f64,
        /// Half-angle of the hot spot, degrees: full light inside it, a
        /// smooth fall-off from it to `angle`.
        hotspot: f64,
    },
    /// Light from a direction at infinity.
    Directional {
        /// Unit direction the light travels in.
        direction: DVec3,
        /// Irradiance on a surface facing the light.
        irradiance: Rgb,
    },
}

impl Light {
    /// The light placed by a transform (group → world): positions and a
    /// spot light's aim move as points, a direction turns with the linear
    /// part and is normalised again. Intensities, irradiance and a spot
    /// light's angles are kept: scaling a lamp does not make it brighter
    /// (a scaled emissive shape does get brighter: it has more area). A
    /// transform that flattens a direction to nothing (a glTF node scaled
    /// by 0) keeps it as it was.
    pub fn placed(&self, m: &DMat4) -> Light {
        let turn = |d: DVec3| m.transform_vector3(d).try_normalize().unwrap_or(d);
        match self.clone() {
            Light::Point {
                position,
                intensity,
            } => Light::Point {
                position: m.transform_point3(position),
                intensity,
            },
            Light::Spot {
                position,
                direction,
                intensity,
                angle,
                hotspot,
            } => Light::Spot {
                position: m.transform_point3(position),
                // The aim (position + direction) moves as a point; the
                // difference of two moved points is the turned direction.
                direction: turn(direction),
                intensity,
                angle,
                hotspot,
            },
            Light::Directional {
                direction,
                irradiance,
            } => Light::Directional {
                direction: turn(direction),
                irradiance,
            },
        }
    }

    /// Where the light is (`None` for a directional light, at infinity).
    pub fn position(&self) -> Option<DVec3> {
        match self {
            Light::Point { position, .. } | Light::Spot { position, .. } => Some(*position),
            Light::Directional { .. } => None,
        }
    }
}

/// A homogeneous medium's coefficients, checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MediumParams {
    /// Absorption coefficient per unit length (σa).
    pub absorption: Rgb,
    /// Scattering coefficient per unit length (σs).
    pub scattering: Rgb,
    /// Henyey–Greenstein g: 0 scatters evenly, > 0 forward, < 0 back.
    pub anisotropy: f64,
}

/// The `atmosphere { }` block: a medium filling the space around the
/// objects, within a ball.
#[derive(Debug, Clone, PartialEq)]
pub struct Atmosphere {
    /// Its coefficients.
    pub medium: MediumParams,
    /// The centre of the ball it fills, if given (else that of the
    /// objects, the camera and the lights).
    pub center: Option<DVec3>,
    /// The ball's radius, if given (else just around the objects, the
    /// camera and the lights).
    pub radius: Option<f64>,
    /// Where the block is.
    pub span: Span,
}

/// The `sky { }` block: a daylight sky and its sun.
#[derive(Debug, Clone, PartialEq)]
pub struct Sky {
    /// Unit direction towards the sun (above the horizon).
    pub sun_direction: DVec3,
    /// Atmospheric turbidity, 1 to 10.
    pub turbidity: f64,
    /// Ground albedo per channel, 0 to 1.
    pub albedo: Rgb,
    /// Scale of the sky's radiance.
    pub intensity: Rgb,
    /// Scale of the sun's radiance.
    pub sun_intensity: Rgb,
    /// Where the block is.
    pub span: Span,
}

/// The `environment { }` block: light from an image all around.
#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    /// The image (relative to the scene file's folder once resolved).
    pub path: PathBuf,
    /// The file's name as the scene writes it (what messages say).
    pub name: String,
    /// Where its name is written.
    pub path_span: Span,
    /// The radiance scale (per channel).
    pub intensity: Rgb,
    /// The map's rotations, in the order written.
    pub rotation: DMat4,
    /// Where the block is.
    pub span: Span,
}

/// A checked scene, ready to lower.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Settings.
    pub render: RenderSettings,
    /// The camera.
    pub camera: Camera,
    /// Background radiance.
    pub background: Rgb,
    /// The environment map, if any (the background is then black).
    pub environment: Option<Environment>,
    /// The daylight sky, if any (the background is then black).
    pub sky: Option<Sky>,
    /// The medium around the objects, if any.
    pub atmosphere: Option<Atmosphere>,
    /// Materials (named and inline), referenced by index.
    pub materials: Vec<Material>,
    /// Objects.
    pub objects: Vec<Object>,
    /// Lights that are not shapes.
    pub lights: Vec<(Light, Span)>,
    /// Groups of objects declared with `group`, referenced by index.
    pub groups: Vec<Group>,
    /// The placements of groups at the top level of the scene.
    pub instances: Vec<Instance>,
    /// The grey material of the objects that name none, if any does (a
    /// mesh whose OBJ file gives materials takes those instead).
    pub default_material: Option<usize>,
}

/// A named group of objects (`group name { … }`), placed by instances.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Its name.
    pub name: String,
    /// Its objects, in the group's frame.
    pub objects: Vec<Object>,
    /// For each object, whether it named no material (it then takes its
    /// instance's, if the instance gives one).
    pub unmaterialled: Vec<bool>,
    /// The groups it places, in its frame.
    pub instances: Vec<Instance>,
    /// Its lights, in its frame, with where each is written: each placement
    /// adds them to the scene's lights, moved by its transforms.
    pub lights: Vec<(Light, Span)>,
    /// How many objects and lights one placement of it makes (its own and
    /// those of the groups it places, through every level; saturating).
    pub placed_objects: u64,
    /// How many lights one placement of it makes, through every level
    /// (saturating): placing a group without any walks none of its tree.
    pub placed_lights: u64,
    /// Where its name is written.
    pub span: Span,
}

impl Group {
    /// Whether the group holds nothing (no object, light or placement).
    pub fn is_empty(&self) -> bool {
        self.objects.is_empty() && self.instances.is_empty() && self.lights.is_empty()
    }
}

/// A placement of a group: `instance name { … }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    /// Index into [`Scene::groups`].
    pub group: usize,
    /// Group-to-parent transform (the world's, or the enclosing group's).
    pub transform: DMat4,
    /// The material of the group's objects that name none.
    pub material: Option<usize>,
    /// Linear motion per unit of shutter time, in the parent's frame.
    pub velocity: DVec3,
    /// Where the instance is written.
    pub span: Span,
}

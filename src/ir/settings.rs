//! Render settings as the renderer reads them: the `render { }` block after
//! command-line overrides, in f32 where the renderer computes with them.
//! Built by lowering from the checked block; the integrator names are
//! defined here once, for the checker, the CLI and the renderer.

use glam::Vec3;

pub use crate::light::selection::LightSelection;
pub use crate::sampling::sampler::SamplerKind;

/// Which light-transport algorithm renders the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Unbiased path tracing with next-event estimation and MIS.
    Path,
    /// Bidirectional path tracing: camera and light paths joined, with MIS.
    Bdpt,
    /// Path tracing and light tracing combined by MIS: `bdpt` without its
    /// inner joins.
    Ptlt,
    /// Recursive ray tracing with shadow rays.
    Whitted,
    /// The paper's blend of Whitted and path tracing.
    Hybrid,
    /// Debug: shading normals as colours.
    Normals,
    /// Debug: the albedo of the first hit.
    Albedo,
    /// Debug: distance to the first hit.
    Depth,
    /// Debug: the texture coordinates of the first hit as red and green.
    Uv,
}

// The one list the checker, the command line, the docs' tables and the
// editors' grammars follow.
named_values!(IntegratorKind {
    "path" => Path,
    "bdpt" => Bdpt,
    "ptlt" => Ptlt,
    "whitted" => Whitted,
    "hybrid" => Hybrid,
    "normals" => Normals,
    "albedo" => Albedo,
    "depth" => Depth,
    "uv" => Uv,
});

impl IntegratorKind {
    /// What `check` and the command line say when [`Self::renders_with`]
    /// leaves a scene to the path integrator.
    pub const MEDIA_LEFT_TO_PATH: &'static str =
        "bdpt and ptlt do not trace media: this scene renders with the path integrator";

    /// Whether it joins camera paths with light paths (`bdpt`, `ptlt`).
    pub fn is_bidirectional(self) -> bool {
        matches!(self, IntegratorKind::Bdpt | IntegratorKind::Ptlt)
    }

    /// The integrator that renders a scene asking for this one: `bdpt` and
    /// `ptlt` leave a scene with media to `path`, which traces them.
    pub fn renders_with(self, has_media: bool) -> IntegratorKind {
        if has_media && self.is_bidirectional() {
            IntegratorKind::Path
        } else {
            self
        }
    }

    /// Whether it is a debug view (no light transport).
    pub fn is_debug_view(self) -> bool {
        matches!(
            self,
            IntegratorKind::Normals
                | IntegratorKind::Albedo
                | IntegratorKind::Depth
                | IntegratorKind::Uv
        )
    }
}

/// The largest image side accepted.
pub const MAX_SIDE: f64 = 16384.0;
/// The largest image area accepted, so a film always fits in memory.
pub const MAX_PIXELS: f64 = 8192.0 * 8192.0;

/// The settings a render reads.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples (camera paths) per pixel.
    pub samples: u32,
    /// Path segments at most (Mitsuba convention).
    pub max_depth: u32,
    /// Light transport algorithm.
    pub integrator: IntegratorKind,
    /// Seed of every random stream.
    pub seed: u64,
    /// Which numbers the samples draw.
    pub sampler: SamplerKind,
    /// The paper's constant ambient term (biased), added at diffuse hits.
    pub ambient: Vec3,
    /// Path depth (in segments) from which Russian roulette may end a path.
    pub rr_depth: u32,
    /// Weight of the Whitted estimate in the hybrid blend.
    pub hybrid_weight: f32,
    /// Largest RGB component of each indirect contribution (biased; `None` = off; see `integrator::path`).
    pub clamp: Option<f32>,
    /// Whether the path integrator samples lights directly (NEE + MIS); `false` is the paper's naive mode.
    pub light_sampling: bool,
    /// How shadow rays choose their light.
    pub light_selection: LightSelection,
    /// Shadow rays per area light and hit in the Whitted integrator.
    pub light_samples: u32,
    /// Exposure in stops applied when writing PNG.
    pub exposure: f32,
    /// A time budget in seconds: a batch render stops when it is spent or
    /// at `samples`, whichever comes first (`None`: samples alone).
    pub time: Option<f64>,
    /// Adaptive sampling: a pixel stops once its noise falls below a
    /// threshold (`None`: every pixel takes `samples`).
    pub adaptive: Option<Adaptive>,
}

/// Adaptive sampling's settings (`noise_threshold`, `min_samples`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    /// The noise below which a pixel stops: Cycles's measure (the half
    /// films' difference over the square root of the brightness).
    pub threshold: f32,
    /// Samples every pixel takes before any may stop.
    pub min_samples: u32,
}

/// `min_samples` when a scene names only `noise_threshold`.
pub const DEFAULT_MIN_SAMPLES: u32 = 16;

/// The most samples per pixel a render takes (`samples`, `--spp`): also
/// what a time budget without samples is given.
pub const MAX_SAMPLES: u32 = 1_000_000;

/// The longest time budget accepted, in seconds (a year).
pub const MAX_TIME: f64 = 365.0 * 24.0 * 3600.0;

impl Default for Settings {
    /// The defaults of a `render { }` block.
    fn default() -> Self {
        Settings {
            width: 512,
            height: 512,
            samples: 16,
            max_depth: 8,
            integrator: IntegratorKind::Path,
            seed: 0,
            sampler: SamplerKind::Sobol,
            ambient: Vec3::ZERO,
            rr_depth: 5,
            hybrid_weight: 0.5,
            clamp: None,
            light_sampling: true,
            light_selection: LightSelection::Auto,
            light_samples: 4,
            exposure: 0.0,
            time: None,
            adaptive: None,
        }
    }
}

//! The checked `environment { }` → an environment map: its image read
//! through the compile's images, its rotations as a frame; and the checked
//! `sky { }` → the daylight sky's light.

use crate::check;
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::light::environment::EnvironmentMap;
use crate::light::sky::{SkyParameters, SunSky, SUN_APERTURE_DEGREES};
use crate::light::Light;
use crate::lower::image::{Encoding, Images};
use crate::source::Files;
use glam::{DMat3, DVec3, Mat3, Vec3};
use std::sync::Arc;

/// The environment map of `e`; `None` after an error in `diags` (a
/// missing or unreadable image, one of a single row). An image that is not
/// twice as wide as high is a warning in `warnings`.
pub fn lower_environment(
    e: &check::scene::Environment,
    (images, files): (&mut Images, &dyn Files),
    diags: &mut Diagnostics,
    warnings: &mut Diagnostics,
) -> Option<Arc<EnvironmentMap>> {
    let sampling = |image: &crate::texture::image::Image| {
        EnvironmentMap::sampling_bytes(image.width, image.height)
    };
    let image = match images
        .get(files, &e.path, Encoding::ByFile)
        .and_then(|image| {
            // Its distribution counts with the scene's images.
            images.charge(sampling(&image), "its sampling distribution")?;
            Ok(image)
        }) {
        Ok(image) if image.height >= 2 => image,
        Ok(_) => {
            diags.push(
                Diagnostic::error(
                    codes::IMAGE_FILE,
                    format!("`{}` has one row of texels", e.name),
                    e.path_span,
                )
                .with_label("an environment map needs two rows at least")
                .with_help("use an equirectangular image, twice as wide as high"),
            );
            return None;
        }
        Err(why) => {
            let help = crate::check::image_files::ENVIRONMENT_HELP;
            diags.push(crate::check::image_files::unreadable(
                &e.name,
                e.path_span,
                why,
                help,
            ));
            return None;
        }
    };
    if image.width != 2 * image.height {
        warnings.push(
            Diagnostic::warning(
                codes::NOT_LATLONG,
                format!(
                    "an environment map of {} × {} texels is not equirectangular",
                    image.width, image.height
                ),
                e.path_span,
            )
            .with_label("not twice as wide as high")
            .with_help("an equirectangular (latitude-longitude) image spans 360° across and 180° down: twice as wide as high; this one is stretched"),
        );
    }
    // The rotations' 3 × 3 part (the checker accepts rotations only).
    let m = DMat3::from_mat4(e.rotation);
    let to_world = Mat3::from_cols(
        m.x_axis.normalize().as_vec3(),
        m.y_axis.normalize().as_vec3(),
        m.z_axis.normalize().as_vec3(),
    );
    Some(Arc::new(EnvironmentMap::new(image, to_world)))
}

/// The checked sky as the renderer's light (`None` when it gives no light).
pub fn lower_sky(s: &check::scene::Sky) -> Option<Light> {
    let v = |c: [f64; 3]| DVec3::from_array(c).as_vec3();
    let sky = SunSky::new(&SkyParameters {
        sun_direction: s.sun_direction.as_vec3(),
        turbidity: s.turbidity as f32,
        albedo: v(s.albedo),
        sky_scale: v(s.intensity),
        sun_scale: v(s.sun_intensity),
        sun_aperture: SUN_APERTURE_DEGREES,
    })?;
    (sky.mean() != Vec3::ZERO).then(|| Light::Sky { sky: Arc::new(sky) })
}

//! Tangents for normal maps on triangle meshes, as glTF asks: a file's
//! `TANGENT`, or when it has none, MikkTSpace's (Mikkelsen 2008,
//! "Simulation of wrinkled surfaces revisited"; the tangent space Blender
//! and the glTF tools bake normal maps in) through the `bevy_mikktspace`
//! crate (a port in safe Rust, with no dependencies, that answers every
//! input: the C translation in the `mikktspace` crate panicked on some
//! fuzzed files).
//! Its tangents follow ∂p/∂u smoothed over a vertex's triangles, so a
//! normal map's frame does not jump at the edges of a curved mesh as one
//! made per triangle does.

use glam::{Vec2, Vec3, Vec4};

/// A mesh's triangles as MikkTSpace reads them, and the tangents it writes
/// at each corner.
struct Faces<'a> {
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    uvs: &'a [Vec2],
    triangles: &'a [[u32; 3]],
    out: Vec<[Vec4; 3]>,
}

impl Faces<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.triangles[face][vert] as usize
    }
}

impl bevy_mikktspace::Geometry for Faces<'_> {
    fn num_faces(&self) -> usize {
        self.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent(
        &mut self,
        tangent: Option<bevy_mikktspace::TangentSpace>,
        face: usize,
        vert: usize,
    ) {
        // A corner it finds no tangent for (a degenerate face alone) keeps
        // w = 0: its triangle's own ∂p/∂u serves.
        if let (Some(t), Some(slot)) = (tangent, self.out.get_mut(face)) {
            slot[vert] = Vec4::from_array(t.tangent_encoded());
        }
    }
}

/// MikkTSpace's tangent at each corner of `triangles` (indices into the
/// vertex lists, which must all be as long as `positions`), in the frame of
/// ptsc's texture coordinates ((0, 0) at the image's bottom left, as
/// Blender's): w = +1 where the bitangent n × t points along +v, −1 where
/// the coordinates are mirrored. `None` when the lists do not match or
/// MikkTSpace gives up.
pub fn generate(
    positions: &[Vec3],
    normals: &[Vec3],
    uvs: &[Vec2],
    triangles: &[[u32; 3]],
) -> Option<Vec<[Vec4; 3]>> {
    let n = positions.len();
    let fits = normals.len() == n
        && uvs.len() == n
        && triangles.iter().flatten().all(|&i| (i as usize) < n);
    // Its arithmetic is f32 throughout: a value it cannot carry is refused.
    let finite = (positions.iter().chain(normals)).all(|v| v.is_finite())
        && uvs.iter().all(|v| v.is_finite());
    if !fits || !finite || triangles.is_empty() {
        return None;
    }
    let mut faces = Faces {
        positions,
        normals,
        uvs,
        triangles,
        out: vec![[Vec4::ZERO; 3]; triangles.len()],
    };
    bevy_mikktspace::generate_tangents(&mut faces).ok()?;
    Some(faces.out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of two quads bent 90° along x = 1, with u along the strip
    /// and v across it (mirrored when `mirror`).
    fn bent_strip(mirror: bool) -> Option<Vec<[Vec4; 3]>> {
        let positions = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, -1.0),
        ];
        let normals = [
            Vec3::Z,
            Vec3::new(1.0, 0.0, 1.0).normalize(),
            Vec3::X,
            Vec3::Z,
            Vec3::new(1.0, 0.0, 1.0).normalize(),
            Vec3::X,
        ];
        let v = |y: f32| if mirror { 1.0 - y } else { y };
        let uvs = [0.0, 0.5, 1.0, 0.0, 0.5, 1.0]
            .iter()
            .zip([0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
            .map(|(&u, y)| Vec2::new(u, v(y)))
            .collect::<Vec<_>>();
        let triangles = [[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]];
        generate(&positions, &normals, &uvs, &triangles)
    }

    #[test]
    fn tangents_follow_u_smoothed_over_the_bend_and_know_mirrors() {
        let t = bent_strip(false).expect("tangents");
        // At the bend (vertex 1, corner 1 of the first face and corner 0 of
        // the third) the two faces' ∂p/∂u (+x and −z) meet halfway.
        let halfway = Vec3::new(1.0, 0.0, -1.0).normalize();
        for corner in [t[0][1], t[2][0]] {
            assert!((corner.truncate() - halfway).length() < 1e-3, "{corner}");
            assert_eq!(corner.w, 1.0);
        }
        // Away from it, each face's own direction.
        assert!(
            (t[0][0].truncate() - Vec3::X).length() < 1e-3,
            "{}",
            t[0][0]
        );
        assert!(
            (t[2][1].truncate() + Vec3::Z).length() < 1e-3,
            "{}",
            t[2][1]
        );
        let mirrored = bent_strip(true).expect("tangents");
        assert!(mirrored.iter().flatten().all(|c| c.w == -1.0));
    }

    #[test]
    fn mismatched_or_non_finite_lists_are_refused() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let n = [Vec3::Z; 3];
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        assert!(generate(&p, &n, &uv, &[[0, 1, 2]]).is_some());
        assert!(generate(&p, &n[..2], &uv, &[[0, 1, 2]]).is_none());
        assert!(generate(&p, &n, &uv, &[[0, 1, 3]]).is_none());
        let bad = [Vec2::ZERO, Vec2::X, Vec2::new(f32::NAN, 0.0)];
        assert!(generate(&p, &n, &bad, &[[0, 1, 2]]).is_none());
    }
}

//! The CPU deformation behind [`Mesh::animated`].

use std::f32::consts::TAU;

use glam::Vec3;

use super::normals::compute_area_weighted_normals;
use super::Mesh;

/// Direction along which the wave travels (not normalized; only its phase matters).
const WAVE_DIR: Vec3 = Vec3::new(1.0, 0.7, 0.4);
/// Waves across the largest extent of the bounding box.
const WAVES: f32 = 1.5;
/// Wave periods per second of `time`.
const FREQUENCY: f32 = 0.5;

pub(crate) fn animated(mesh: &Mesh, time: f32, amplitude: f32) -> Mesh {
    if !time.is_finite() || !amplitude.is_finite() || amplitude == 0.0 {
        return mesh.clone();
    }
    let tris = mesh.position_indices();
    let directions = compute_area_weighted_normals(&mesh.positions, &tris);
    let normals_were_computed =
        mesh.triangles.iter().all(|t| t.n == t.p) && mesh.normals == directions;

    let (lo, hi) = mesh.bounds();
    let extent = (hi - lo).max_element();
    let k = if extent > 0.0 && extent.is_finite() {
        TAU * WAVES / (extent * WAVE_DIR.length())
    } else {
        0.0
    };
    let positions: Vec<Vec3> = mesh
        .positions
        .iter()
        .zip(&directions)
        .map(|(&p, &d)| {
            let phase = k * (p - lo).dot(WAVE_DIR) - TAU * FREQUENCY * time;
            let moved = p + d * (amplitude * phase.sin());
            if moved.is_finite() {
                moved
            } else {
                p
            }
        })
        .collect();
    let normals = if normals_were_computed {
        compute_area_weighted_normals(&positions, &tris)
    } else {
        mesh.normals.clone()
    };
    Mesh {
        name: mesh.name.clone(),
        positions,
        normals,
        triangles: mesh.triangles.clone(),
        texcoords: mesh.texcoords.clone(),
    }
}

#[cfg(test)]
mod tests {
    use crate::mesh::test_support::load_model;

    #[test]
    fn deterministic_bounded_and_recomputes_computed_normals() {
        let (mesh, report) = load_model("torus_16x8.obj");
        assert!(report.normals_computed);
        let a = mesh.animated(0.3, 0.05);
        let b = mesh.animated(0.3, 0.05);
        assert_eq!(a, b);
        assert_ne!(a.positions, mesh.positions);
        assert_ne!(a.normals, mesh.normals);
        assert_eq!(a.triangles, mesh.triangles);
        for (p, q) in mesh.positions.iter().zip(&a.positions) {
            assert!((*p - *q).length() <= 0.05 + 1e-6);
        }
        assert!(a.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
        // Different times differ; the animation is periodic in time with period 2.
        assert_ne!(mesh.animated(0.8, 0.05).positions, a.positions);
        let c = mesh.animated(2.3, 0.05);
        for (p, q) in c.positions.iter().zip(&a.positions) {
            assert!((*p - *q).length() < 1e-4);
        }
    }

    /// The window's animation moves no vertex further than `WOBBLE` of the bounding radius
    /// (what window.md says), and some vertex nearly that far (the share is the amplitude,
    /// not a looser bound), on meshes of very different sizes.
    #[test]
    fn the_window_wobble_is_its_share_of_the_radius() {
        for (file, scale) in [("torus_16x8.obj", 1.0), ("spot_control_tri.obj", 1e3)] {
            let (mut mesh, _) = load_model(file);
            mesh.positions.iter_mut().for_each(|p| *p *= scale);
            let r = mesh.bounding_radius();
            let mut largest = 0.0f32;
            for step in 0..80 {
                let moved = mesh.wobbled(step as f32 * 0.025);
                for (p, q) in mesh.positions.iter().zip(&moved.positions) {
                    largest = largest.max((*p - *q).length());
                }
            }
            assert!(largest <= super::super::WOBBLE * r * (1.0 + 1e-5), "{file}");
            assert!(
                largest >= 0.95 * super::super::WOBBLE * r,
                "{file}: {largest}"
            );
        }
    }

    #[test]
    fn given_normals_are_kept() {
        for file in ["cylinder_hard_normals.obj", "spot_control_tri_vn.obj"] {
            let (mesh, report) = load_model(file);
            assert!(!report.normals_computed);
            let a = mesh.animated(1.0, 0.1);
            assert_eq!(a.normals, mesh.normals, "{file}");
            assert_ne!(a.positions, mesh.positions, "{file}");
        }
    }

    #[test]
    fn zero_or_non_finite_parameters_leave_the_mesh_alone() {
        let (mesh, _) = load_model("icosahedron.obj");
        assert_eq!(mesh.animated(1.0, 0.0), mesh);
        assert_eq!(mesh.animated(f32::NAN, 1.0), mesh);
        assert_eq!(mesh.animated(1.0, f32::INFINITY), mesh);
    }
}

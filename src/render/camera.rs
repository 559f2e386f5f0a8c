//! Orbit camera around a target, Vulkan clip conventions (depth 0..1, y down).

use glam::{Mat4, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub target: Vec3,
    /// Horizontal angle (radians).
    pub yaw: f32,
    /// Vertical angle (radians), clamped to (-pi/2, pi/2).
    pub pitch: f32,
    pub distance: f32,
    /// Vertical field of view (radians).
    pub fov_y: f32,
    /// Radius of the bounding sphere around `target` that is framed: the near and far planes
    /// and the closest zoom follow from it, so any scale of mesh is drawn (no fixed clamps).
    pub radius: f32,
}

/// How much of the bounding sphere's radius the depth range keeps around it, for rounding and
/// for the demo's animation (which moves vertices by up to 3% of the radius).
const DEPTH_MARGIN: f32 = 1.1;

impl Camera {
    /// A camera that frames a sphere of `radius` around `center`. For meshes far from the
    /// origin, or much smaller or larger than 1, draw
    /// [`Mesh::for_viewing`](crate::mesh::Mesh::for_viewing) instead: single-precision view maths cannot.
    pub fn framing(center: Vec3, radius: f32) -> Self {
        let fov_y = 45f32.to_radians();
        let radius = if radius > 0.0 && radius.is_finite() {
            radius
        } else {
            1.0
        };
        Self {
            target: center,
            yaw: 2.2,
            pitch: 0.35,
            distance: radius / (fov_y * 0.5).sin() * 0.9,
            fov_y,
            radius,
        }
    }

    pub fn eye(&self) -> Vec3 {
        let dir = Vec3::new(
            self.pitch.cos() * self.yaw.sin(),
            self.pitch.sin(),
            self.pitch.cos() * self.yaw.cos(),
        );
        self.target + dir * self.distance
    }

    /// Near and far planes: the bounding sphere (with a margin) from the eye; when the eye is
    /// inside it, the near plane is a thousandth of the radius.
    pub fn depth_range(&self) -> (f32, f32) {
        let r = self.radius * DEPTH_MARGIN;
        let near = (self.distance - r).max(self.radius * 1e-3);
        let far = (self.distance + r).max(near * 2.0);
        (near, far)
    }

    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        let (near, far) = self.depth_range();
        let mut proj = Mat4::perspective_rh(self.fov_y, aspect.max(1e-6), near, far);
        proj.y_axis.y = -proj.y_axis.y; // Vulkan's clip space has y pointing down
        proj * Mat4::look_at_rh(self.eye(), self.target, Vec3::Y)
    }

    pub fn orbit(&mut self, dx: f32, dy: f32) {
        self.yaw -= dx;
        self.pitch = (self.pitch + dy).clamp(-1.5, 1.5);
    }

    pub fn zoom(&mut self, factor: f32) {
        self.distance = (self.distance * factor).max(self.radius * 1e-2);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_framed_sphere_is_inside_the_depth_range_at_any_scale() {
        // (Far beyond this range f32 view maths fails: draw `Mesh::for_viewing`.)
        for r in [1e-5_f32, 1e-2, 1.0, 1e3, 1e6] {
            let cam = Camera::framing(Vec3::ZERO, r);
            let (near, far) = cam.depth_range();
            assert!(
                near > 0.0 && near < cam.distance - r && far > cam.distance + r,
                "{r}"
            );
            // The sphere's centre projects inside clip space.
            let p = cam.view_proj(16.0 / 9.0) * glam::Vec4::new(0.0, 0.0, 0.0, 1.0);
            let z = p.z / p.w;
            assert!(p.w > 0.0 && (0.0..=1.0).contains(&z), "{r}: {p}");
        }
        let mut cam = Camera::framing(Vec3::ZERO, 1e-5);
        cam.zoom(1e-9);
        assert!(cam.distance > 0.0 && cam.depth_range().0 > 0.0);
    }
}

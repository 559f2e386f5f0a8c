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

    /// A camera at `eye` looking at `target` (up is +Y) with a vertical field of view of
    /// `fov_y` radians; `radius` is the scene's bounding radius (it sets the depth range).
    /// `None` when the eye is at the target or a value is not finite.
    pub fn looking(eye: Vec3, target: Vec3, fov_y: f32, radius: f32) -> Option<Self> {
        let offset = eye - target;
        let distance = offset.length();
        if !(eye.is_finite() && target.is_finite() && distance > 0.0 && distance.is_finite()) {
            return None;
        }
        let dir = offset / distance;
        if dir.y.abs() > 0.9999 {
            return None; // straight up or down: +Y cannot be up
        }
        Some(Self {
            target,
            yaw: dir.x.atan2(dir.z),
            pitch: dir.y.clamp(-1.0, 1.0).asin(),
            distance,
            fov_y,
            radius: if radius > 0.0 && radius.is_finite() {
                radius
            } else {
                1.0
            },
        })
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

    #[test]
    fn a_camera_looking_from_an_eye_has_that_eye() {
        let target = Vec3::new(0.5, -1.0, 2.0);
        for eye in [
            Vec3::new(3.0, 1.0, -2.0),
            Vec3::new(-0.1, 0.2, 0.3),
            Vec3::new(0.0, 5.0, 1.0),
        ] {
            let cam = Camera::looking(eye, target, 0.8, 1.0).unwrap();
            assert!(
                (cam.eye() - eye).length() < 1e-5 * eye.length().max(1.0),
                "{eye}"
            );
            // The target projects to the image's centre.
            let p = cam.view_proj(1.5) * target.extend(1.0);
            assert!(
                (p.x / p.w).abs() < 1e-4 && (p.y / p.w).abs() < 1e-4,
                "{eye}: {p}"
            );
        }
        assert!(Camera::looking(target, target, 0.8, 1.0).is_none());
        assert!(Camera::looking(target + Vec3::Y, target, 0.8, 1.0).is_none());
        assert!(Camera::looking(Vec3::splat(f32::NAN), target, 0.8, 1.0).is_none());
    }
}

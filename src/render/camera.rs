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
}

impl Camera {
    /// A camera that frames a sphere of `radius` around `center`.
    pub fn framing(center: Vec3, radius: f32) -> Self {
        let fov_y = 45f32.to_radians();
        let radius = radius.max(1e-6);
        Self {
            target: center,
            yaw: 2.2,
            pitch: 0.35,
            distance: radius / (fov_y * 0.5).sin() * 0.9,
            fov_y,
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

    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        let near = (self.distance * 0.01).max(1e-4);
        let far = self.distance * 100.0;
        let mut proj = Mat4::perspective_rh(self.fov_y, aspect.max(1e-6), near, far);
        proj.y_axis.y = -proj.y_axis.y; // Vulkan's clip space has y pointing down
        proj * Mat4::look_at_rh(self.eye(), self.target, Vec3::Y)
    }

    pub fn orbit(&mut self, dx: f32, dy: f32) {
        self.yaw -= dx;
        self.pitch = (self.pitch + dy).clamp(-1.5, 1.5);
    }

    pub fn zoom(&mut self, factor: f32) {
        self.distance = (self.distance * factor).max(1e-4);
    }
}

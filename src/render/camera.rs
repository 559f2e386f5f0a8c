//! Orbit camera around a target, Vulkan clip conventions (depth 0..1, y down).

use super::Framing;
use glam::{Mat4, Vec3, Vec4};

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

/// The fraction of the distance the depth range keeps in front of the target at least ([`Camera::depth_range`]).
const DISTANT_MARGIN: f32 = 1e-3;

/// Past this `|sin pitch|` the view's up is not +Y ([`Camera::up`]).
const VERTICAL_SIN: f32 = 0.9999;

/// The direction the framing cameras look from: yaw and pitch (radians).
const FRAMING_YAW: f32 = 2.2;
const FRAMING_PITCH: f32 = 0.35;

/// The fraction of the image's half-width and half-height [`Camera::fit`] keeps free at the
/// tighter border.
pub const FIT_MARGIN: f32 = 0.08;

/// The fraction of the framed radius a fitted eye keeps at least between itself and the
/// nearest point's depth: ten times the near plane's least distance ([`Camera::depth_range`]).
const NEAR_CLEARANCE: f32 = 1e-2;

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
            yaw: FRAMING_YAW,
            pitch: FRAMING_PITCH,
            distance: radius / (fov_y * 0.5).sin() * 0.9,
            fov_y,
            radius,
        }
    }

    /// The camera looking from the framing direction (as [`Camera::framing`]) with a vertical
    /// field of view of 45 degrees that shows every point of `points` in an image of `aspect`
    /// (width / height) and comes as close as it can: the projected points fill the image up to
    /// a margin of [`FIT_MARGIN`] at its tighter pair of borders, and are centred between the
    /// other pair. The depth range holds them all. With no finite point, it frames the unit
    /// sphere; with points all in one place, a tiny sphere there.
    pub fn fit(points: &[Vec3], aspect: f32) -> Self {
        Self::framing(Vec3::ZERO, 1.0).fit_from(points, aspect)
    }

    /// [`Camera::fit`] of `framing`'s points with a vertical field of view of `fov_y` radians
    /// instead of 45 degrees, its eye outside each element's reach ([`Camera::fit_clear_of`]):
    /// the eye comes as close as that field of view lets it (farther for a narrow one, closer
    /// for a wide one), so the points fill the image as they do at 45 degrees, until the reach
    /// or the near plane keeps it back (wide angles, coarse meshes).
    pub fn fit_with_fov(framing: &Framing, aspect: f32, fov_y: f32) -> Self {
        Self {
            fov_y,
            ..Self::framing(Vec3::ZERO, 1.0)
        }
        .fit_clear_of(&framing.points, &framing.reach, aspect)
    }

    /// This camera moved so that, looking in the same direction with the same field of view, it
    /// shows every point of `points` as [`Camera::fit`] does from the framing direction (the
    /// window's fit-to-view). With no finite point, it is unchanged.
    pub fn fit_from(&self, points: &[Vec3], aspect: f32) -> Self {
        self.fit_clear_of(points, &[], aspect)
    }

    /// [`Camera::fit_from`] with the eye outside every sphere of `reach` (centre, radius) and
    /// the points wholly in front of the near plane: where the closest fit puts the eye inside
    /// one, or within `NEAR_CLEARANCE` of the framed radius of the nearest point's depth, the
    /// eye moves back along its line of sight until it is clear, and the points are centred
    /// again at that depth (which moves its line of sight: a few rounds), so they stay inside
    /// the frustum, centred in the image, and take less of it.
    pub fn fit_clear_of(&self, points: &[Vec3], reach: &[Vec4], aspect: f32) -> Self {
        let mut cam = *self;
        let points: Vec<Vec3> = points.iter().copied().filter(|p| p.is_finite()).collect();
        let Some(&first) = points.first() else {
            return cam;
        };
        let aspect = if aspect > 0.0 && aspect.is_finite() {
            aspect
        } else {
            1.0
        };
        // The camera's frame: forward (from the eye to the target), right and up, from the
        // direction alone (as seen from the framing camera's place, so that the result does not
        // depend on where this camera stands).
        let aim = Self {
            target: Vec3::ZERO,
            distance: Self::framing(Vec3::ZERO, 1.0).distance,
            ..cam
        };
        let forward = (aim.target - aim.eye()).normalize();
        let right = forward.cross(aim.up()).normalize();
        let up = right.cross(forward);
        let ty = (cam.fov_y * 0.5).tan() * (1.0 - FIT_MARGIN);
        let tx = (cam.fov_y * 0.5).tan() * aspect * (1.0 - FIT_MARGIN);
        // With the eye at (ex, ey, ez) in this frame, a point (x, y, z) is inside the narrowed
        // frustum when |x - ex| <= tx (z - ez) and |y - ey| <= ty (z - ez). For each axis the
        // farthest forward eye is where the two planes touch the extreme points: with
        // a = min(z - x / tx) and b = min(z + x / tx), ex = tx (b - a) / 2 and ez = (a + b) / 2.
        let frame: Vec<Vec3> = points
            .iter()
            .map(|p| Vec3::new(p.dot(right), p.dot(up), p.dot(forward)))
            .collect();
        let (mut a, mut b, mut c, mut d) = (f32::MAX, f32::MAX, f32::MAX, f32::MAX);
        let (mut zmin, mut zmax) = (f32::MAX, f32::MIN);
        for &Vec3 { x, y, z } in &frame {
            a = a.min(z - x / tx);
            b = b.min(z + x / tx);
            c = c.min(z - y / ty);
            d = d.min(z + y / ty);
            zmin = zmin.min(z);
            zmax = zmax.max(z);
        }
        let mut ez = ((a + b) * 0.5).min((c + d) * 0.5);
        let (mut ex, mut ey) = (tx * (b - a) * 0.5, ty * (d - c) * 0.5);
        // Where the eye must stand back (below), the points are centred again in the image at
        // the new depth, which can bring the axis into another sphere: a few rounds settle it.
        for _ in 0..4 {
            // Centred in the image: the points' projections reach as far past the axis on one
            // side as on the other (the eye anywhere in [lo, hi] keeps them inside the frustum).
            ex = centred(&frame, ez, |p| p.x, tx * (ez - a), tx * (b - ez));
            ey = centred(&frame, ez, |p| p.y, ty * (ez - c), ty * (d - ez));
            let back = clear_of(&frame, &points, reach, [right, up, forward], [ex, ey, ez]);
            if back >= ez {
                break;
            }
            ez = back;
        }
        let eye = right * ex + up * ey + forward * ez;
        let distance = (zmin + zmax) * 0.5 - ez;
        let target = eye + forward * distance;
        let radius = points
            .iter()
            .map(|p| (*p - target).length())
            .fold(0.0f32, f32::max);
        let scale = first.abs().max_element().max(1e-30);
        if !(distance > scale * 1e-6 && radius.is_finite() && distance.is_finite()) {
            return Self::framing(first, (scale * 1e-6).max(1e-6));
        }
        cam.target = target;
        cam.distance = distance;
        cam.radius = radius.max(distance * 1e-3);
        cam
    }

    /// A camera at `eye` looking at `target` (up is +Y, or where the camera looks nearly
    /// straight up or down, as [`Camera::up`] says) with a vertical field of view of `fov_y`
    /// radians; `radius` is the scene's bounding radius (it sets the depth range). `None` when
    /// the eye is at the target or a value is not finite.
    pub fn looking(eye: Vec3, target: Vec3, fov_y: f32, radius: f32) -> Option<Self> {
        let offset = eye - target;
        let distance = offset.length();
        if !(eye.is_finite() && target.is_finite() && distance > 0.0 && distance.is_finite()) {
            return None;
        }
        let dir = offset / distance;
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

    /// The up vector of the view: +Y, except where the camera looks within about 0.8° of
    /// straight up or down (`|sin pitch| > 0.9999`), where +Y is (nearly) the view direction
    /// and gives no up: there it is the direction in which raising the pitch moves the eye,
    /// which lies in the plane of +Y and the view direction and so draws the same image as +Y
    /// wherever both apply. Looking straight down (yaw 0), the image's up is -Z; straight up,
    /// +Z.
    pub fn up(&self) -> Vec3 {
        let s = self.pitch.sin();
        if s.abs() <= VERTICAL_SIN {
            return Vec3::Y;
        }
        let up = Vec3::new(-s * self.yaw.sin(), self.pitch.cos(), -s * self.yaw.cos());
        // Rounding's crumbs (cos(pi/2) is not 0 in f32) are zeros: straight down, (0, 0, -1).
        let clean = |c: f32| if c.abs() < 1e-6 { 0.0 } else { c };
        Vec3::new(clean(up.x), clean(up.y), clean(up.z)).normalize()
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
    /// inside it, the near plane is a thousandth of the radius. From an eye more than about a
    /// thousand radii away the near plane keeps at least a thousandth of the distance: in
    /// `f32` the distance minus the radius rounds to the distance itself past about 1e7
    /// radii, and a near plane there would cut through the sphere.
    pub fn depth_range(&self) -> (f32, f32) {
        let r = self.radius * DEPTH_MARGIN;
        let d = self.distance;
        let near = (d - r)
            .min(d * (1.0 - DISTANT_MARGIN))
            .max(self.radius * 1e-3);
        let far = (d + r).max(near * 2.0);
        (near, far)
    }

    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        let (near, far) = self.depth_range();
        let mut proj = Mat4::perspective_rh(self.fov_y, aspect.max(1e-6), near, far);
        proj.y_axis.y = -proj.y_axis.y; // Vulkan's clip space has y pointing down
        proj * Mat4::look_at_rh(self.eye(), self.target, self.up())
    }

    pub fn orbit(&mut self, dx: f32, dy: f32) {
        self.yaw -= dx;
        self.pitch = (self.pitch + dy).clamp(-1.5, 1.5);
    }

    /// Moves the eye toward (`factor < 1`) or away from the target: never closer than a
    /// hundredth of the framed radius, nor farther than `MAX_ZOOM_RADII` radii (where the
    /// mesh is a few pixels across) unless it already is (a camera given so stays).
    pub fn zoom(&mut self, factor: f32) {
        let d = self.distance * factor;
        self.distance = if factor > 1.0 {
            d.min((self.radius * MAX_ZOOM_RADII).max(self.distance))
        } else {
            d.max(self.radius * 1e-2)
        };
    }
}

/// How far zooming out takes the eye at most, in framed radii: at 45 degrees the mesh is then
/// about a hundredth of the view's height.
pub const MAX_ZOOM_RADII: f32 = 100.0;

/// A viewpoint asked for (the command line's `--eye`, `--look-at` and `--fov`), in the drawn
/// coordinates: what is not given comes from the camera fitted to the surface as drawn
/// ([`Camera::fit_with_fov`] at `fov_y`), the one default camera of every command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewpoint {
    pub eye: Option<Vec3>,
    pub look_at: Option<Vec3>,
    /// Vertical field of view (radians).
    pub fov_y: f32,
}

impl Default for Viewpoint {
    /// The fitted camera at 45 degrees.
    fn default() -> Self {
        Self {
            eye: None,
            look_at: None,
            fov_y: 45f32.to_radians(),
        }
    }
}

/// The least distance between the eye and the point looked at, in radii of the surface, that
/// gives a view direction ([`Viewpoint::complete`]): a thousand times `f32`'s step at the drawn
/// frame's unit scale, so the direction is good to about a tenth of a degree.
pub const MIN_VIEW_RADII: f32 = 1e-4;

impl Viewpoint {
    /// The camera for an image of `aspect` (width / height) showing `points`, the surface as
    /// drawn ([`crate::render::framing_points`]): fitted at this field of view, then moved to
    /// the eye and the point looked at where given, the other completed from the fitted camera.
    /// `None` when the eye and the point looked at give no view direction (the same point).
    pub fn camera(&self, framing: &Framing, aspect: f32) -> Option<Camera> {
        self.complete(Camera::fit_with_fov(framing, aspect, self.fov_y))
    }

    /// `fitted` (a camera fitted at this field of view) moved to the eye and the point looked
    /// at where given: the other comes from `fitted`.
    pub fn complete(&self, fitted: Camera) -> Option<Camera> {
        let (c, r) = (fitted.target, fitted.radius);
        if self.eye.is_none() && self.look_at.is_none() {
            return Some(fitted);
        }
        let eye = self.eye.unwrap_or(fitted.eye());
        let target = self.look_at.unwrap_or(fitted.target);
        // Closer together than single precision resolves a direction at the surface's scale
        // (an eye given at the default target as printed, which maps back into the drawn frame
        // a rounding away from it): no view direction, rather than one made of rounding.
        if (target - eye).length() <= r * MIN_VIEW_RADII {
            return None;
        }
        // A look-at far beyond the mesh would grow the sphere the depth range holds, and with
        // it the near plane, past the mesh: the target moves back along the view ray to the
        // point nearest the mesh's centre. Eye and direction, so the image, stay.
        let ray = target - eye;
        let dir = ray.normalize_or_zero();
        let along = (c - eye).dot(dir);
        // A look-at beyond the whole surface with the surface not ahead of the eye (behind or
        // beside it) comes back as far as the surface's farthest point: the camera keeps the
        // target and rebuilds the eye from it (`Camera::eye`), in f32, which at a distance of
        // 1e7 radii would move the eye by a good part of the mesh. The eye and direction stay;
        // the depth range, which follows the target, still holds the whole surface (its near
        // plane comes no farther from the eye).
        let reach = (c - eye).length() + r;
        let target = if along > r * 1e-3 && along < ray.length() {
            eye + dir * along
        } else if ray.length() > reach {
            eye + dir * reach
        } else {
            target
        };
        // The depth range holds the whole surface around the target.
        let radius = r + (target - c).length();
        Camera::looking(eye, target, self.fov_y, radius)
    }
}

/// Where on one axis of the camera's frame (`coord` of each point in `frame`: right, up,
/// forward) an eye at depth `ez` centres the points in the image: their projections
/// `(q - e) / (z - ez)` reach as far past the axis on one side as on the other. That reach is
/// falling in `e`, so bisected in `[lo, hi]` (where every point stays inside the frustum).
fn centred(frame: &[Vec3], ez: f32, coord: impl Fn(&Vec3) -> f32, lo: f32, hi: f32) -> f32 {
    let (lo, hi) = (lo as f64, hi as f64);
    // An empty or degenerate interval (the tighter axis, where both borders touch), or NaN.
    if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
        return ((lo + hi) * 0.5) as f32;
    }
    let t =
        |p: &Vec3, e: f64| (coord(p) as f64 - e) / (p.z as f64 - ez as f64).max(f64::MIN_POSITIVE);
    // Each point's `t` falls as `e` grows (rounding keeps it monotonic), so over [lo, hi] the
    // largest is a point whose `t` at `lo` reaches the largest at `hi`, and the smallest one
    // whose `t` at `hi` is at most the smallest at `lo`: every few steps the bisection keeps
    // those alone, the same extremes as all of them (on a large mesh, soon a few points of
    // millions).
    let (mut lo, mut hi) = (lo, hi);
    let (mut highs, mut lows): (Vec<Vec3>, Vec<Vec3>) = (Vec::new(), Vec::new());
    for step in 0..60 {
        if step % 4 == 0 {
            let (from_highs, from_lows) = if step == 0 {
                (frame, frame)
            } else {
                (&highs[..], &lows[..])
            };
            let most_at_hi = from_highs.iter().map(|p| t(p, hi)).fold(f64::MIN, f64::max);
            let least_at_lo = from_lows.iter().map(|p| t(p, lo)).fold(f64::MAX, f64::min);
            let kept_highs = (from_highs.iter().copied())
                .filter(|p| t(p, lo) >= most_at_hi)
                .collect();
            let kept_lows = (from_lows.iter().copied())
                .filter(|p| t(p, hi) <= least_at_lo)
                .collect();
            (highs, lows) = (kept_highs, kept_lows);
        }
        let mid = 0.5 * (lo + hi);
        let most = highs.iter().map(|p| t(p, mid)).fold(f64::MIN, f64::max);
        let least = lows.iter().map(|p| t(p, mid)).fold(f64::MAX, f64::min);
        if most + least > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)) as f32
}

/// The depth an eye at `(ex, ey)` of the camera's frame (`axes`: right, up, forward) must
/// stand at or behind, from depth `ez`: outside each sphere of `reach` its line of sight passes
/// through, and `NEAR_CLEARANCE` of the framed radius before the nearest point. Moved back
/// along its axis, every point stays inside the frustum (the nearer cone lies inside the
/// farther one with the same axis and angle).
fn clear_of(frame: &[Vec3], points: &[Vec3], reach: &[Vec4], axes: [Vec3; 3], e: [f32; 3]) -> f32 {
    let [right, up, forward] = axes;
    let [ex, ey, mut ez] = e;
    let (zmin, zmax) = frame.iter().fold((f32::MAX, f32::MIN), |(lo, hi), p| {
        (lo.min(p.z), hi.max(p.z))
    });
    // The target (below) is on the view axis, at the middle of the points' depths: moving the
    // eye along the axis moves neither it nor the radius around it.
    let mid = right * ex + up * ey + forward * ((zmin + zmax) * 0.5);
    let framed = points
        .iter()
        .map(|p| (*p - mid).length())
        .fold(0.0f32, f32::max);
    for s in reach {
        let c = s.truncate();
        let (x, y, z) = (c.dot(right), c.dot(up), c.dot(forward));
        // A thousandth more, so that rounding leaves the eye outside.
        let w = s.w * (1.0 + 1e-3);
        let across = (x - ex) * (x - ex) + (y - ey) * (y - ey);
        if across < w * w {
            ez = ez.min(z - (w * w - across).sqrt());
        }
    }
    ez.min(zmin - framed * NEAR_CLEARANCE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// Zooming out stops at MAX_ZOOM_RADII radii (80 wheel clicks went to 10⁵ radii, an empty
    /// view), zooming in at a hundredth of one; an eye placed farther stays where it is.
    #[test]
    fn zoom_stays_within_sight_of_the_mesh() {
        let mut cam = Camera::framing(Vec3::ZERO, 2.0);
        for _ in 0..80 {
            cam.zoom(1.0 / 0.9);
        }
        assert_eq!(cam.distance, 2.0 * MAX_ZOOM_RADII);
        for _ in 0..200 {
            cam.zoom(0.9);
        }
        assert_eq!(cam.distance, 2.0 * 1e-2);
        cam.distance = 1e4;
        cam.zoom(1.0 / 0.9);
        assert_eq!(cam.distance, 1e4);
        cam.zoom(0.9);
        assert!(cam.distance < 1e4);
    }

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
        assert!(Camera::looking(Vec3::splat(f32::NAN), target, 0.8, 1.0).is_none());
    }

    #[test]
    fn a_camera_looks_straight_down_or_up_with_minus_or_plus_z_up() {
        let project = |cam: &Camera, p: Vec3| {
            let c = cam.view_proj(1.0) * p.extend(1.0);
            glam::Vec2::new(c.x / c.w, c.y / c.w) // Vulkan: y grows downwards
        };
        for (eye, up) in [
            (Vec3::new(0.0, 5.0, 0.0), -Vec3::Z),
            (Vec3::new(0.0, -5.0, 0.0), Vec3::Z),
        ] {
            let cam = Camera::looking(eye, Vec3::ZERO, 0.8, 1.0).unwrap();
            assert!((cam.eye() - eye).length() < 1e-5, "{eye}");
            assert_eq!(cam.up(), up, "{eye}");
            assert!(project(&cam, Vec3::ZERO).length() < 1e-5, "{eye}");
            let above = project(&cam, up * 0.5);
            assert!(above.y < -0.1 && above.x.abs() < 1e-5, "{eye}: {above}");
        }
        // Just inside the vertical band and just outside it the image is the same (to
        // rounding): the up vector changes, the view does not.
        for (a, b) in [(0.99989f32, 0.99991f32), (-0.99989, -0.99991)] {
            let cam = |s: f32| {
                let eye =
                    Vec3::new(0.3 * (1.0 - s * s).sqrt(), s, 0.954 * (1.0 - s * s).sqrt()) * 4.0;
                Camera::looking(eye, Vec3::ZERO, 0.8, 1.0).unwrap()
            };
            let (ca, cb) = (cam(a), cam(b));
            assert_eq!(ca.up(), Vec3::Y);
            assert_ne!(cb.up(), Vec3::Y);
            for p in [Vec3::X, Vec3::Z, -Vec3::X * 0.5, Vec3::new(0.2, 0.1, -0.3)] {
                let (pa, pb) = (project(&ca, p), project(&cb, p));
                assert!((pa - pb).length() < 1e-3, "{p}: {pa} {pb}");
            }
        }
    }

    #[test]
    fn a_fitted_camera_shows_every_point_and_touches_the_margin() {
        // A lopsided cloud far from the origin, in wide, square and tall images.
        let points: Vec<Vec3> = (0..200)
            .map(|i| {
                let t = i as f32 * 0.37;
                Vec3::new(
                    5.0 + 2.0 * t.sin(),
                    -3.0 + 0.3 * (t * 1.7).cos(),
                    0.5 * (t * 0.3).sin(),
                )
            })
            .collect();
        for aspect in [16.0 / 9.0, 1.0, 0.5] {
            let cam = Camera::fit(&points, aspect);
            let m = cam.view_proj(aspect);
            let mut extent = 0.0f32;
            let (mut lo, mut hi) = (Vec2::MAX, Vec2::MIN);
            for p in &points {
                let c = m * p.extend(1.0);
                let (x, y, z) = (c.x / c.w, c.y / c.w, c.z / c.w);
                (lo, hi) = (lo.min(Vec2::new(x, y)), hi.max(Vec2::new(x, y)));
                assert!(
                    c.w > 0.0 && (0.0..=1.0).contains(&z),
                    "{aspect}: {p} at depth {z}"
                );
                assert!(
                    x.abs() <= 1.0 - FIT_MARGIN + 1e-4 && y.abs() <= 1.0 - FIT_MARGIN + 1e-4,
                    "{aspect}: {p} at {x} {y}"
                );
                extent = extent.max(x.abs()).max(y.abs());
            }
            assert!(
                extent > 1.0 - FIT_MARGIN - 1e-3,
                "{aspect}: fills only {extent}"
            );
            // Centred in the image between both pairs of borders, the looser one too (the
            // cloud is deeper on one side: centring the eye between the positions that touch
            // either border would not centre it).
            assert!((lo + hi).abs().max_element() < 1e-3, "{aspect}: {lo} {hi}");
            assert_eq!((cam.yaw, cam.pitch), (FRAMING_YAW, FRAMING_PITCH));
        }
        // No point, or one: a camera still.
        assert_eq!(Camera::fit(&[], 1.0), Camera::framing(Vec3::ZERO, 1.0));
        let one = Camera::fit(&[Vec3::ONE], 1.0);
        assert!(one.distance > 0.0 && one.target == Vec3::ONE);
    }

    /// The bisection that centres the eye reads only the points that can be extreme between
    /// its bounds, and finds the same bits as one reading every point, on clouds of every
    /// shape and depth, for each coordinate and interval.
    #[test]
    fn centring_reads_the_extreme_points_alone() {
        let every = |frame: &[Vec3], ez: f32, coord: &dyn Fn(&Vec3) -> f32, lo: f32, hi: f32| {
            let (mut lo, mut hi) = (lo as f64, hi as f64);
            if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
                return ((lo + hi) * 0.5) as f32;
            }
            let balance = |e: f64| {
                let (mut most, mut least) = (f64::MIN, f64::MAX);
                for p in frame {
                    let t = (coord(p) as f64 - e) / (p.z as f64 - ez as f64).max(f64::MIN_POSITIVE);
                    most = most.max(t);
                    least = least.min(t);
                }
                most + least
            };
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if balance(mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            (0.5 * (lo + hi)) as f32
        };
        let (mut compared, mut filtered) = (0, 0);
        for shape in 0..4 {
            let frame: Vec<Vec3> = (0..3000)
                .map(|i| {
                    let t = i as f32 * 0.618;
                    let r = [1.0, 0.2, 3.0, 1.0][shape] * (1.0 + 0.5 * (t * 2.3).sin());
                    let z = [4.0, 2.0, 10.0, 0.5][shape]
                        + (t * 0.7).cos() * [1.0, 0.5, 6.0, 0.4][shape];
                    Vec3::new(r * t.cos() + 0.3 * shape as f32, r * (t * 1.3).sin(), z)
                })
                .collect();
            for (ez, lo, hi) in [
                (0.0, -1.0, 1.0),
                (-2.0, -5.0, 0.5),
                (-0.1, 0.2, 0.2),
                (-1.0, -0.01, 0.02),
            ] {
                for axis in 0..2 {
                    let coord = |p: &Vec3| if axis == 0 { p.x } else { p.y };
                    let got = centred(&frame, ez, coord, lo, hi);
                    assert_eq!(got.to_bits(), every(&frame, ez, &coord, lo, hi).to_bits());
                    compared += 1;
                    filtered += (lo < hi) as usize;
                }
            }
        }
        assert_eq!((compared, filtered), (32, 24));
    }

    #[test]
    fn a_fitted_eye_stays_outside_every_reach_and_before_the_near_plane() {
        // A bumpy sphere of 400 points in 100 elements of four, each reaching twice its size.
        let points: Vec<Vec3> = (0..400)
            .map(|i| {
                let (t, u) = (i as f32 * 0.37, i as f32 * 0.11);
                Vec3::new(t.sin() * u.cos(), u.sin(), t.cos() * u.cos()) * (1.0 + 0.1 * t.sin())
            })
            .collect();
        let reach: Vec<Vec4> = (points.chunks(4))
            .map(|c| {
                let centre = c.iter().copied().sum::<Vec3>() / 4.0;
                let r = c.iter().map(|p| (*p - centre).length()).fold(0.0, f32::max);
                centre.extend(2.0 * r)
            })
            .collect();
        let framing = Framing {
            points: points.clone(),
            reach: reach.clone(),
        };
        let aspect = 16.0 / 9.0;
        for degrees in [20.0f32, 45.0, 90.0, 120.0, 150.0, 170.0, 179.0, 179.99] {
            let fov_y = degrees.to_radians();
            let cam = Camera::fit_with_fov(&framing, aspect, fov_y);
            let eye = cam.eye();
            for s in &reach {
                assert!(
                    (eye - s.truncate()).length() > s.w,
                    "{degrees}: the eye is in {s}"
                );
            }
            let (near, _) = cam.depth_range();
            let m = cam.view_proj(aspect);
            let forward = (cam.target - eye).normalize();
            let (mut lo, mut hi) = (Vec2::MAX, Vec2::MIN);
            for p in &points {
                assert!(
                    (*p - eye).dot(forward) > near,
                    "{degrees}: {p} before the near plane"
                );
                let c = m * p.extend(1.0);
                let (x, y) = (c.x / c.w, c.y / c.w);
                assert!(
                    x.abs() <= 1.0 - FIT_MARGIN + 1e-3 && y.abs() <= 1.0 - FIT_MARGIN + 1e-3,
                    "{degrees}: {p} at {x} {y}"
                );
                (lo, hi) = (lo.min(Vec2::new(x, y)), hi.max(Vec2::new(x, y)));
            }
            // Centred in the image where the eye stood back too (below 179 degrees, where the
            // points still span more than rounding).
            if degrees < 179.0 {
                let off = (lo + hi).abs().max_element() / (hi - lo).max_element();
                assert!(off < 1e-3, "{degrees}: {lo} {hi}");
            }
            // Where the reach does not keep it back (as at 45 degrees), the eye is where the
            // points alone put it.
            let free = Camera::fit_with_fov(&Framing::points(points.clone()), aspect, fov_y);
            if degrees <= 45.0 {
                assert_eq!(cam, free, "{degrees}");
            } else {
                assert!(cam.distance >= free.distance, "{degrees}");
            }
        }
    }

    #[test]
    fn a_distant_look_at_keeps_the_fitted_eye_and_its_own_direction() {
        let points: Vec<Vec3> = (0..8)
            .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, (i >> 2) as f32) - 0.5)
            .collect();
        let framing = Framing::points(points);
        let fitted = Camera::fit_with_fov(&framing, 4.0 / 3.0, 45f32.to_radians());
        let eye = fitted.eye();
        for d in [1e3f32, 1e5, 1e7, 1e12] {
            for axis in [
                Vec3::X,
                -Vec3::X,
                Vec3::Z,
                -Vec3::Z,
                Vec3::new(0.6, 0.0, 0.8),
            ] {
                let look_at = axis * d;
                let v = Viewpoint {
                    look_at: Some(look_at),
                    ..Viewpoint::default()
                };
                let cam = v.complete(fitted).unwrap();
                let moved = (cam.eye() - eye).length();
                assert!(moved < 1e-5, "{d} {axis}: the eye moved by {moved}");
                let want = (look_at - eye).normalize();
                let got = (cam.target - cam.eye()).normalize();
                assert!(got.dot(want) > 1.0 - 1e-6, "{d} {axis}: looks along {got}");
            }
        }
    }

    #[test]
    fn a_viewpoint_completes_what_it_does_not_give_from_the_fitted_camera() {
        let points: Vec<Vec3> = (0..100)
            .map(|i| {
                let t = i as f32 * 0.61;
                Vec3::new(t.sin(), 0.5 * (t * 1.3).cos(), 0.7 * (t * 0.7).sin())
            })
            .collect();
        let framing = Framing::points(points.clone());
        let aspect = 4.0 / 3.0;
        // Nothing given: the fitted camera at 45 degrees, exactly.
        let default = Viewpoint::default();
        assert_eq!(
            default.camera(&framing, aspect),
            Some(Camera::fit(&points, aspect))
        );
        // A field of view alone: fitted with it, so the points still touch the margin (closer
        // for a wide one, farther for a narrow one), until the eye keeps its distance from the
        // nearest point: at 170 degrees they take less of the image.
        for degrees in [20.0f32, 90.0, 170.0] {
            let fov_y = degrees.to_radians();
            let v = Viewpoint { fov_y, ..default };
            let cam = v.camera(&framing, aspect).unwrap();
            assert_eq!(cam, Camera::fit_with_fov(&framing, aspect, fov_y));
            assert_eq!(cam.fov_y, fov_y);
            let m = cam.view_proj(aspect);
            let extent = (points.iter())
                .map(|p| {
                    let c = m * p.extend(1.0);
                    assert!(c.w > 0.0, "{degrees}: {p} behind the eye");
                    (c.x / c.w).abs().max((c.y / c.w).abs())
                })
                .fold(0.0f32, f32::max);
            let fills = if degrees < 170.0 {
                (extent - (1.0 - FIT_MARGIN)).abs() < 2e-3
            } else {
                extent > 0.3 && extent < 1.0 - FIT_MARGIN
            };
            assert!(fills, "{degrees}: fills {extent}");
        }
        // A lone eye looks at the fitted camera's target; a lone point looked at is seen from
        // the fitted camera's eye; both at the field of view given.
        let fov_y = 60f32.to_radians();
        let fitted = Camera::fit_with_fov(&framing, aspect, fov_y);
        let eye = Vec3::new(3.0, 1.0, -2.0);
        let v = Viewpoint {
            eye: Some(eye),
            fov_y,
            ..default
        };
        let cam = v.camera(&framing, aspect).unwrap();
        assert!((cam.eye() - eye).length() < 1e-5, "{}", cam.eye());
        assert!((cam.target - fitted.target).length() < 1e-5);
        assert_eq!(cam.fov_y, fov_y);
        let target = Vec3::new(0.2, -0.1, 0.1);
        let v = Viewpoint {
            look_at: Some(target),
            fov_y,
            ..default
        };
        let cam = v.camera(&framing, aspect).unwrap();
        assert!((cam.eye() - fitted.eye()).length() < 1e-4, "{}", cam.eye());
        assert!((cam.target - target).length() < 1e-5);
        // An eye at the fitted target gives no direction.
        let v = Viewpoint {
            eye: Some(fitted.target),
            fov_y,
            ..default
        };
        assert_eq!(v.camera(&framing, aspect), None);
    }
}

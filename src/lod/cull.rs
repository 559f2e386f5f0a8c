//! Culling helpers, conservative for curved and displaced patches: a bounding sphere against
//! the view frustum, and a normal cone against the eye (back faces of closed surfaces).

use super::net::Net;
use super::Sphere;
use crate::mesh::Mesh;
use glam::{Mat4, Vec3, Vec4};

/// The six planes of a view-projection (Vulkan clip space: `-w <= x, y <= w`, `0 <= z <= w`),
/// each `n·p + d >= 0` inside, `|n| = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    pub planes: [Vec4; 6],
}

impl Frustum {
    pub fn from_view_proj(m: Mat4) -> Self {
        let r = [0, 1, 2, 3].map(|i| m.row(i));
        let planes = [
            r[3] + r[0],
            r[3] - r[0],
            r[3] + r[1],
            r[3] - r[1],
            r[2],
            r[3] - r[2],
        ]
        .map(|p| p / p.truncate().length());
        Self { planes }
    }

    /// Whether the whole sphere lies outside one of the planes.
    pub fn outside(&self, s: &Sphere) -> bool {
        self.planes
            .iter()
            .any(|p| p.truncate().dot(s.centre) + p.w < -s.radius)
    }
}

/// A cone of directions: every direction within `acos(cos)` of the unit `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalCone {
    pub axis: Vec3,
    pub cos: f32,
}

/// The cone of the normals of a Bézier patch's drawn triangles, oriented as the stored corners
/// wind (`flip`: the net's corner order is an odd permutation of the stored one). `P_u` and
/// `P_v` lie in the convex hulls of the first differences `U_β = b_{β+e1} − b_{β+e0}` and
/// `V_β = b_{β+e2} − b_{β+e0}` (with the same convex weights), so `P_u × P_v` lies in the convex
/// cone of the products `U_β × V_γ`, and so does a drawn triangle's normal (its edges are
/// averages of `P_u`, `P_v`). `None` when that cone is not within a half-space.
pub fn normal_cone(net: &Net, flip: bool) -> Option<NormalCone> {
    let m = net.degree;
    let diff = |to: usize| -> Vec<Vec3> {
        Net::multi(m - 1)
            .map(|g| {
                let (mut a, mut b) = (g, g);
                a[0] += 1;
                b[to] += 1;
                net.at(b) - net.at(a)
            })
            .collect()
    };
    let (u, v) = (diff(1), diff(2));
    let sign = if flip { -1.0 } else { 1.0 };
    let mut dirs = Vec::with_capacity(u.len() * v.len());
    for a in &u {
        for b in &v {
            let c = a.cross(*b) * sign;
            if c != Vec3::ZERO {
                dirs.push(c.normalize());
            }
        }
    }
    let axis = dirs
        .iter()
        .fold(Vec3::ZERO, |s, &d| s + d)
        .normalize_or_zero();
    if axis == Vec3::ZERO {
        return None;
    }
    let cos = dirs.iter().map(|d| d.dot(axis)).fold(1.0f32, f32::min);
    // A margin for the rounding of the products.
    let cos = cos - 1e-5;
    (cos > 0.0).then_some(NormalCone { axis, cos })
}

impl NormalCone {
    /// Whether every triangle drawn inside sphere `s` with a normal in this cone faces away from
    /// `eye` (`(p − eye)·n > 0`): the angle `β` between the eye's direction to the sphere's
    /// centre and the axis, plus the sphere's angular radius `γ`, plus the cone's half-angle
    /// `θ`, is below 90° less `1e-4`. Written with cosines and sines, not inverse functions (a
    /// GPU's `acos` may be off by a thousandth of a radian, which would make the level pass and
    /// this mirror disagree on elements near the threshold, on every silhouette): with `β` and
    /// `φ = γ + θ` both below 90°, `β + φ < 90° − ε` exactly when `cos(β + φ) > sin ε`.
    /// Mirror: `lod_back_facing` in glsl/include/lod_metric.glsl.
    pub fn back_facing(&self, s: &Sphere, eye: Vec3) -> bool {
        let v = s.centre - eye;
        let d = v.length();
        if d <= s.radius {
            return false;
        }
        if self.cos <= 0.0 {
            return false;
        }
        let sine = |c: f32| (1.0 - c * c).max(0.0).sqrt();
        let cb = (v.dot(self.axis) / d).clamp(-1.0, 1.0);
        let sg = s.radius / d;
        let ct = self.cos.clamp(-1.0, 1.0);
        let (sb, cg, st) = (sine(cb), sine(sg), sine(ct));
        // φ = γ + θ.
        let cp = cg * ct - sg * st;
        let sp = sg * ct + cg * st;
        cb > 0.0 && cp > 0.0 && cb * cp - sb * sp > BACK_FACING_MARGIN
    }
}

/// `cos(90° − 1e-4 rad) = sin(1e-4)`, which is 1e-4 in `f32`: how far inside 90° a
/// facing-away patch's angles must stay (room for rounding). Mirror: `LOD_BACK_FACING_MARGIN`.
pub const BACK_FACING_MARGIN: f32 = 1e-4;

/// Whether `eye` sees a closed mesh wound outwards ([`Mesh::closed_outward`]) from outside, so
/// that its faces facing away are hidden behind its own front and may be culled: the eye lies
/// outside every element's sphere (`records`, the spheres of the drawn surface) and the coarse
/// mesh's winding number about it is zero. Every element's sphere contains its coarse triangle
/// and its drawn patch (a net's hull holds its corners; displacement grows the sphere), hence
/// every point between the two; blending each coarse triangle into its patch (shared edges
/// stay shared: the surfaces are watertight) moves the surface only inside the spheres, so the
/// winding number about an eye outside them is the drawn surface's. From inside (an eye in a
/// room, or closer to the surface than a sphere's reach) the visible faces may face away: no
/// culling for facing away then, only for lying outside the view.
pub fn eye_outside(eye: Vec3, records: &[super::frame::LodRecord], mesh: &Mesh) -> bool {
    let spheres = records.iter().map(|r| {
        let s = Vec4::from(r.sphere);
        Sphere {
            centre: s.truncate(),
            radius: s.w,
        }
    });
    eye_outside_spheres(eye, spheres, mesh)
}

/// [`eye_outside`] from the elements' spheres alone.
pub fn eye_outside_spheres(
    eye: Vec3,
    mut spheres: impl Iterator<Item = Sphere>,
    mesh: &Mesh,
) -> bool {
    spheres.all(|s| (s.centre - eye).length() > s.radius) && mesh.winding_number(eye).abs() < 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The facing-away test written with cosines decides as the angle sum `β + γ + θ < 90° −
    /// 1e-4` computed in double precision, for random eyes, spheres (up to nearly holding the
    /// eye) and cones (down to half-angles of a hundredth of a degree), except within 4e-6
    /// radians of the threshold (single precision's `1 − c²` near `c = 1` loses about 1e-6).
    #[test]
    fn back_facing_is_the_angle_sum() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f64 / (1u64 << 24) as f64
        };
        let (mut culled, mut kept, mut near) = (0, 0, 0);
        for _ in 0..200_000 {
            let unit = |x: f64, y: f64, z: f64| glam::DVec3::new(x, y, z).normalize();
            let axis = unit(next() - 0.5, next() - 0.5, next() - 0.5);
            let to_eye = unit(next() - 0.5, next() - 0.5, next() - 0.5);
            let d = 0.5 + 4.0 * next();
            let radius = d * 0.95 * next() * next();
            let cos = match next() {
                x if x < 0.2 => 1.0 - 1e-8 * (1.0 + 1e4 * next()),
                _ => 0.05 + 0.95 * next(),
            };
            let centre = glam::DVec3::new(next(), next(), next());
            let eye = centre + to_eye * d;
            let s = Sphere {
                centre: centre.as_vec3(),
                radius: radius as f32,
            };
            let cone = NormalCone {
                axis: axis.as_vec3(),
                cos: cos as f32,
            };
            // The reference, in double precision from the same single-precision inputs.
            let v = s.centre.as_dvec3() - eye.as_vec3().as_dvec3();
            let dist = v.length();
            let sum = (v.dot(cone.axis.as_dvec3()) / dist).clamp(-1.0, 1.0).acos()
                + (s.radius as f64 / dist).asin()
                + (cone.cos as f64).acos();
            let margin = sum - (std::f64::consts::FRAC_PI_2 - 1e-4);
            let got = cone.back_facing(&s, eye.as_vec3());
            if margin.abs() <= 4e-6 {
                near += 1;
                continue;
            }
            assert_eq!(got, margin < 0.0, "margin {margin}");
            if got {
                culled += 1;
            } else {
                kept += 1;
            }
        }
        assert!(
            culled > 10_000 && kept > 10_000 && near < 100,
            "{culled} {kept} {near}"
        );
    }
}

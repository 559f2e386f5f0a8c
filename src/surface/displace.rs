//! Displacement: maps a surface point to a surface point, along its unit normal; combines with
//! every surface. Mirror of `glsl/include/displace.glsl`.
//!
//! - `sine`: `P′ = P + a·sin(f·|P|)·N` (Boubekeur & Schlick 2005, Fig. 4), P and N the undisplaced
//!   point and the unit normal of the surface's normal field, in the mesh's coordinates (at split
//!   normals with closed seams, N is that field evaluated with the shared geometry normals:
//!   [`SurfacePoint::direction`]);
//! - `noise`: `P′ = P + a·Σ_o noise(2^o f·P)/2^o·N`, Ken Perlin's improved noise ([`super::noise`]);
//! - `heightmap`: `P′ = P + a·(h − b)·N`, h in [0, 1] read from a grayscale image at the OBJ's
//!   texture coordinates ([`super::heightmap`]), b = `--bias`; its derivatives come from the
//!   filtered map's own differences and the texture coordinates' derivatives.
//!
//! Normals: the height `h` has analytic derivatives `h_u = ∇h·dP/du`, `h_v = ∇h·dP/dv`; the
//! displaced tangents are `dP/du + h_u N`, `dP/dv + h_v N` (N held constant over the sample's
//! neighbourhood), and the displaced normal is Blinn's perturbed normal
//! `N′ = normalize(N + σ (h_u (N × dP/dv) − h_v (N × dP/du)) / |dP/du × dP/dv|)`, σ the sign of
//! `(dP/du × dP/dv)·N`: it equals the surface's own normal where the height is flat, so the
//! surface's normal field (not its geometric normal) is what displacement perturbs.
//!
//! Watertight: `P′` depends on P and the direction only, which are bit-identical on shared edges.

use super::bounds::{DisplaceBound, Height};
use super::{dot3, heightmap, noise, DisplaceFacts, DisplaceInputs, SurfaceParams, SurfacePoint};
use crate::lod::Sphere;
use glam::Vec3;

/// The displacement applied after the surface. The discriminant is the `DISPLACE`
/// specialization constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[repr(u32)]
pub enum Displace {
    /// No displacement.
    #[default]
    None = 0,
    /// a·sin(f·|P|) along the normal (the 2005 paper's Fig. 4).
    Sine = 1,
    /// a·Perlin noise(f·P) along the normal, --octaves octaves.
    Noise = 2,
    /// a·(h − bias) along the normal, h from a grayscale PNG at the mesh's texture coordinates.
    Heightmap = 3,
}

impl Displace {
    pub const ALL: [Displace; 4] = [
        Displace::None,
        Displace::Sine,
        Displace::Noise,
        Displace::Heightmap,
    ];

    /// What the displacement declares about itself.
    pub fn facts(self) -> &'static DisplaceFacts {
        const NONE: DisplaceFacts = DisplaceFacts {
            name: "none",
            help: "No displacement",
            options: &[],
            texture_coordinates: false,
            bindings: &[],
            bound: DisplaceBound::Zero,
        };
        const SINE: DisplaceFacts = DisplaceFacts {
            name: "sine",
            help: "a·sin(f·|P|) along the normal (the 2005 paper's Fig. 4)",
            options: &["amplitude", "frequency"],
            texture_coordinates: false,
            bindings: &[],
            bound: DisplaceBound::OfPoint(sine_bound),
        };
        const NOISE: DisplaceFacts = DisplaceFacts {
            name: "noise",
            help: "a·Perlin noise(f·P) along the normal, --octaves octaves",
            options: &["amplitude", "frequency", "octaves"],
            texture_coordinates: false,
            bindings: &["BINDING_NOISE"],
            bound: DisplaceBound::OfPoint(noise::bound),
        };
        const HEIGHTMAP: DisplaceFacts = DisplaceFacts {
            name: "heightmap",
            help: "a·(h − bias) along the normal, h from a grayscale PNG at the mesh's texture coordinates",
            options: &["amplitude", "bias", "heightmap"],
            texture_coordinates: true,
            bindings: &["BINDING_UVS", "BINDING_HEIGHTMAP", "BINDING_HEIGHTMAP_TEXELS"],
            bound: DisplaceBound::Texture(heightmap::BOUND),
        };
        match self {
            Displace::None => &NONE,
            Displace::Sine => &SINE,
            Displace::Noise => &NOISE,
            Displace::Heightmap => &HEIGHTMAP,
        }
    }

    pub fn name(self) -> &'static str {
        self.facts().name
    }
}

/// Height `h` at `p` and its gradient with respect to `p` (the procedural displacements).
pub fn height(d: Displace, params: &SurfaceParams, p: Vec3) -> (f32, Vec3) {
    let (a, f) = (params.amplitude, params.frequency);
    match d {
        Displace::None | Displace::Heightmap => (0.0, Vec3::ZERO),
        Displace::Sine => {
            let r = dot3(p, p).sqrt();
            let h = a * (f * r).sin();
            let grad = if r > 0.0 {
                p * (a * f * (f * r).cos() / r)
            } else {
                Vec3::ZERO
            };
            (h, grad)
        }
        Displace::Noise => {
            let mut h = 0.0;
            let mut grad = Vec3::ZERO;
            let mut scale = 1.0f32;
            for _ in 0..params.octaves {
                let (n, g) = noise::noise_grad(p * (f * scale));
                h += n / scale;
                grad += g * f;
                scale *= 2.0;
            }
            (a * h, grad * a)
        }
    }
}

/// The sine displacement's height bound over sphere `s`: `η = a sin(f r)` has `|η| <= |a|`,
/// `|∇η| <= |a| f`, and its Hessian's radial curvature `−a f² sin(f r)` and tangential
/// `a f cos(f r) / r` give `|a| max(f², f / r_min)`, `r_min` the sphere's distance from the
/// displacement's origin (the cone point of `|P|` at the origin has unbounded curvature: a patch
/// containing it gets no finite bound). `η` is a function of the distance from the origin alone
/// (`φ(r) = a sin(f r)`, `|φ''| <= |a| f²`: [`Radial`](super::bounds::Radial)), so a patch whose
/// distance from the origin changes slowly gets less than `|a| f² |P'|²` (src/lod/bound.rs). A
/// zero amplitude or frequency is no displacement at all: every bound zero.
fn sine_bound(params: &SurfaceParams, s: &Sphere) -> Height {
    let (a, f) = (params.amplitude.abs(), params.frequency);
    if !params.moves(super::Displace::Sine) {
        return Height {
            max: 0.0,
            grad: 0.0,
            hess: 0.0,
            radial: None,
        };
    }
    // η = a sin(f r): radial curvature −a f² sin(f r), tangential a f cos(f r) / r.
    let r_min = (s.centre - params.origin).length() - s.radius;
    let tangential = if r_min > 0.0 {
        f / r_min
    } else {
        f32::INFINITY
    };
    Height {
        max: a,
        grad: a * f,
        hess: a * (f * f).max(tangential),
        radial: Some(super::bounds::Radial {
            origin: params.origin,
            curve: a * f * f,
        }),
    }
}

/// Height and its derivatives by the sample's `u` and `v`.
fn height_uv(d: &DisplaceInputs, params: &SurfaceParams, sp: &SurfacePoint) -> [f32; 3] {
    let d = match d {
        DisplaceInputs::Heightmap(h) => {
            let (t, g) = h.map.sample(sp.uv, h.lod);
            let a = params.amplitude;
            let [du, dv] = sp.duv;
            return [
                a * (t - params.bias),
                a * (g.x * du.x + g.y * du.y),
                a * (g.x * dv.x + g.y * dv.y),
            ];
        }
        DisplaceInputs::None => Displace::None,
        DisplaceInputs::Sine => Displace::Sine,
        DisplaceInputs::Noise => Displace::Noise,
    };
    let (h, grad) = height(d, params, sp.position - params.origin);
    [h, dot3(grad, sp.dpdu), dot3(grad, sp.dpdv)]
}

/// Displace surface point `sp` by `d` (with its inputs).
pub fn apply(d: &DisplaceInputs, params: &SurfaceParams, sp: SurfacePoint) -> SurfacePoint {
    if matches!(d, DisplaceInputs::None) {
        return sp;
    }
    let [h, hu, hv] = height_uv(d, params, &sp);
    let n = sp.normal;
    let dir = sp.direction;
    let cross = sp.dpdu.cross(sp.dpdv);
    let area = cross.length();
    let normal = if area > 0.0 {
        let sigma = if dot3(cross, n) < 0.0 { -1.0 } else { 1.0 };
        let bump = (n.cross(sp.dpdv) * hu - n.cross(sp.dpdu) * hv) * (sigma / area);
        (n + bump).normalize_or_zero()
    } else {
        n
    };
    SurfacePoint {
        position: sp.position + dir * h,
        normal,
        direction: dir,
        dpdu: sp.dpdu + dir * hu,
        dpdv: sp.dpdv + dir * hv,
        ..sp
    }
}

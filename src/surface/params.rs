//! The values of the surfaces and displacements sent per frame ([`SurfaceParams`]), their
//! ranges and the limits on how far and how fast displacement may move a mesh. What changes
//! what is built (records, tables, pipelines) is in [`super::BuildOptions`].

use super::Displace;
use glam::Vec3;

/// The surfaces' and displacements' per-frame values (the `Frame` block's `params` on the GPU,
/// and `origin` and `bias` beside them): a frame may change any of them without rebuilding
/// anything.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceParams {
    /// Phong tessellation's shape factor α in [0, 1] (0: flat, 1: full projection).
    pub alpha: f32,
    /// Displacement amplitude a, in the mesh's units.
    pub amplitude: f32,
    /// Displacement frequency f, in radians (sine) or noise cells (noise) per mesh unit.
    pub frequency: f32,
    /// Octaves of the noise displacement (each doubles the frequency and halves the amplitude).
    pub octaves: u32,
    /// Where the mesh's own origin is in the coordinates drawn (zero unless the mesh is drawn
    /// moved and scaled, see [`SurfaceParams::in_drawn_frame`]): displacement is a function of
    /// the point in the mesh's coordinates.
    pub origin: Vec3,
    /// The height map displacement's bias b: `P′ = P + a·(h − b)·N`.
    pub bias: f32,
}

/// `x` for messages: as typed for ordinary magnitudes, in exponent form for huge or tiny ones
/// (`3.4e38`, not 39 digits).
pub fn shown_number(x: f32) -> String {
    let a = x.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e7).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Largest displacement reach accepted, in bounding radii of the mesh
/// ([`SurfaceParams::check_displacement`]).
pub const MAX_REACH_RADII: f64 = 1e6;

/// Largest displacement frequency accepted, in radians per bounding radius of the mesh.
pub const MAX_FREQUENCY_RADII: f64 = 1e6;

/// Largest phase accepted for `sine` and `noise`, in radians: their argument (`f·|P|`, and
/// `2^o f·P` for each octave) is a function of the mesh's own coordinates, computed in `f32`,
/// which resolves it to within half a radian up to 2^22. A mesh far from its origin reaches
/// phases the frequency limit alone would not bound.
pub const MAX_PHASE: f64 = 4_194_304.0;

impl Default for SurfaceParams {
    fn default() -> Self {
        Self {
            alpha: 0.75,
            amplitude: 0.03,
            frequency: 24.0,
            octaves: 1,
            origin: Vec3::ZERO,
            bias: 0.0,
        }
    }
}

impl SurfaceParams {
    /// Most octaves accepted (beyond this the added detail is below f32 resolution).
    pub const MAX_OCTAVES: u32 = 8;

    /// Defaults scaled to a mesh of bounding radius `radius`: amplitude 3% of it, frequency
    /// 24 radians (sine) per radius.
    pub fn for_radius(radius: f32) -> Self {
        let r = if radius.is_finite() && radius > 0.0 {
            radius
        } else {
            1.0
        };
        Self {
            amplitude: 0.03 * r,
            frequency: 24.0 / r,
            ..Self::default()
        }
    }

    /// One sentence naming the first parameter out of its range.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.alpha.is_finite() && (0.0..=1.0).contains(&self.alpha)) {
            return Err(format!("--alpha {} is not within [0, 1]", self.alpha));
        }
        if !self.amplitude.is_finite() {
            return Err(format!(
                "--amplitude {} is not a finite number",
                self.amplitude
            ));
        }
        if !(self.frequency.is_finite() && self.frequency >= 0.0) {
            return Err(format!(
                "--frequency {} is not a finite number >= 0",
                self.frequency
            ));
        }
        if !self.bias.is_finite() {
            return Err(format!("--bias {} is not a finite number", self.bias));
        }
        if !(1..=Self::MAX_OCTAVES).contains(&self.octaves) {
            return Err(format!(
                "--octaves {} is not within [1, {}]",
                self.octaves,
                Self::MAX_OCTAVES
            ));
        }
        Ok(())
    }

    /// Whether displacement `d` moves any point: not without amplitude, nor a sine or noise
    /// without frequency (`a sin(0)`, `a noise(0)`: zero), which draw the undisplaced surface's
    /// positions (`P + 0`: the same values, a coordinate `−0` made `+0`).
    /// Mirror: `lod_moves` in glsl/include/lod.glsl.
    pub fn moves(&self, d: Displace) -> bool {
        d != Displace::None
            && self.amplitude != 0.0
            && !(matches!(d, Displace::Sine | Displace::Noise) && self.frequency == 0.0)
    }

    /// How far displacement `d` can move a point, in the mesh's units: |a| times the largest
    /// |height| (1 for sine, 2 for noise's octaves, 1 + |bias| for a height map).
    pub fn reach(&self, d: Displace) -> f64 {
        let h = match d {
            Displace::None => 0.0,
            Displace::Sine => 1.0,
            Displace::Noise => 2.0,
            Displace::Heightmap => 1.0 + (self.bias as f64).abs(),
        };
        (self.amplitude as f64).abs() * h
    }

    /// The options that set [`SurfaceParams::reach`], for messages: "--amplitude 2" or
    /// "--amplitude 2 with --bias 0.5".
    pub fn reach_options(&self, d: Displace) -> String {
        if d == Displace::Heightmap && self.bias != 0.0 {
            format!(
                "--amplitude {} with --bias {}",
                shown_number(self.amplitude),
                shown_number(self.bias)
            )
        } else {
            format!("--amplitude {}", shown_number(self.amplitude))
        }
    }

    /// Refuses a displacement whose result would not be finite or meaningful on a mesh of
    /// bounding radius `radius` whose points are at most `extent` from the origin, before
    /// anything is drawn: the reach at most [`MAX_REACH_RADII`] radii, the highest frequency
    /// (the last octave's) at most [`MAX_FREQUENCY_RADII`] radians per radius and
    /// [`MAX_PHASE`] radians at the mesh's farthest point from its origin, and the displaced
    /// points within `f32`. Within these limits positions, tangents and normals stay
    /// finite (the normal's perturbation is at most about a·f, whose square is far from
    /// overflowing).
    pub fn check_displacement(&self, d: Displace, radius: f32, extent: f64) -> Result<(), String> {
        if d == Displace::None {
            return Ok(());
        }
        let r = if radius.is_finite() && radius > 0.0 {
            radius as f64
        } else {
            1.0
        };
        let reach = self.reach(d);
        let by = self.reach_options(d);
        if reach > MAX_REACH_RADII * r {
            return Err(format!(
                "{by} moves the surface up to {:.3e} times the mesh's bounding radius ({r:.3e}); at most {MAX_REACH_RADII:e} times is accepted (beyond that positions and normals are not finite)",
                reach / r
            ));
        }
        if extent + reach > f32::MAX as f64 / 4.0 {
            return Err(format!(
                "{by} moves the surface beyond the range of f32 coordinates (the mesh reaches {extent:.3e} from the origin)"
            ));
        }
        if matches!(d, Displace::Sine | Displace::Noise) {
            let octaves = if d == Displace::Noise {
                self.octaves.max(1)
            } else {
                1
            };
            let top = self.frequency as f64 * r * 2f64.powi(octaves as i32 - 1);
            if top > MAX_FREQUENCY_RADII {
                let with = if octaves > 1 {
                    format!(" (with --octaves {octaves}, the last octave's)")
                } else {
                    String::new()
                };
                return Err(format!(
                    "--frequency {} is {top:.3e} radians per bounding radius of the mesh{with}; at most {MAX_FREQUENCY_RADII:e} is accepted (beyond that the displacement is noise at any level and its normals are not finite)",
                    shown_number(self.frequency)
                ));
            }
            let phase = top / r * extent;
            if phase > MAX_PHASE {
                return Err(format!(
                    "--displace {} at --frequency {} reaches phases of {phase:.3e} radians on this mesh, whose points lie up to {extent:.3e} from its origin (the displacement is a function of the mesh's coordinates); f32 resolves them up to 2^22 (about 4.2e6): move the mesh nearer its origin or lower --frequency{}",
                    d.name(),
                    shown_number(self.frequency),
                    if octaves > 1 { " or --octaves" } else { "" }
                ));
            }
        }
        Ok(())
    }

    /// The same displacement for a mesh drawn as `(P − centre) · scale` (what
    /// `Mesh::for_viewing` draws): amplitude in drawn units, frequency per drawn unit, and the
    /// mesh's origin where it lands.
    pub fn in_drawn_frame(&self, centre: glam::DVec3, scale: f64) -> Self {
        Self {
            amplitude: (self.amplitude as f64 * scale) as f32,
            frequency: (self.frequency as f64 / scale) as f32,
            origin: (-centre * scale).as_vec3() + self.origin,
            ..*self
        }
    }

    /// As the `Frame` block's `params` vector: (alpha, amplitude, frequency, octaves).
    pub fn to_gpu(&self) -> [f32; 4] {
        [
            self.alpha,
            self.amplitude,
            self.frequency,
            self.octaves as f32,
        ]
    }
}

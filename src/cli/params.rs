//! Turning the surface parameters given on the command line ([`ParamOpts`]) into the
//! library's [`SurfaceParams`], checked, every value named as typed in its sentence.
#![forbid(unsafe_code)]

use super::args::ParamOpts;
use meshrefine::surface::{BuildOptions, Displace, SurfaceParams};

impl ParamOpts {
    /// The parameters for a mesh of bounding radius `radius`, checked (a bad value named as
    /// typed).
    pub fn params(&self, radius: f32) -> Result<SurfaceParams, String> {
        self.alpha
            .check("alpha", Some((0.0, 1.0, "within [0, 1]")))?;
        if let Some(a) = &self.amplitude {
            a.check("amplitude", None)?;
        }
        if let Some(f) = &self.frequency {
            f.check("frequency", Some((0.0, f32::MAX, "a finite number >= 0")))?;
        }
        self.bias.check("bias", None)?;
        // A whole number as typed (`numbers::whole_number`), so that a negative or huge count
        // gets the range's sentence too.
        let octaves = (self.octaves.parse::<u32>().ok())
            .filter(|o| (1..=SurfaceParams::MAX_OCTAVES).contains(o))
            .ok_or_else(|| {
                format!(
                    "--octaves {} is not within [1, {}]",
                    meshrefine::mesh::shown_word(&self.octaves),
                    SurfaceParams::MAX_OCTAVES
                )
            })?;
        let d = SurfaceParams::for_radius(radius);
        let p = SurfaceParams {
            alpha: self.alpha.value,
            amplitude: self.amplitude.as_ref().map_or(d.amplitude, |a| a.value),
            frequency: self.frequency.as_ref().map_or(d.frequency, |f| f.value),
            octaves,
            origin: d.origin,
            bias: self.bias.value,
        };
        p.validate()?;
        Ok(p)
    }

    /// The options built into the mesh's data, checked.
    pub fn build(&self) -> Result<BuildOptions, String> {
        let b = BuildOptions {
            seams: self.pn_seams,
            boundary: self.boundary,
            bft_level: self.bft_level,
            normal_field: self.normal_field,
        };
        b.validate()?;
        Ok(b)
    }

    /// [`ParamOpts::params`] for `mesh`, with every displacement in `displaces` checked against
    /// the mesh's scale (`SurfaceParams::check_displacement`): a result that would not be
    /// finite is refused before anything is drawn.
    pub fn params_for(
        &self,
        mesh: &meshrefine::mesh::Mesh,
        displaces: &[Displace],
    ) -> Result<SurfaceParams, String> {
        let radius = mesh.bounding_radius();
        let p = self.params(radius)?;
        let (lo, hi) = mesh.bounds();
        // In f64: a mesh 1.9e19 from its origin has a squared extent past f32's range.
        let extent = lo.abs().max(hi.abs()).as_dvec3().length();
        for &d in displaces {
            p.check_displacement(d, radius, extent).map_err(|e| {
                // A value given is named as typed; a frequency not given is the mesh's
                // default, named as such.
                let shown = |name: &str, x: f32| {
                    format!("--{name} {}", meshrefine::surface::shown_number(x))
                };
                let amplitude = shown("amplitude", p.amplitude);
                let e = match &self.amplitude {
                    Some(a) => e.replacen(&amplitude, &format!("--amplitude {}", a.text.trim()), 1),
                    None => e.replacen(
                        &amplitude,
                        &format!("the default {amplitude} (3% of the mesh's bounding radius)"),
                        1,
                    ),
                };
                let e = e.replacen(
                    &format!(" with {}", shown("bias", p.bias)),
                    &format!(" with --bias {}", self.bias.text.trim()),
                    1,
                );
                let typed = shown("frequency", p.frequency);
                match &self.frequency {
                    None => e.replacen(
                        &typed,
                        &format!("the default {typed} (24 over the mesh's bounding radius)"),
                        1,
                    ),
                    Some(f) => e.replacen(&typed, &format!("--frequency {}", f.text.trim()), 1),
                }
            })?;
        }
        Ok(p)
    }
}

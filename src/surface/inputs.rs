//! What each surface's and displacement's CPU mirror reads besides the element record and the
//! per-frame [`SurfaceParams`]: each declares its inputs in its own module (`pn`: its normal
//! field; [`stpn::Inputs`]; [`loop_::Inputs`]; [`heightmap::Inputs`]), and one function,
//! [`Mirror::new`], builds them from what a mesh holds ([`Sources`]) and the per-build options
//! ([`BuildOptions`]). A [`Mirror`] is a surface and a displacement together with their inputs,
//! so an input cannot be missing when a sample is evaluated: the one place that could find it
//! missing is `Mirror::new`, which says so in a sentence (docs/architecture.md, "Surfaces as
//! plug-ins").
//!
//! The evaluation ([`Mirror::eval`]) matches on the variant once per sample, as it matched on
//! the surface before: no allocation, no dynamic dispatch.

use super::{
    displace, heightmap, loop_, stpn, BuildOptions, CornerRecord, Displace, ElementRecord,
    Heightmap, NormalField, Surface, SurfaceParams, SurfacePoint,
};

/// What a mesh holds for the mirrors to read, each part where the mesh has it; [`Mirror::new`]
/// takes what the chosen surface and displacement declare.
#[derive(Clone, Copy, Debug, Default)]
pub struct Sources<'a> {
    /// Each coarse triangle's texture coordinates (stored corner order), when the mesh has them
    /// on every face.
    pub uvs: Option<&'a [[[f32; 2]; 3]]>,
    /// The height map.
    pub heightmap: Option<&'a Heightmap>,
    /// The pyramid level the height map is read at (one per mesh and refinement level,
    /// [`Heightmap::lod_for`]).
    pub lod: f32,
    /// Every vertex's scalar tags (`None`: neutral tags, where `stpn` is `pn`).
    pub tags: Option<&'a [stpn::VertexTag]>,
    /// The `loop` surface's tables and M1, once built.
    pub loop_: Option<loop_::Inputs<'a>>,
}

/// A surface with the inputs its mirror reads (each declared in the surface's module).
#[derive(Clone, Copy, Debug)]
pub enum SurfaceInputs<'a> {
    Flat,
    Phong,
    /// `pn` reads its normal field (a per-build option: the `NORMAL_FIELD` specialization
    /// constant on the GPU).
    Pn(NormalField),
    Stpn(stpn::Inputs<'a>),
    Loop(loop_::Inputs<'a>),
}

/// A displacement with the inputs its mirror reads.
#[derive(Clone, Copy, Debug)]
pub enum DisplaceInputs<'a> {
    None,
    Sine,
    Noise,
    Heightmap(heightmap::Inputs<'a>),
}

/// A surface and a displacement with everything their mirrors read besides the records and the
/// per-frame parameters: what every CPU evaluation (the static driver, the framing camera, the
/// bounds, the tests' expectations) is made from.
#[derive(Clone, Copy, Debug)]
pub struct Mirror<'a> {
    pub surface: SurfaceInputs<'a>,
    pub displace: DisplaceInputs<'a>,
    /// The elements' texture coordinates, where the surface's elements carry them and the mesh
    /// has them (always, with the `heightmap` displacement).
    pub uvs: Option<&'a [[[f32; 2]; 3]]>,
}

impl<'a> Mirror<'a> {
    /// The mirror of `surface` with `displace`, its inputs taken from `sources` and `build`;
    /// one sentence when something they declare is not there.
    pub fn new(
        surface: Surface,
        displace: Displace,
        build: &BuildOptions,
        sources: &Sources<'a>,
    ) -> Result<Self, String> {
        let field = build.normal_field;
        let s = match surface {
            Surface::Flat => SurfaceInputs::Flat,
            Surface::Phong => SurfaceInputs::Phong,
            Surface::Pn => SurfaceInputs::Pn(field),
            Surface::Stpn => SurfaceInputs::Stpn(stpn::Inputs {
                field,
                tags: sources.tags,
            }),
            Surface::Loop => SurfaceInputs::Loop(sources.loop_.ok_or_else(|| {
                "the loop surface's M1 faces and tables are not built yet (the scene builds them when prepared for loop)".to_string()
            })?),
        };
        if let Some(why) = surface.incompatibility(displace, sources.uvs.is_some()) {
            return Err(why);
        }
        let uvs = sources.uvs.filter(|_| surface.facts().texture_coordinates);
        let d = match displace {
            Displace::None => DisplaceInputs::None,
            Displace::Sine => DisplaceInputs::Sine,
            Displace::Noise => DisplaceInputs::Noise,
            Displace::Heightmap => DisplaceInputs::Heightmap(heightmap::Inputs {
                map: sources
                    .heightmap
                    .ok_or_else(|| "the heightmap displacement has no height map".to_string())?,
                lod: sources.lod,
            }),
        };
        Ok(Self {
            surface: s,
            displace: d,
            uvs,
        })
    }

    /// The surface this mirror evaluates.
    pub fn surface(&self) -> Surface {
        match self.surface {
            SurfaceInputs::Flat => Surface::Flat,
            SurfaceInputs::Phong => Surface::Phong,
            SurfaceInputs::Pn(_) => Surface::Pn,
            SurfaceInputs::Stpn(_) => Surface::Stpn,
            SurfaceInputs::Loop(_) => Surface::Loop,
        }
    }

    /// The displacement this mirror applies.
    pub fn displace(&self) -> Displace {
        match self.displace {
            DisplaceInputs::None => Displace::None,
            DisplaceInputs::Sine => Displace::Sine,
            DisplaceInputs::Noise => Displace::Noise,
            DisplaceInputs::Heightmap(_) => Displace::Heightmap,
        }
    }

    /// The normal field of `pn` and `stpn` (the default for the others, which read none).
    pub fn normal_field(&self) -> NormalField {
        match self.surface {
            SurfaceInputs::Pn(f) => f,
            SurfaceInputs::Stpn(i) => i.field,
            _ => NormalField::default(),
        }
    }

    /// Element `t`'s texture coordinates, where it has them.
    pub fn uv(&self, t: usize) -> Option<&'a [[f32; 2]; 3]> {
        self.uvs.and_then(|u| u.get(t))
    }

    /// An element's corners' global vertex indices (M1's for `loop`): what orders an edge
    /// canonically (from the lower index to the higher).
    pub fn corner_indices(&self, rec: &ElementRecord) -> [u32; 3] {
        match self.surface {
            SurfaceInputs::Loop((data, _)) => data.m1.faces[rec.words[0] as usize],
            _ => {
                let r = CornerRecord::decode(rec);
                [r.idx[0], r.idx[1], r.idx[2]]
            }
        }
    }

    /// Evaluate the surface (without displacement) at barycentric sample `bary` of element `t`,
    /// whose record is `rec`. Mirror of `surface_eval()` in `glsl/include/surface.glsl`.
    pub fn eval_surface(
        &self,
        params: &SurfaceParams,
        t: usize,
        rec: &ElementRecord,
        bary: [f32; 3],
    ) -> SurfacePoint {
        let (surface, field, tags) = match self.surface {
            SurfaceInputs::Flat => (Surface::Flat, NormalField::default(), None),
            SurfaceInputs::Phong => (Surface::Phong, NormalField::default(), None),
            SurfaceInputs::Pn(f) => (Surface::Pn, f, None),
            SurfaceInputs::Stpn(i) => (Surface::Stpn, i.field, i.tags),
            SurfaceInputs::Loop((data, frame)) => return loop_::eval(data, frame, rec, bary),
        };
        super::eval_local(surface, params, field, tags, rec, bary, self.uv(t))
    }

    /// Evaluate the surface and its displacement at barycentric sample `bary` of element `t`,
    /// whose record is `rec`: what every driver computes for every sample. Mirror of
    /// `evaluate()` in `glsl/include/surface.glsl`.
    pub fn eval(
        &self,
        params: &SurfaceParams,
        t: usize,
        rec: &ElementRecord,
        bary: [f32; 3],
    ) -> SurfacePoint {
        let sp = self.eval_surface(params, t, rec, bary);
        displace::apply(&self.displace, params, sp)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a surface or displacement declares is required, and `Mirror::new` says which is
    /// missing instead of an evaluation finding out.
    #[test]
    fn missing_inputs_are_refused_when_the_mirror_is_built() {
        let build = BuildOptions::default();
        let none = Sources::default();
        let e = Mirror::new(Surface::Loop, Displace::None, &build, &none).unwrap_err();
        assert!(e.contains("loop surface's M1 faces"), "{e}");
        let e = Mirror::new(Surface::Pn, Displace::Heightmap, &build, &none).unwrap_err();
        assert!(e.contains("no texture coordinates"), "{e}");
        let uvs = [[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]];
        let with_uvs = Sources {
            uvs: Some(&uvs),
            ..Sources::default()
        };
        let e = Mirror::new(Surface::Pn, Displace::Heightmap, &build, &with_uvs).unwrap_err();
        assert!(e.contains("no height map"), "{e}");
        let map = Heightmap::generated();
        let full = Sources {
            heightmap: Some(&map),
            ..with_uvs
        };
        let m = Mirror::new(Surface::Pn, Displace::Heightmap, &build, &full).unwrap();
        assert_eq!(
            (m.surface(), m.displace(), m.uv(0), m.uv(1)),
            (Surface::Pn, Displace::Heightmap, Some(&uvs[0]), None)
        );
        // Loop's elements carry no texture coordinates: the mesh's are not handed to it.
        for s in Surface::ALL {
            let facts = s.facts();
            if s != Surface::Loop {
                let m = Mirror::new(s, Displace::None, &build, &full).unwrap();
                assert_eq!(m.surface(), s);
                assert_eq!(m.uvs.is_some(), facts.texture_coordinates, "{}", facts.name);
            }
        }
    }
}

//! What each surface and displacement declares about itself: its elements, the options it
//! reads, what inputs it needs, where its normal field is evaluated, how its chord error is
//! bounded (src/surface/bounds.rs). Each surface's module
//! holds its own `FACTS` (`flat.rs`, `phong.rs`, `pn.rs`, `stpn.rs`, `loop.rs`), each
//! displacement's is in `displace.rs`; [`super::Surface::facts`] and
//! [`super::Displace::facts`] are the one place that matches on them. The scene, the window,
//! the command line and the benchmark ask these questions instead of naming surfaces.

/// What a surface's elements are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Elements {
    /// The coarse mesh's triangles, one record each (the local surfaces).
    CoarseTriangles,
    /// The faces of one Loop step M1, which a pre-pass makes on the GPU every frame from the
    /// coarse positions (`loop`).
    LoopFaces,
}

impl Elements {
    /// What they are called in the panel and reports.
    pub fn label(self) -> &'static str {
        match self {
            Elements::CoarseTriangles => "coarse triangles",
            Elements::LoopFaces => "M1 faces",
        }
    }
}

/// Where a surface's normal field is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FragmentNormals {
    /// Interpolated from the refined vertices.
    Never,
    /// In the fragment stage, always: highlights do not depend on the level.
    Always,
    /// In the fragment stage from this level up, without displacement and on the GPU drivers
    /// (where refined vertices outnumber pixels, evaluating per fragment costs less).
    FromLevel(u32),
}

/// What a surface declares about itself.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceFacts {
    /// The name on the command line, in the GLSL and of the module.
    pub name: &'static str,
    /// One line for `--help`: what it is and where it comes from.
    pub help: &'static str,
    pub elements: Elements,
    /// The command-line options (clap ids) that this surface reads and no other surface needs
    /// to (`alpha` for phong): an option read by none of the chosen surfaces is reported.
    pub options: &'static [&'static str],
    /// Whether its elements carry the coarse triangles' texture coordinates (what a height map
    /// is sampled at).
    pub texture_coordinates: bool,
    /// Whether it needs every face of the file: one dropped at loading (degenerate or
    /// duplicate) would open a hole in what it refines.
    pub needs_every_face: bool,
    /// Whether it reads per-vertex scalar tags (`--tags`, or derived from hard edges).
    pub tags: bool,
    pub fragment_normals: FragmentNormals,
    /// The per-mesh bindings (set 1, `src/render/bindings.rs`) its GLSL include declares
    /// beyond the element records, which the mesh's descriptor sets must hold.
    pub bindings: &'static [&'static str],
    /// How its chord error is bounded (src/lod's adaptive levels).
    pub bound: super::bounds::SurfaceBound,
}

/// What a displacement declares about itself.
#[derive(Clone, Copy, Debug)]
pub struct DisplaceFacts {
    pub name: &'static str,
    /// One line for `--help`.
    pub help: &'static str,
    /// The command-line options (clap ids) it reads.
    pub options: &'static [&'static str],
    /// Whether it reads the elements' texture coordinates.
    pub texture_coordinates: bool,
    /// The bindings its GLSL reads (besides the frame's uniforms).
    pub bindings: &'static [&'static str],
    /// How its height is bounded (src/lod's adaptive levels).
    pub bound: super::bounds::DisplaceBound,
}

/// Why `surface` cannot be drawn with `displace` on a mesh that has (or lacks) texture
/// coordinates on every face: one sentence, or `None` when it can.
pub fn incompatibility(
    surface: &SurfaceFacts,
    displace: &DisplaceFacts,
    mesh_has_texcoords: bool,
) -> Option<String> {
    if !displace.texture_coordinates {
        return None;
    }
    if !surface.texture_coordinates {
        return Some(format!(
            "the {} surface has no texture coordinates: the {} displacement needs them (use sine or noise)",
            surface.name, displace.name
        ));
    }
    (!mesh_has_texcoords).then(|| {
        format!(
            "the mesh has no texture coordinates (vt on every face): the {} displacement reads the map there",
            displace.name
        )
    })
}

#[cfg(test)]
mod tests {
    use super::super::{Displace, Surface};

    /// The `binding = BINDING_X` names a GLSL source declares.
    fn declared(source: &str) -> Vec<&str> {
        let mut out: Vec<&str> = source
            .match_indices("binding = ")
            .map(|(i, m)| {
                let rest = &source[i + m.len()..];
                let end = rest
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(rest.len());
                &rest[..end]
            })
            .collect();
        out.sort_unstable();
        out
    }

    fn glsl(name: &str) -> String {
        let path = format!("{}/glsl/include/{name}.glsl", env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
    }

    /// Each surface's declared bindings are exactly those its GLSL include declares.
    #[test]
    fn surfaces_declare_the_bindings_their_glsl_reads() {
        for s in Surface::ALL {
            let mut want: Vec<&str> = s.facts().bindings.to_vec();
            want.sort_unstable();
            assert_eq!(declared(&glsl(s.name())), want, "{}", s.name());
        }
    }

    /// Each displacement with a GLSL file of its own declares the bindings that file reads
    /// (texture coordinates live with the records, glsl/include/records.glsl).
    #[test]
    fn displacements_declare_the_bindings_their_glsl_reads() {
        for d in Displace::ALL {
            let path = format!(
                "{}/glsl/include/{}.glsl",
                env!("CARGO_MANIFEST_DIR"),
                d.name()
            );
            let Ok(source) = std::fs::read_to_string(path) else {
                continue;
            };
            for b in declared(&source) {
                assert!(d.facts().bindings.contains(&b), "{}: {b}", d.name());
            }
        }
        assert!(Displace::Heightmap
            .facts()
            .bindings
            .contains(&"BINDING_UVS"));
    }
}

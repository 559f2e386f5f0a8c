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

/// A pass a surface declares to run before drawing: it makes the surface's elements from the
/// coarse mesh. The surface says which; the renderer builds its data when the surface is first
/// drawn (or its build options change) and records it every frame before the draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PrePass {
    /// One Loop subdivision step M0 -> M1, whose faces are the elements: its data (the step's
    /// entries, M1's topology, the basis function tables of the build options' `boundary` and
    /// `bft_level`) built once per mesh, the step run on the GPU every frame from the coarse
    /// positions (src/render/loop_gpu.rs), and on the CPU for the mirror when it is read.
    LoopStep,
}

impl PrePass {
    /// Whether data built with `built` serves `want`: the options the pass's data is made of
    /// are the same.
    pub fn same_data(self, built: &super::BuildOptions, want: &super::BuildOptions) -> bool {
        match self {
            PrePass::LoopStep => {
                built.boundary == want.boundary && built.bft_level == want.bft_level
            }
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
    /// The pass that makes its elements before drawing, if any (`loop`: one Loop step).
    pub pre_pass: Option<PrePass>,
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
    // The mesh first: without its coordinates no surface can take the displacement.
    if !mesh_has_texcoords {
        return Some(format!(
            "the mesh has no texture coordinates (vt on every face), where the {} displacement reads its map",
            displace.name
        ));
    }
    (!surface.texture_coordinates).then(|| {
        format!(
            "the {} surface has no texture coordinates: the {} displacement needs them (use sine or noise)",
            surface.name, displace.name
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

    /// A surface whose elements are not the coarse triangles declares the pass that makes them.
    #[test]
    fn elements_other_than_coarse_triangles_come_from_a_pre_pass() {
        for s in Surface::ALL {
            let f = s.facts();
            assert_eq!(
                f.pre_pass.is_some(),
                f.elements != super::Elements::CoarseTriangles,
                "{}",
                f.name
            );
        }
    }

    /// Loop's step is rebuilt for its boundary rule and table level, not for the options of the
    /// other surfaces or the pipelines.
    #[test]
    fn loop_step_data_depends_on_boundary_and_table_level_alone() {
        use super::super::{loop_, BuildOptions, NormalField, Seams};
        let pass = Surface::Loop.pre_pass().unwrap();
        let built = BuildOptions::default();
        let other = BuildOptions {
            seams: Seams::Open,
            normal_field: NormalField::Linear,
            ..built
        };
        assert!(pass.same_data(&built, &other));
        let boundary = BuildOptions {
            boundary: loop_::Boundary::EdgeAndCorner,
            ..built
        };
        let level = BuildOptions {
            bft_level: built.bft_level + 1,
            ..built
        };
        assert!(!pass.same_data(&built, &boundary) && !pass.same_data(&built, &level));
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

//! The cage overlay: the coarse mesh's edges drawn as lines over the refined surface (the
//! control mesh, for `loop`, whose M0 is the coarse mesh), so that element boundaries, the
//! pattern or the tessellator's rings inside them, and the control net can be told apart
//! (`--wireframe cage|both`, the window's `W`). glsl/cage/cage.vert and cage.frag draw it.

use super::pipelines::Renderer;
use crate::gpu::shaders::names;
use crate::gpu::{
    vk, Buffer, BufferDesc, Cmd, Context, GpuError, GraphicsPipelineDesc, Pipeline, PipelineLayout,
};
use crate::mesh::Mesh;
use std::sync::Arc;

/// Which edges a wireframe shows (`--wireframe refined|cage|both`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Wireframe {
    /// The refined triangles' edges, darker than the surface.
    #[default]
    Refined,
    /// The coarse mesh's edges (Loop's control mesh) in light cyan (glsl/cage/cage.frag).
    Cage,
    /// Both.
    Both,
}

impl Wireframe {
    pub const ALL: [Wireframe; 3] = [Wireframe::Refined, Wireframe::Cage, Wireframe::Both];

    pub fn name(self) -> &'static str {
        match self {
            Wireframe::Refined => "refined",
            Wireframe::Cage => "cage",
            Wireframe::Both => "both",
        }
    }

    /// Whether the refined triangles' edges are drawn.
    pub fn refined(self) -> bool {
        self != Wireframe::Cage
    }

    /// Whether the cage is drawn.
    pub fn cage(self) -> bool {
        self != Wireframe::Refined
    }
}

/// The coarse mesh's unique edges as line vertices, on the GPU.
pub struct Cage {
    /// Two positions (`vec3`) per edge.
    lines: Buffer,
    /// Each edge's two vertex indices, ascending, sorted: what `lines` holds.
    edges: Vec<[u32; 2]>,
    /// The mesh moved since `lines` were written (`Scene::update_mesh`): they are written again
    /// when the cage is next prepared to be drawn.
    pub(super) stale: bool,
}

/// `mesh`'s unique edges (by vertex index), each as (smaller, larger), sorted.
pub fn unique_edges(mesh: &Mesh) -> Vec<[u32; 2]> {
    let mut edges: Vec<[u32; 2]> = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t.p[k], t.p[(k + 1) % 3])))
        .map(|(a, b)| [a.min(b), a.max(b)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

impl Cage {
    /// The edges of `mesh`, uploaded.
    pub fn new(ctx: &Arc<Context>, mesh: &Mesh) -> Result<Self, GpuError> {
        let edges = unique_edges(mesh);
        let mut lines = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                (edges.len().max(1) * 2 * 12) as u64,
                vk::BufferUsageFlags::VERTEX_BUFFER,
            ),
            "cage lines",
        )?;
        lines.write_pod(0, &line_vertices(&edges, &mesh.positions));
        Ok(Self {
            lines,
            edges,
            stale: false,
        })
    }

    /// New positions for the same mesh (animation). The caller makes sure no pending work
    /// reads the lines.
    pub fn update(&mut self, positions: &[glam::Vec3]) {
        self.lines
            .write_pod(0, &line_vertices(&self.edges, positions));
    }

    /// Bytes [`Cage::update`] writes: two positions an edge.
    pub fn upload_bytes(&self) -> u64 {
        self.edges.len() as u64 * 24
    }

    /// Lines drawn.
    pub fn edge_count(&self) -> u32 {
        self.edges.len() as u32
    }

    /// Draw the cage (frame set bound; inside the rendering).
    pub fn cmd_draw(&self, cmd: &Cmd<'_>, r: &Renderer) {
        cmd.bind_graphics_pipeline(r.cage_pipeline());
        cmd.bind_vertex_buffer(0, &self.lines);
        cmd.draw(2 * self.edge_count(), 1, 0, 0);
    }
}

fn line_vertices(edges: &[[u32; 2]], positions: &[glam::Vec3]) -> Vec<[f32; 3]> {
    edges
        .iter()
        .flat_map(|e| e.map(|v| positions[v as usize].to_array()))
        .collect()
}

/// The cage's pipeline: lines, depth-tested, pulled towards the camera by the vertex stage so
/// they win against the surface where they lie on it.
pub fn pipeline(
    ctx: &Arc<Context>,
    layout: &PipelineLayout,
    color_format: vk::Format,
    depth_format: vk::Format,
    samples: vk::SampleCountFlags,
) -> Result<Pipeline, GpuError> {
    let desc = GraphicsPipelineDesc {
        stages: vec![
            (vk::ShaderStageFlags::VERTEX, names::CAGE_CAGE_VERT.into()),
            (vk::ShaderStageFlags::FRAGMENT, names::CAGE_CAGE_FRAG.into()),
        ],
        spec: vec![],
        vertex_bindings: vec![(0, 12, false)],
        vertex_attributes: vec![(0, 0, vk::Format::R32G32B32_SFLOAT, 0)],
        topology: vk::PrimitiveTopology::LINE_LIST,
        primitive_restart: false,
        patch_control_points: 0,
        color_format,
        depth_format,
        polygon_mode: vk::PolygonMode::FILL,
        depth_bias: None,
        depth_write: false,
        dynamic_cull: false,
        samples,
    };
    Pipeline::new_graphics(ctx, layout, &desc, "cage lines")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;

    /// A closed triangle mesh has 3F/2 edges, each once.
    #[test]
    fn a_closed_mesh_has_three_halves_its_faces_in_edges() {
        let (mesh, _) = load_model("spot_control_tri.obj");
        let edges = unique_edges(&mesh);
        assert_eq!(edges.len() * 2, mesh.triangles.len() * 3);
        assert!(edges.iter().all(|e| e[0] < e[1]));
        let (grid, _) = load_model("grid_open_8x8.obj");
        // 8 x 8 quads, two triangles each: 8·9 horizontal, 8·9 vertical, 64 diagonal edges.
        assert_eq!(unique_edges(&grid).len(), 2 * 8 * 9 + 64);
    }
}

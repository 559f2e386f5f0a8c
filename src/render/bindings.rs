// Descriptor set and binding numbers, defined once here and handed to GLSL as `-D` macro
// definitions by build.rs (which `include!`s this file), so the two cannot drift.
// Sets are grouped by update rate (docs/architecture.md, "Descriptors"): 0 per frame, 1 per
// mesh, 2 capture output.

/// Set 0: per frame.
pub const SET_FRAME: u32 = 0;
/// Set 0, binding 0: `Frame` uniform block (camera, light, view options).
pub const BINDING_FRAME: u32 = 0;
/// Set 0, binding 1: Perlin's permutation table (`uvec4[64]` uniform block), written once.
pub const BINDING_NOISE: u32 = 1;

/// Set 1: per mesh. No drawing stage reads a storage buffer of it (every binding is a texel
/// buffer or a uniform block): see [`BINDING_ELEMENT_TEXELS`], and a storage binding visible to
/// every stage would count against each stage's maxPerStageDescriptorStorageBuffers (at least 4).
pub const SET_MESH: u32 = 1;
/// Binding 0 of set [`SET_MESH`] in the GLSL twin of the bounds (glsl/lod/bounds.comp, run by
/// tests/lod_mirror.rs with its own layout): `ElementRecord[]`, a storage buffer.
pub const BINDING_ELEMENTS: u32 = 0;
/// Set 1, binding 13: the chunk's records as a uniform texel buffer of `RGBA32UI`, seven texels
/// an element (`fetch_record` in glsl/include/records.glsl): what the stages read per
/// invocation (the adaptive instanced pattern's vertices, the tessellator's evaluated vertices,
/// the fragment stage's per-fragment normal fields). lavapipe fetches texels with vector
/// gathers but loads a storage buffer one invocation and one component at a time, which would
/// make a `pn` frame's fragment stage several times slower (docs/bench/record-texels.md).
pub const BINDING_ELEMENT_TEXELS: u32 = 13;
/// Set 1, binding 1: a window of [`UBO_WINDOW`] `ElementRecord`s, dynamic uniform buffer (`ubo`
/// submission).
pub const BINDING_ELEMENT_UBO: u32 = 1;
/// Records per `ubo` window: 144 × 112 bytes fit the 16 KiB every device's maxUniformBufferRange
/// offers, and window offsets (multiples of 144 × 112) meet any minUniformBufferOffsetAlignment
/// up to the 256 bytes Vulkan allows.
pub const UBO_WINDOW: u32 = 144;

/// Set 1, binding 2: each element's texture coordinates, three `vec2` padded to 32 bytes
/// (`heightmap` displacement), chunked like the records, two `RGBA32F` texels an element
/// (`fetch_uvs`).
pub const BINDING_UVS: u32 = 2;
/// Set 1, binding 3: the height map's pyramid layout (`Heightmap::gpu_header`, 272 bytes), a
/// uniform block.
pub const BINDING_HEIGHTMAP: u32 = 3;
/// Set 1, binding 12: the height map's texels, every level (`Heightmap::gpu_texels`), an `R32`
/// uniform texel buffer: maxTexelBufferElements texels (at least 65,536; 134 M on common
/// devices), not the 128 MiB a storage-buffer range may span, so an 8192² map fits.
pub const BINDING_HEIGHTMAP_TEXELS: u32 = 12;
/// Set 1, binding 4: every vertex's scalar tags (`stpn`), three `RGBA32F` texels each, a uniform
/// texel buffer (read per vertex and per fragment: [`BINDING_ELEMENT_TEXELS`] says why).
pub const BINDING_TAGS: u32 = 4;

/// Set 1, binding 11: each element's levels for adaptive drawing (`vec4`: its stored edges'
/// continuous levels, then its inner level; inner level 0 means culled: draw nothing), chunked
/// like the records, one `RGBA32F` texel an element (`fetch_levels`). Written by the level pass
/// each frame as a storage buffer of its own set (or uploaded,
/// [`crate::lod::levels::ElementLevels`]); the drivers read it when they draw adaptively.
pub const BINDING_LEVELS: u32 = 11;

/// Set 1, bindings 5-10, texel buffers: the `loop` surface (src/render/loop_gpu.rs uploads them): M1's
/// positions and normals (`vec4`, written by the Loop passes), each M1 face's table entry
/// (`uvec4`: its table's rows, control points and column pairs, first control index,
/// orientation), the faces' control points (M1 vertex indices, four a texel), the basis
/// function tables' distinct rows (`float`, four a texel) and every table's row map (`uint`).
/// Unchunked: one face's owners may be in another chunk.
pub const BINDING_LOOP_P1: u32 = 5;
pub const BINDING_LOOP_N1: u32 = 6;
pub const BINDING_LOOP_FACES: u32 = 7;
pub const BINDING_LOOP_CONTROL: u32 = 8;
pub const BINDING_LOOP_TABLES: u32 = 9;
pub const BINDING_LOOP_ROWS: u32 = 10;

/// Set 2: capture output of the `CAPTURE` shader variants.
pub const SET_CAPTURE: u32 = 2;
/// Set 2, binding 0: evaluated vertices, `CapturedVertex[]`.
pub const BINDING_CAPTURE: u32 = 0;
/// Set 2, binding 1: append counter and capacity (`tess` capture), the pass's first element and
/// first packed slot.
pub const BINDING_CAPTURE_COUNT: u32 = 1;
/// Set 2, binding 2: each element's first slot in the adaptive pattern driver's packed capture.
pub const BINDING_CAPTURE_OFFSETS: u32 = 2;

/// The Loop step's compute pass (its own set 0): per-M1-vertex entry offsets, entries
/// (parent, weight), M0 positions in, M1 positions out.
pub const LOOP_BINDING_OFFSETS: u32 = 0;
pub const LOOP_BINDING_ENTRIES: u32 = 1;
pub const LOOP_BINDING_M0: u32 = 2;
pub const LOOP_BINDING_M1: u32 = 3;
/// The normals pass (same set): M1's one-rings and M1's normals out.
pub const LOOP_BINDING_RING_OFFSETS: u32 = 4;
pub const LOOP_BINDING_RINGS: u32 = 5;
pub const LOOP_BINDING_N1: u32 = 6;

/// The GLSL twin of the bounds (compute, set 2): per element, its bounds and its three edges'
/// bounds (glsl/lod/bounds.comp, src/lod).
pub const SET_LOD: u32 = 2;
pub const BINDING_LOD_BOUNDS: u32 = 0;

/// The per-frame level pass (glsl/lod/levels.comp, its own set 0): each element's bounds
/// (`LodRecord`s, src/lod/frame.rs, as a uniform texel buffer of `RGBA32F`) in, the mesh's
/// whole levels buffer out (storage buffer); for the lift (src/lod/frame/lift.rs), the same
/// records' neighbours (the same buffer as `RGBA32UI` texels), and what the first dispatch
/// leaves of each element (a storage buffer: the chunk's own range, and the whole of it).
pub const LEVEL_BINDING_RECORDS: u32 = 0;
pub const LEVEL_BINDING_LEVELS: u32 = 1;
pub const LEVEL_BINDING_NEIGHBOURS: u32 = 2;
pub const LEVEL_BINDING_BEFORE: u32 = 3;
pub const LEVEL_BINDING_BEFORE_ALL: u32 = 4;

/// Specialization constant ids.
pub const SPEC_SURFACE: u32 = 0;
pub const SPEC_SUBMIT: u32 = 1;
pub const SPEC_WIRE: u32 = 2;
pub const SPEC_DISPLACE: u32 = 3;
pub const SPEC_FRAGMENT_FIELD: u32 = 4;
/// `pn`'s and `stpn`'s normal field (`crate::surface::NormalField`).
pub const SPEC_NORMAL_FIELD: u32 = 5;
/// Geomorphing in the adaptive pattern driver (`DrawConfig::geomorph`).
pub const SPEC_GEOMORPH: u32 = 6;
/// What the fragment stage shows (`super::View`): each view compiles to its own work alone.
pub const SPEC_VIEW: u32 = 7;
/// The level pass's lift (`LevelPass`): its second dispatch's pipeline is the first's with this
/// set, so each does its own work alone.
pub const SPEC_LIFTING: u32 = 8;

/// Everything above, as GLSL macro definitions.
pub const GLSL_DEFINES: &[(&str, u32)] = &[
    ("SET_FRAME", SET_FRAME),
    ("BINDING_FRAME", BINDING_FRAME),
    ("BINDING_NOISE", BINDING_NOISE),
    ("SET_MESH", SET_MESH),
    ("BINDING_ELEMENTS", BINDING_ELEMENTS),
    ("BINDING_ELEMENT_TEXELS", BINDING_ELEMENT_TEXELS),
    ("BINDING_ELEMENT_UBO", BINDING_ELEMENT_UBO),
    ("UBO_WINDOW", UBO_WINDOW),
    ("BINDING_UVS", BINDING_UVS),
    ("BINDING_HEIGHTMAP", BINDING_HEIGHTMAP),
    ("BINDING_HEIGHTMAP_TEXELS", BINDING_HEIGHTMAP_TEXELS),
    ("BINDING_TAGS", BINDING_TAGS),
    ("BINDING_LEVELS", BINDING_LEVELS),
    ("SET_CAPTURE", SET_CAPTURE),
    ("BINDING_CAPTURE", BINDING_CAPTURE),
    ("BINDING_CAPTURE_COUNT", BINDING_CAPTURE_COUNT),
    ("BINDING_CAPTURE_OFFSETS", BINDING_CAPTURE_OFFSETS),
    ("LOOP_BINDING_OFFSETS", LOOP_BINDING_OFFSETS),
    ("LOOP_BINDING_ENTRIES", LOOP_BINDING_ENTRIES),
    ("LOOP_BINDING_M0", LOOP_BINDING_M0),
    ("LOOP_BINDING_M1", LOOP_BINDING_M1),
    ("LOOP_BINDING_RING_OFFSETS", LOOP_BINDING_RING_OFFSETS),
    ("LOOP_BINDING_RINGS", LOOP_BINDING_RINGS),
    ("LOOP_BINDING_N1", LOOP_BINDING_N1),
    ("BINDING_LOOP_P1", BINDING_LOOP_P1),
    ("BINDING_LOOP_N1", BINDING_LOOP_N1),
    ("BINDING_LOOP_FACES", BINDING_LOOP_FACES),
    ("BINDING_LOOP_CONTROL", BINDING_LOOP_CONTROL),
    ("BINDING_LOOP_TABLES", BINDING_LOOP_TABLES),
    ("BINDING_LOOP_ROWS", BINDING_LOOP_ROWS),
    ("SET_LOD", SET_LOD),
    ("BINDING_LOD_BOUNDS", BINDING_LOD_BOUNDS),
    ("LEVEL_BINDING_RECORDS", LEVEL_BINDING_RECORDS),
    ("LEVEL_BINDING_LEVELS", LEVEL_BINDING_LEVELS),
    ("LEVEL_BINDING_NEIGHBOURS", LEVEL_BINDING_NEIGHBOURS),
    ("LEVEL_BINDING_BEFORE", LEVEL_BINDING_BEFORE),
    ("LEVEL_BINDING_BEFORE_ALL", LEVEL_BINDING_BEFORE_ALL),
    ("SPEC_SURFACE", SPEC_SURFACE),
    ("SPEC_SUBMIT", SPEC_SUBMIT),
    ("SPEC_WIRE", SPEC_WIRE),
    ("SPEC_DISPLACE", SPEC_DISPLACE),
    ("SPEC_FRAGMENT_FIELD", SPEC_FRAGMENT_FIELD),
    ("SPEC_NORMAL_FIELD", SPEC_NORMAL_FIELD),
    ("SPEC_GEOMORPH", SPEC_GEOMORPH),
    ("SPEC_VIEW", SPEC_VIEW),
    ("SPEC_LIFTING", SPEC_LIFTING),
];

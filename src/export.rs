//! `meshrefine export`: the refined mesh as the GPU evaluated it. The vertices come from the
//! capture variant of the chosen driver's real drawing pipeline; here they are welded (equal
//! position bits become one vertex: shared coarse edges weld because refinement is watertight)
//! and connected with the pattern's triangles. Texture coordinates, where the mesh has them,
//! are computed on the CPU per captured vertex from its element and sample (`texcoords.rs`).
#![forbid(unsafe_code)]

mod texcoords;

pub use texcoords::element_texcoord;

use crate::pattern::Pattern;
use crate::render::{CaptureResult, CapturedVertex, XfbVertex};
use glam::{DVec3, Vec2, Vec3};
use std::collections::HashMap;
use std::fmt::Write as _;

/// A welded triangle mesh with separately indexed normals (OBJ's `v`/`vn`).
#[derive(Clone, Debug, Default)]
pub struct RefinedMesh {
    /// As drawn; written where [`RefinedMesh::placement`] puts them.
    pub positions: Vec<Vec3>,
    /// Where the positions drawn lie in the coordinates written (the identity by default).
    pub placement: Placement,
    pub normals: Vec<Vec3>,
    /// Per corner: (position index, normal index).
    pub triangles: Vec<[(u32, u32); 3]>,
    /// Texture coordinates (OBJ's `vt`), bit-equal ones merged; empty when the export has none.
    pub texcoords: Vec<Vec2>,
    /// Per corner of each triangle, its index into `texcoords` (empty when there are none).
    pub texcoord_triangles: Vec<[u32; 3]>,
}

impl RefinedMesh {
    /// Without the positions, normals and texture coordinates no triangle uses (those of
    /// triangles dropped as degenerate, where nothing else shares them), the rest in their
    /// order: an export writes no vertex no face uses. Unchanged where every one is used.
    fn without_unused(mut self) -> Self {
        fn keep<T: Copy>(items: &mut Vec<T>, used: impl Iterator<Item = u32>) -> Option<Vec<u32>> {
            let mut new = vec![u32::MAX; items.len()];
            for i in used {
                new[i as usize] = 0;
            }
            if new.iter().all(|&i| i == 0) {
                return None;
            }
            let mut kept = 0;
            for (i, slot) in new.iter_mut().enumerate() {
                if *slot == 0 {
                    items[kept as usize] = items[i];
                    *slot = kept;
                    kept += 1;
                }
            }
            items.truncate(kept as usize);
            Some(new)
        }
        let positions = self.triangles.iter().flatten().map(|c| c.0);
        if let Some(new) = keep(&mut self.positions, positions) {
            (self.triangles.iter_mut().flatten()).for_each(|c| c.0 = new[c.0 as usize]);
        }
        let normals = self.triangles.iter().flatten().map(|c| c.1);
        if let Some(new) = keep(&mut self.normals, normals) {
            (self.triangles.iter_mut().flatten()).for_each(|c| c.1 = new[c.1 as usize]);
        }
        if let Some(new) = keep(
            &mut self.texcoords,
            self.texcoord_triangles.iter().flatten().copied(),
        ) {
            (self.texcoord_triangles.iter_mut().flatten()).for_each(|i| *i = new[*i as usize]);
        }
        self
    }
}

/// The map from drawn positions to written ones, `drawn / scale + centre` in `f64`: the inverse
/// of `Mesh::viewing_transform`, so an export is written in the mesh's own coordinates while
/// the GPU draws it centred at unit size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub centre: DVec3,
    pub scale: f64,
}

impl Default for Placement {
    fn default() -> Self {
        Self {
            centre: DVec3::ZERO,
            scale: 1.0,
        }
    }
}

impl Placement {
    /// Whether the written coordinates need more than `f32`: the mesh's centre lies more than
    /// 256 bounding radii from the origin, where `f32`'s step at the centre, `2^-24` of its
    /// distance, exceeds `2^-16` radii, no longer far below the shortest refined edges (an
    /// element of a dense mesh at level 1024). Then each coordinate is written as the
    /// shortest decimal of its `f64` value, else of its `f32` rounding (shorter lines, the
    /// digits single-precision readers take).
    pub fn needs_f64(&self) -> bool {
        self.centre.abs().max_element() * self.scale > 256.0
    }

    /// Writes `p` placed, `v X Y Z`, in `f64` where `wide` ([`Placement::needs_f64`]).
    fn write_v(&self, line: &mut String, p: Vec3, wide: bool) {
        let q = p.as_dvec3() / self.scale + self.centre;
        let _ = if wide {
            writeln!(line, "v {} {} {}", q.x, q.y, q.z)
        } else {
            let q = q.as_vec3();
            writeln!(line, "v {} {} {}", q.x, q.y, q.z)
        };
    }
}

/// The texture coordinates of a captured vertex (from its element and sample), for
/// [`weld_with`] and [`weld_adaptive_with`].
pub type TexcoordOf<'a> = &'a dyn Fn(&CapturedVertex) -> Vec2;

/// Weld captured vertices, triangles whose corners weld together (degenerate) dropped. Fails if
/// the capture misses a vertex (its `w` was never set to 1).
pub fn weld(capture: &CaptureResult, pattern: &Pattern) -> Result<RefinedMesh, String> {
    weld_with(capture, pattern, None)
}

/// [`weld`], with each vertex's texture coordinates from `uv` where given. Positions weld on
/// their bits alone, as without: a position with two texture coordinates (a seam of the
/// mesh's texture coordinates) stays one `v` with two `vt`.
pub fn weld_with(
    capture: &CaptureResult,
    pattern: &Pattern,
    uv: Option<TexcoordOf<'_>>,
) -> Result<RefinedMesh, String> {
    let pv = capture.pattern_vertex_count as usize;
    if pattern.bary.len() != pv {
        return Err(format!(
            "capture holds {pv} vertices per triangle, the pattern {}",
            pattern.bary.len()
        ));
    }
    let mut w = Welder::default();
    let mut remap = Vec::with_capacity(capture.vertices.len());
    let mut uv_remap = Vec::new();
    for (k, v) in capture.vertices.iter().enumerate() {
        if v.position[3] != 1.0 {
            return Err(format!(
                "the GPU did not write vertex {} of coarse triangle {}",
                k % pv,
                k / pv
            ));
        }
        remap.push(w.add(
            Vec3::from_slice(&v.position[..3]),
            Vec3::from_slice(&v.normal[..3]),
        ));
        if let Some(uv) = uv {
            uv_remap.push(w.add_texcoord(uv(v)));
        }
    }
    let mut out = w.out;
    let local = pattern.triangles();
    for t in 0..capture.vertices.len() / pv {
        for tri in &local {
            let c = tri.map(|i| remap[t * pv + i as usize]);
            // Distinct lattice points whose positions round to the same `f32` (detail far
            // below the drawing frame's precision) make a triangle of no area: dropped, as
            // the adaptive and tessellated captures drop theirs.
            if c[0].0 == c[1].0 || c[1].0 == c[2].0 || c[2].0 == c[0].0 {
                continue;
            }
            out.triangles.push(c);
            if uv.is_some() {
                out.texcoord_triangles
                    .push(tri.map(|i| uv_remap[t * pv + i as usize]));
            }
        }
    }
    Ok(out.without_unused())
}

/// Weld the vertices the pattern driver captured drawing adaptively at largest level
/// `max_level` (packed: each element's vertices at its drawn inner level only, in that level's
/// pattern order, each written vertex's `id.z` that level; a culled element has none;
/// [`CaptureResult::adaptive_elements`]): each element's inner-level triangles, those whose
/// corners snapping welded together (degenerate) dropped.
pub fn weld_adaptive(capture: &CaptureResult, max_level: u32) -> Result<RefinedMesh, String> {
    weld_adaptive_with(capture, max_level, None)
}

/// [`weld_adaptive`], with each vertex's texture coordinates from `uv` where given (as
/// [`weld_with`]).
pub fn weld_adaptive_with(
    capture: &CaptureResult,
    max_level: u32,
    uv: Option<TexcoordOf<'_>>,
) -> Result<RefinedMesh, String> {
    let Some(levels) = &capture.inner_levels else {
        return Err("the capture was not drawn adaptively".to_string());
    };
    if !max_level.is_power_of_two() {
        return Err(format!(
            "adaptive captures have a power of two as largest level, not {max_level}"
        ));
    }
    let packed: u64 = (levels.iter())
        .map(|&l| {
            if l == 0 {
                0
            } else {
                crate::pattern::vertex_count(l) as u64
            }
        })
        .sum();
    if packed != capture.vertices.len() as u64 {
        return Err(format!(
            "capture holds {} vertices, the levels of its elements {packed}",
            capture.vertices.len()
        ));
    }
    let mut w = Welder::default();
    let mut triangles = Vec::new();
    let mut texcoord_triangles = Vec::new();
    // Each level's triangles (the uniform pattern's: in the hierarchy's order).
    let mut patterns: HashMap<u32, Vec<u32>> = HashMap::new();
    let mut index = Vec::new();
    for (t, (inner, vertices)) in capture.adaptive_elements().enumerate() {
        if inner == 0 {
            continue; // culled
        }
        if inner > max_level {
            return Err(format!("element {t} was drawn at level {inner}"));
        }
        index.clear();
        for (i, v) in vertices.iter().enumerate() {
            if v.position[3] != 1.0 {
                return Err(format!("the GPU did not write vertex {i} of element {t}"));
            }
            if v.id[2] != inner {
                return Err(format!(
                    "element {t} was drawn at level {}, captured at level {inner}",
                    v.id[2]
                ));
            }
            let (p, n) = w.add(
                Vec3::from_slice(&v.position[..3]),
                Vec3::from_slice(&v.normal[..3]),
            );
            index.push((p, n, uv.map_or(0, |uv| w.add_texcoord(uv(v)))));
        }
        let local = patterns
            .entry(inner)
            .or_insert_with(|| Pattern::uniform(inner).indices);
        for tri in local.chunks_exact(3) {
            let c = [0, 1, 2].map(|k| index[tri[k] as usize]);
            if c[0].0 != c[1].0 && c[1].0 != c[2].0 && c[2].0 != c[0].0 {
                triangles.push(c.map(|(p, n, _)| (p, n)));
                if uv.is_some() {
                    texcoord_triangles.push(c.map(|(_, _, t)| t));
                }
            }
        }
    }
    let mut out = w.out;
    out.triangles = triangles;
    out.texcoord_triangles = texcoord_triangles;
    Ok(out.without_unused())
}

/// Weld the triangles transform feedback captured from the `tess` driver (corners in the order
/// the tessellator emitted them), those whose corners weld together (degenerate) dropped.
pub fn weld_triangles(triangles: &[[XfbVertex; 3]]) -> RefinedMesh {
    let mut w = TriangleWelder::default();
    w.add(triangles);
    w.finish()
}

/// The texture coordinates of a vertex transform feedback captured (from its element and
/// sample), for [`TriangleWelder::with_texcoords`].
pub type XfbTexcoordOf<'a> = &'a dyn Fn(&XfbVertex) -> Vec2;

/// [`weld_triangles`] a piece at a time (a capture pass after another): the same mesh as
/// welding every piece at once, in the same order, without holding the captured triangles.
#[derive(Default)]
pub struct TriangleWelder<'a> {
    w: Welder,
    uv: Option<XfbTexcoordOf<'a>>,
}

impl<'a> TriangleWelder<'a> {
    /// A welder that also gives each corner its texture coordinates from `uv`, merged on their
    /// bits as [`weld_with`] merges them: positions still weld on their bits alone, so a
    /// position with two texture coordinates (a seam) stays one `v` with two `vt`.
    pub fn with_texcoords(uv: XfbTexcoordOf<'a>) -> Self {
        Self {
            w: Welder::default(),
            uv: Some(uv),
        }
    }

    /// Weld the next `triangles`.
    pub fn add(&mut self, triangles: &[[XfbVertex; 3]]) {
        let w = &mut self.w;
        w.out.triangles.reserve(triangles.len());
        for t in triangles {
            let tri = t.map(|v| w.add(Vec3::from(v.position), Vec3::from(v.normal)));
            if tri[0].0 == tri[1].0 || tri[1].0 == tri[2].0 || tri[2].0 == tri[0].0 {
                // Corners welded together (the geomorphing tess driver's outer ring snapped
                // onto a coarser edge's sample): no area, dropped as the pattern's are.
                continue;
            }
            w.out.triangles.push(tri);
            if let Some(uv) = self.uv {
                let tri = t.map(|v| w.add_texcoord(uv(&v)));
                w.out.texcoord_triangles.push(tri);
            }
        }
    }

    /// Triangles welded so far.
    pub fn triangles(&self) -> usize {
        self.w.out.triangles.len()
    }

    pub fn finish(self) -> RefinedMesh {
        self.w.out.without_unused()
    }
}

#[derive(Default)]
struct Welder {
    out: RefinedMesh,
    pos_index: HashMap<[u32; 3], u32, BitsHash>,
    nrm_index: HashMap<[u32; 3], u32, BitsHash>,
    uv_index: HashMap<[u32; 2], u32, BitsHash>,
}

/// The welder's hash of a vector's bits: a multiply-rotate per 32-bit word and a 64-bit
/// finalizer (MurmurHash3's `fmix64`) so every bit reaches the bucket index. Several times
/// cheaper than the default SipHash, which resists chosen keys the welder does not face; the
/// indices the welder hands out follow insertion order, so the hash never changes the output.
type BitsHash = std::hash::BuildHasherDefault<BitsHasher>;

#[derive(Default)]
struct BitsHasher(u64);

impl std::hash::Hasher for BitsHasher {
    fn write(&mut self, bytes: &[u8]) {
        for word in bytes.chunks(4) {
            let mut w = [0u8; 4];
            w[..word.len()].copy_from_slice(word);
            self.write_u32(u32::from_le_bytes(w));
        }
    }

    fn write_u32(&mut self, i: u32) {
        self.0 = (self.0.rotate_left(5) ^ i as u64).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn finish(&self) -> u64 {
        let mut h = self.0;
        h ^= h >> 33;
        h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^= h >> 33;
        h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        h ^ (h >> 33)
    }
}

impl Welder {
    /// Index pair of `(p, n)`, merging bit-equal positions and bit-equal normals (+0 == -0).
    fn add(&mut self, p: Vec3, n: Vec3) -> (u32, u32) {
        let bits = |v: Vec3| v.to_array().map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        let out = &mut self.out;
        let pi = *self.pos_index.entry(bits(p)).or_insert_with(|| {
            out.positions.push(p);
            out.positions.len() as u32 - 1
        });
        let ni = *self.nrm_index.entry(bits(n)).or_insert_with(|| {
            out.normals.push(n);
            out.normals.len() as u32 - 1
        });
        (pi, ni)
    }

    /// Index of texture coordinates `t`, merging bit-equal ones (+0 == -0).
    fn add_texcoord(&mut self, t: Vec2) -> u32 {
        let bits = t.to_array().map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        let out = &mut self.out;
        *self.uv_index.entry(bits).or_insert_with(|| {
            out.texcoords.push(t);
            out.texcoords.len() as u32 - 1
        })
    }
}

/// Wavefront OBJ text (`v`, `vn`, `f v//vn`; with texture coordinates `vt` and `f v/vt/vn`),
/// with `header` lines as comments.
pub fn to_obj(mesh: &RefinedMesh, header: &[String]) -> String {
    let mut s = Vec::with_capacity(mesh.positions.len() * 40 + mesh.triangles.len() * 30);
    write_obj(mesh, header, &mut s, |_| {}).expect("writing to memory does not fail");
    String::from_utf8(s).expect("OBJ text is UTF-8")
}

/// Lines [`write_obj`] writes between two reports of its progress.
pub const WRITE_PROGRESS_LINES: usize = 1 << 18;

/// [`to_obj`]'s text written to `out` as it is made (nothing is held but what `out` buffers);
/// `progress` hears the lines written so far, of `v`, `vt`, `vn` and `f` lines in all, every
/// [`WRITE_PROGRESS_LINES`] lines and at the end.
pub fn write_obj(
    mesh: &RefinedMesh,
    header: &[String],
    out: &mut impl std::io::Write,
    mut progress: impl FnMut((usize, usize)),
) -> std::io::Result<()> {
    let total =
        mesh.positions.len() + mesh.texcoords.len() + mesh.normals.len() + mesh.triangles.len();
    let mut done = 0;
    let mut line = String::with_capacity(80);
    let mut emit = |out: &mut dyn std::io::Write, line: &mut String| {
        out.write_all(line.as_bytes())?;
        line.clear();
        done += 1;
        if done % WRITE_PROGRESS_LINES == 0 {
            progress((done, total));
        }
        std::io::Result::Ok(())
    };
    for h in header {
        writeln!(out, "# {h}")?;
    }
    let wide = mesh.placement.needs_f64();
    for &p in &mesh.positions {
        mesh.placement.write_v(&mut line, p, wide);
        emit(out, &mut line)?;
    }
    for t in &mesh.texcoords {
        let _ = writeln!(line, "vt {} {}", t.x, t.y);
        emit(out, &mut line)?;
    }
    for n in &mesh.normals {
        let _ = writeln!(line, "vn {} {} {}", n.x, n.y, n.z);
        emit(out, &mut line)?;
    }
    if mesh.texcoord_triangles.len() == mesh.triangles.len() && !mesh.texcoords.is_empty() {
        for (t, uv) in mesh.triangles.iter().zip(&mesh.texcoord_triangles) {
            let _ = writeln!(
                line,
                "f {}/{}/{} {}/{}/{} {}/{}/{}",
                t[0].0 + 1,
                uv[0] + 1,
                t[0].1 + 1,
                t[1].0 + 1,
                uv[1] + 1,
                t[1].1 + 1,
                t[2].0 + 1,
                uv[2] + 1,
                t[2].1 + 1
            );
            emit(out, &mut line)?;
        }
        progress((total, total));
        return Ok(());
    }
    for t in &mesh.triangles {
        let _ = writeln!(
            line,
            "f {}//{} {}//{} {}//{}",
            t[0].0 + 1,
            t[0].1 + 1,
            t[1].0 + 1,
            t[1].1 + 1,
            t[2].0 + 1,
            t[2].1 + 1
        );
        emit(out, &mut line)?;
    }
    progress((total, total));
    Ok(())
}

/// Most refined triangles one export writes. The export holds the welded mesh and the captured
/// vertices (`tess`: one capture pass; the OBJ text is written as it is made): at most about
/// [`MEMORY_PER_TRIANGLE`] bytes per refined triangle at its peak (measured, docs/bench/export.md:
/// 0.84 GB for 6.0 million with `pattern`, 0.88 GB for 9.0 million with `tess`), and the file
/// takes about [`FILE_PER_TRIANGLE`] bytes per triangle; at this limit that is at most about
/// 2.7 GB of memory and a 1.5 GB file.
pub const MAX_EXPORT_TRIANGLES: u64 = 1 << 24;

/// Peak memory of an export per refined triangle, in bytes (an upper estimate, rounded up).
pub const MEMORY_PER_TRIANGLE: u64 = 160;

/// OBJ text per refined triangle, in bytes (an estimate: a `v`, a `vn` and an `f` line per two
/// triangles' worth of vertices and faces).
pub const FILE_PER_TRIANGLE: u64 = 90;

/// Refuses, before anything is evaluated, an export of `elements` elements (coarse triangles,
/// or M1's faces for the loop surface) at `level` whose refined size passes
/// [`MAX_EXPORT_TRIANGLES`], each element making `per_element(level)` triangles (the driver's:
/// `N²` from a pattern, about `1.5 N²` from the tessellator): one clause naming the count, the
/// estimated memory and file, and the highest level that fits. Returns the refined triangle
/// count.
pub fn check_size(
    elements: u64,
    level: u32,
    per_element: impl Fn(u32) -> u32,
) -> Result<u64, String> {
    let made = |l: u32| elements.saturating_mul(per_element(l) as u64);
    let per = per_element(level) as u64;
    let triangles = made(level);
    if triangles <= MAX_EXPORT_TRIANGLES {
        return Ok(triangles);
    }
    let gb = |bytes: u64| bytes as f64 / 1e9;
    let remedy = match (1..level).rev().find(|&l| made(l) <= MAX_EXPORT_TRIANGLES) {
        Some(fits) => format!("use --level {fits} or lower for this mesh"),
        None => "this mesh has too many elements to export at any level".to_string(),
    };
    Err(format!(
        "--level {level} would export {triangles} refined triangles ({elements} elements x {per}), about {:.1} GB of memory and a {:.1} GB file; at most {MAX_EXPORT_TRIANGLES} (2^24) are exported: {remedy}",
        gb(triangles.saturating_mul(MEMORY_PER_TRIANGLE)),
        gb(triangles.saturating_mul(FILE_PER_TRIANGLE)),
    ))
}

/// Refuses an adaptive export (`--pixel-error`) whose chosen levels make more than
/// [`MAX_EXPORT_TRIANGLES`], after the levels are chosen and before anything is captured:
/// `histogram` holds the visible elements per drawn level (`LevelReport::histogram`), each
/// counted at `per_element(N)` triangles, the driver's at a uniform level (an upper bound:
/// transition triangles along coarser edges make a few less). One clause naming the count, the estimated memory and file, and the remedy: a
/// larger `--pixel-error` (named `pixel_error`, as given; not where the `fixed` elements, drawn
/// at `max_level` whatever the pixel error, with no finite bound or holding the eye, make more
/// than fit by themselves), or the largest `--max-level` below `max_level` that fits (a power
/// of two where `power_of_two`, the pattern driver's). Returns the refined triangle count.
pub fn check_adaptive_size(
    histogram: &std::collections::BTreeMap<u32, u64>,
    pixel_error: &str,
    (max_level, fixed): (u32, u64),
    power_of_two: bool,
    per_element: impl Fn(u32) -> u32,
) -> Result<u64, String> {
    // The triangles the same levels make capped at `m` (a smaller --max-level caps them so).
    let capped = |m: u32| -> u64 {
        (histogram.iter())
            .map(|(&l, &n)| n.saturating_mul(per_element(l.min(m)) as u64))
            .fold(0, u64::saturating_add)
    };
    let triangles = capped(u32::MAX);
    if triangles <= MAX_EXPORT_TRIANGLES {
        return Ok(triangles);
    }
    let gb = |bytes: u64| bytes as f64 / 1e9;
    let elements: u64 = histogram.values().sum();
    let lower = (1..max_level)
        .rev()
        .filter(|m| !power_of_two || m.is_power_of_two())
        .find(|&m| capped(m) <= MAX_EXPORT_TRIANGLES);
    // The least a larger pixel error can make: the fixed elements at the largest level, the
    // others at level 1.
    let floor = fixed
        .saturating_mul(per_element(max_level) as u64)
        .saturating_add((elements.saturating_sub(fixed)).saturating_mul(per_element(1) as u64));
    let larger = if floor > MAX_EXPORT_TRIANGLES {
        // Too many whatever the pixel error: only --max-level helps.
        ""
    } else {
        "a larger --pixel-error, or "
    };
    let remedy = match lower {
        Some(m) if power_of_two => {
            format!("use {larger}--max-level {m} or a smaller power of two")
        }
        Some(m) => format!("use {larger}--max-level {m} or lower"),
        None => format!(
            "its {elements} elements drawn are too many to export even at level 1 (a camera that sees fewer of them exports fewer)"
        ),
    };
    Err(format!(
        "--pixel-error {} chooses levels that would export {triangles} refined triangles ({elements} elements drawn, up to level {}), about {:.1} GB of memory and a {:.1} GB file; at most {MAX_EXPORT_TRIANGLES} (2^24) are exported: {remedy}",
        pixel_error,
        histogram.keys().max().copied().unwrap_or(0),
        gb(triangles.saturating_mul(MEMORY_PER_TRIANGLE)),
        gb(triangles.saturating_mul(FILE_PER_TRIANGLE)),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bytemuck::Zeroable;

    /// Transform feedback's triangles with texture coordinates: positions weld on their bits
    /// alone, texture coordinates on theirs, so a corner shared by two triangles whose
    /// coordinates differ (a seam) is one `v` with two `vt`.
    #[test]
    fn triangle_texcoords_merge_on_their_bits_and_keep_seams() {
        let v = |x: f32, element: u32| XfbVertex {
            position: [x, 0.0, 0.0],
            element,
            normal: [0.0, 0.0, 1.0],
            bary: [x, 0.0, 0.0],
        };
        // Element 1's coordinates are shifted by one: the corner at x = 1 is on a seam.
        let uv = |v: &XfbVertex| Vec2::new(v.bary[0] + v.element as f32, 0.0);
        let mut w = TriangleWelder::with_texcoords(&uv);
        w.add(&[[v(0.0, 0), v(1.0, 0), v(0.5, 0)]]);
        w.add(&[[v(1.0, 1), v(2.0, 0), v(0.5, 0)]]);
        let mesh = w.finish();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles[1][0].0, mesh.triangles[0][1].0);
        let texcoords: Vec<f32> = mesh.texcoords.iter().map(|t| t.x).collect();
        assert_eq!(texcoords, [0.0, 1.0, 0.5, 2.0]);
        assert_eq!(mesh.texcoord_triangles, [[0, 1, 2], [3, 3, 2]]);
    }

    /// Welding in pieces gives the mesh welding at once does, and the streamed writer the text
    /// `to_obj` makes, its progress ending at every line written.
    #[test]
    fn welding_in_pieces_and_streaming_change_nothing() {
        let v = |x: f32, y: f32, n: f32| XfbVertex {
            position: [x, y, 0.0],
            normal: [0.0, n, 1.0],
            ..XfbVertex::zeroed()
        };
        // A strip of triangles sharing corners, with -0.0 and 0.0 (welded as one).
        let tris: Vec<[XfbVertex; 3]> = (0..50)
            .map(|i| {
                let x = i as f32 * 0.25;
                [v(x, 0.0, -0.0), v(x + 0.25, 0.0, 0.0), v(x, 1.0, 0.5)]
            })
            .collect();
        let whole = weld_triangles(&tris);
        assert_eq!(whole.positions.len(), 51 + 50);
        assert_eq!(whole.normals.len(), 2);
        let mut pieces = TriangleWelder::default();
        for chunk in tris.chunks(7) {
            pieces.add(chunk);
        }
        assert_eq!(pieces.triangles(), 50);
        let pieces = pieces.finish();
        assert_eq!(pieces.triangles, whole.triangles);
        assert_eq!(pieces.positions, whole.positions);
        assert_eq!(pieces.normals, whole.normals);
        let header = ["a mesh".to_string()];
        let mut out = Vec::new();
        let mut heard = Vec::new();
        write_obj(&whole, &header, &mut out, |p| heard.push(p)).unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), to_obj(&whole, &header));
        assert_eq!(heard, [(153, 153)]);
    }

    /// A triangle whose corners weld together is dropped with the vertices only it used (a
    /// tiny triangle far from the rest: its positions round together), and its normal; the
    /// rest keep their order.
    #[test]
    fn dropped_triangles_leave_no_unused_vertex() {
        let v = |x: f32, y: f32, n: f32| XfbVertex {
            position: [x, y, 0.0],
            normal: [0.0, n, 1.0],
            ..XfbVertex::zeroed()
        };
        let tris = [
            [v(5.0, 5.0, 0.25), v(5.0, 5.0, 0.25), v(6.0, 5.0, 0.25)],
            [v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.5)],
        ];
        let mesh = weld_triangles(&tris);
        assert_eq!(mesh.positions, [Vec3::ZERO, Vec3::X, Vec3::Y]);
        assert_eq!(mesh.normals.len(), 2);
        assert_eq!(mesh.triangles, [[(0, 0), (1, 0), (2, 1)]]);
        let text = to_obj(&mesh, &[]);
        assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 3);
    }

    /// A packed adaptive capture by hand: two triangles sharing an edge in the plane, element
    /// 0 at level 2 with that edge at level 1 (its middle vertex snapped onto a corner),
    /// element 1 at level 1, and a culled element between them. Welded: element 0's 4
    /// triangles less the one snapping made degenerate, element 1's one, closed along the
    /// shared edge; texture coordinates follow each vertex.
    fn hand_capture() -> CaptureResult {
        let v = |e: u32, p: [f32; 2], level: u32| CapturedVertex {
            position: [p[0], p[1], 0.0, 1.0],
            normal: [0.0, 0.0, 1.0, 0.0],
            coord: [p[0], p[1], 0.0, 0.0],
            id: [e, 0, level, 1],
        };
        // Element 0: corners (0,0) (1,0) (0,1), lattice of level 2 in its order; the shared
        // edge is edge 1 (from (1,0) to (0,1)), whose middle (0.5,0.5) snapped onto (1,0).
        let e0 = [
            [0.0, 0.0],
            [0.5, 0.0],
            [1.0, 0.0],
            [0.0, 0.5],
            [1.0, 0.0],
            [0.0, 1.0],
        ];
        // Element 2: (1,0) (1,1) (0,1) at level 1.
        let e2 = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut vertices: Vec<CapturedVertex> = e0.iter().map(|&p| v(0, p, 2)).collect();
        vertices.extend(e2.iter().map(|&p| v(2, p, 1)));
        CaptureResult {
            vertices,
            pattern_vertex_count: crate::pattern::vertex_count(4),
            inner_levels: Some(vec![2, 0, 1]),
            stats: None,
        }
    }

    #[test]
    fn packed_adaptive_captures_weld_each_element_at_its_level() {
        let cap = hand_capture();
        let levels: Vec<(u32, usize)> =
            cap.adaptive_elements().map(|(l, v)| (l, v.len())).collect();
        assert_eq!(levels, [(2, 6), (0, 0), (1, 3)]);
        let uv = |v: &CapturedVertex| Vec2::new(v.coord[0], v.coord[1]);
        let mesh = weld_adaptive_with(&cap, 4, Some(&uv)).unwrap();
        // (0,0) (.5,0) (1,0) (0,.5) (0,1) (1,1): the snapped vertex welds onto (1,0).
        assert_eq!(mesh.positions.len(), 6);
        assert_eq!(mesh.normals.len(), 1);
        let tris: Vec<[u32; 3]> = mesh.triangles.iter().map(|t| t.map(|c| c.0)).collect();
        // Level 2's triangles (0 1 3) (1 2 4) (1 4 3) (3 4 5), the second degenerate; then
        // element 2's.
        assert_eq!(tris, [[0, 1, 3], [1, 2, 3], [3, 2, 4], [2, 5, 4]]);
        assert_eq!(mesh.texcoord_triangles, tris);
        assert_eq!(mesh.texcoords.len(), 6);
        let mut edges = HashMap::new();
        for t in &tris {
            for k in 0..3 {
                let (a, b) = (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]));
                *edges.entry((a, b)).or_insert(0) += 1;
            }
        }
        // The shared edge (1,0)-(0,1) has both sides; the rest is the square's outline.
        assert_eq!(edges[&(2, 4)], 2);
        assert_eq!(edges.values().filter(|&&n| n == 1).count(), 6);
    }

    /// What a packed capture that does not match its levels says.
    #[test]
    fn packed_adaptive_captures_are_checked() {
        let mut cap = hand_capture();
        assert!(weld_adaptive(&cap, 1)
            .unwrap_err()
            .contains("element 0 was drawn at level 2"));
        assert!(weld_adaptive(&cap, 3).unwrap_err().contains("power of two"));
        cap.vertices[7].position[3] = 0.0;
        let e = weld_adaptive(&cap, 4).unwrap_err();
        assert_eq!(e, "the GPU did not write vertex 1 of element 2");
        cap.vertices[7].position[3] = 1.0;
        cap.vertices[1].id[2] = 4;
        let e = weld_adaptive(&cap, 4).unwrap_err();
        assert_eq!(e, "element 0 was drawn at level 4, captured at level 2");
        cap.vertices.pop();
        let e = weld_adaptive(&cap, 4).unwrap_err();
        assert_eq!(e, "capture holds 8 vertices, the levels of its elements 9");
        cap.inner_levels = None;
        assert!(weld_adaptive(&cap, 4)
            .unwrap_err()
            .contains("not drawn adaptively"));
    }

    #[test]
    fn obj_text_has_vt_only_with_texture_coordinates() {
        let mut mesh = RefinedMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            normals: vec![Vec3::Z],
            triangles: vec![[(0, 0), (1, 0), (2, 0)]],
            ..RefinedMesh::default()
        };
        let head = ["a".to_string()];
        let plain = "# a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";
        assert_eq!(to_obj(&mesh, &head), plain);
        mesh.texcoords = vec![Vec2::ZERO, Vec2::new(0.5, 1.0)];
        mesh.texcoord_triangles = vec![[0, 1, 1]];
        assert_eq!(
            to_obj(&mesh, &head),
            "# a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 0.5 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/2/1\n"
        );
    }

    /// Triangles a pattern makes per element.
    fn n2(level: u32) -> u32 {
        crate::pattern::triangle_count(level)
    }

    #[test]
    fn exports_are_refused_past_the_limit_with_the_level_that_fits() {
        let check_size = |e, l| super::check_size(e, l, n2);
        // 16 elements at level 1024 are exactly 2^24 triangles; one more element is too many.
        assert_eq!(check_size(16, 1024), Ok(1 << 24));
        let e = check_size(17, 1024).unwrap_err();
        assert!(
            e.starts_with("--level 1024 would export 17825792 refined triangles (17 elements x 1048576), about 2.9 GB of memory and a 1.6 GB file"),
            "{e}"
        );
        assert!(e.ends_with("use --level 993 or lower for this mesh"), "{e}");
        // The suggested level fits.
        assert!(check_size(17, 993).is_ok());
        assert!(check_size(17, 994).is_err());
        let e = check_size(u64::MAX / 2, 1).unwrap_err();
        assert!(
            e.ends_with("too many elements to export at any level"),
            "{e}"
        );
    }

    /// The tessellator makes about 1.5 N² triangles an element: its exports are counted so
    /// (Spot's 5,856 triangles at level 53 make 24.7 M, past the limit), and the level advised
    /// fits; a coarser edge only takes triangles away, so the uniform count bounds adaptive ones.
    #[test]
    fn tess_exports_count_the_tessellators_triangles() {
        use crate::render::tess::{tess_triangle_count, tess_triangle_count_levels};
        let e = check_size(5856, 53, tess_triangle_count).unwrap_err();
        assert!(
            e.starts_with(
                "--level 53 would export 24671328 refined triangles (5856 elements x 4213)"
            ),
            "{e}"
        );
        assert!(e.ends_with("use --level 43 or lower for this mesh"), "{e}");
        assert!(check_size(5856, 43, tess_triangle_count).is_ok());
        assert!(check_size(5856, 44, tess_triangle_count).is_err());
        let over = std::collections::BTreeMap::from([(64, 4096)]);
        let e = check_adaptive_size(&over, "1", (64, 0), true, tess_triangle_count).unwrap_err();
        assert!(
            e.ends_with("--max-level 32 or a smaller power of two"),
            "{e}"
        );
        for inner in 1..=64 {
            for outer in 1..=inner {
                let levels = tess_triangle_count_levels([outer, inner, 1], inner);
                assert!(levels <= tess_triangle_count(inner), "{outer} {inner}");
            }
        }
    }

    /// Adaptive exports count the levels drawn, and advise the adaptive options: the largest
    /// `--max-level` whose capped levels fit (a power of two for the pattern driver).
    #[test]
    fn adaptive_exports_are_refused_on_the_levels_drawn() {
        use std::collections::BTreeMap;
        let check_adaptive_size =
            |h, px, max, pow2| super::check_adaptive_size(h, px, (max, 0), pow2, n2);
        // 4096 elements at level 64 are exactly 2^24 triangles; more at level 1 are too many.
        let fits = BTreeMap::from([(64, 4096)]);
        assert_eq!(check_adaptive_size(&fits, "1", 64, true), Ok(1 << 24));
        let over = BTreeMap::from([(1, 1000), (64, 4096)]);
        let e = check_adaptive_size(&over, "0.5", 64, true).unwrap_err();
        assert!(e.starts_with("--pixel-error 0.5 chooses levels that would export 16778216 refined triangles (5096 elements drawn, up to level 64)"), "{e}");
        assert!(
            e.ends_with("use a larger --pixel-error, or --max-level 32 or a smaller power of two"),
            "{e}"
        );
        assert!(!e.contains("--level"), "{e}");
        // Integer levels: the largest that fits, 63 (4096 x 63² + 1000 < 2^24).
        let e = check_adaptive_size(&over, "0.5", 64, false).unwrap_err();
        assert!(e.ends_with("--max-level 63 or lower"), "{e}");
        let crowd = BTreeMap::from([(1, (1 << 24) + 1), (2, 1)]);
        let e = check_adaptive_size(&crowd, "0.5", 64, true).unwrap_err();
        assert!(e.contains("too many to export even at level 1"), "{e}");
        // Elements drawn at the largest level whatever the pixel error (no finite bound), too
        // many by themselves: only --max-level is advised.
        let unbounded = BTreeMap::from([(64, 5000)]);
        let e = super::check_adaptive_size(&unbounded, "1", (64, 5000), true, n2).unwrap_err();
        assert!(
            e.ends_with("use --max-level 32 or a smaller power of two"),
            "{e}"
        );
        let e = super::check_adaptive_size(&unbounded, "1", (64, 100), true, n2).unwrap_err();
        assert!(
            e.contains("use a larger --pixel-error, or --max-level 32"),
            "{e}"
        );
    }
}

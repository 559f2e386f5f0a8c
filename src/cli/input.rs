//! What every command loads before it draws: the mesh (with its load report, the warnings
//! about what loading dropped, and why Loop would refuse it), the height map and the stpn tags
//! the options name, and the draw configuration scaled to the mesh.
//!
//! Errors are one sentence naming the file (`'x.obj': ...`); warnings go to standard error and
//! the command goes on.
#![forbid(unsafe_code)]

use super::args::{SurfaceOpts, Technique};
use super::loop_check::loop_refusal;
use crate::note;
use anyhow::{bail, Result};
use meshrefine::mesh::{LoadReport, Mesh, MeshError};
use meshrefine::render::{DrawConfig, Driver, Headless};
use std::path::Path;

/// A loaded mesh and what messages call it.
pub struct Input {
    pub mesh: Mesh,
    /// The path as given, or "the default mesh (spot)".
    pub shown: String,
    /// `--heightmap`, loaded (None: the scene's generated map).
    pub heightmap: Option<meshrefine::surface::Heightmap>,
    /// `--tags`, parsed and checked (None: the scene's tags derived from hard edges).
    pub tags: Option<Vec<meshrefine::surface::stpn::VertexTag>>,
    /// Why `--surface loop` must refuse the mesh though it loaded ([`loop_refusal`]).
    pub loop_refusal: Option<String>,
    /// What loading did (the faces' lines and the file's vertex numbers, for messages).
    pub report: LoadReport,
}

/// Loads `path` (the default mesh when `None`); `for_loop` when the loop surface will subdivide
/// it, which refuses degenerate faces instead of dropping them.
pub fn load_mesh(path: Option<&Path>, for_loop: bool) -> Result<Input> {
    let Some(p) = path else {
        return Ok(Input {
            mesh: meshrefine::mesh::default_mesh(),
            shown: "the default mesh (spot)".into(),
            heightmap: None,
            tags: None,
            loop_refusal: None,
            report: LoadReport::default(),
        });
    };
    let shown = p.display().to_string();
    let (mesh, report) = Mesh::load_obj(p)?;
    let loop_refusal = loop_refusal(&shown, &mesh, &report, for_loop);
    if let Some(why) = loop_refusal.as_ref().filter(|_| for_loop) {
        bail!("{why}");
    }
    for w in load_warnings(&shown, &report) {
        note(format_args!("{w}"));
    }
    if let Err(MeshError::NonManifold {
        edges, vertices, ..
    }) = mesh.require_manifold()
    {
        // Only Loop subdivision needs a manifold (and refuses the mesh when it is drawn).
        let e = MeshError::NonManifold {
            path: shown.clone(),
            edges,
            vertices,
        };
        note(format_args!("warning: {e} (only --surface loop needs one)"));
    }
    let flipped = mesh.stats().inconsistently_oriented_edges;
    if flipped > 0 {
        // Drawn all the same, but a face wound the other way is easy to miss in the image.
        let normals = match report.normals_computed {
            true => "the normals computed from the faces are wrong beside them, and ",
            false => "",
        };
        note(format_args!(
            "warning: '{shown}' is not consistently oriented: {flipped} edge(s) join triangles of opposite winding; {normals}no element is culled as facing away"
        ));
    }
    Ok(Input {
        mesh,
        shown,
        heightmap: None,
        tags: None,
        loop_refusal,
        report,
    })
}

/// How many degenerate faces a warning lists before "and N more".
const LISTED_DEGENERATE: usize = 3;

/// One warning line for every dropped face: the count, then the first few runs of faces with
/// the same line and reason.
pub fn degenerate_warning(shown: &str, report: &LoadReport) -> Option<String> {
    let dropped = &report.dropped_degenerate;
    if dropped.is_empty() {
        return None;
    }
    let mut runs: Vec<(String, usize)> = Vec::new();
    for d in dropped {
        let what = d.describe();
        match runs.last_mut() {
            Some((last, n)) if *last == what => *n += 1,
            _ => runs.push((what, 1)),
        }
    }
    let mut listed: Vec<String> = runs
        .iter()
        .take(LISTED_DEGENERATE)
        .map(|(what, n)| match n {
            1 => what.clone(),
            n => format!("{what} ({n} triangles)"),
        })
        .collect();
    if runs.len() > LISTED_DEGENERATE {
        let more: usize = runs[LISTED_DEGENERATE..].iter().map(|(_, n)| n).sum();
        listed.push(format!("and {more} more triangle(s)"));
    }
    Some(format!(
        "warning: '{shown}': dropped {} degenerate face(s) (repeated vertex, zero area, an area f32 cannot represent, or the same three vertices as an earlier face): {}",
        dropped.len(),
        listed.join("; ")
    ))
}

/// One warning line for the polygons whose triangles may overlap or turn over: how many, and
/// the first few lines.
pub fn polygon_warning(shown: &str, report: &LoadReport) -> Option<String> {
    let lines = &report.uncovered_polygons;
    let first = lines.first()?;
    let (which, what) = match lines.len() {
        1 => (
            format!("the polygon at line {first}"),
            "crosses or touches itself, or is concave with more than {MAX} corners: it is",
        ),
        n => (
            format!("{n} polygons (the first at line {first})"),
            "cross or touch themselves, or are concave with more than {MAX} corners: they are",
        ),
    };
    let what = what.replace("{MAX}", &meshrefine::mesh::MAX_CLIPPED_CORNERS.to_string());
    Some(format!(
        "warning: '{shown}': {which} {what} split into triangles that may overlap or turn over (split such faces into simple polygons in the file)"
    ))
}

/// The warnings loading gives: dropped degenerate faces, polygons not covered.
pub fn load_warnings(shown: &str, report: &LoadReport) -> impl Iterator<Item = String> {
    [
        degenerate_warning(shown, report),
        polygon_warning(shown, report),
    ]
    .into_iter()
    .flatten()
}

/// `--crease-angle`'s range: (0, 180) degrees.
pub fn check_crease_angle(a: &super::numbers::TypedF32) -> Result<(), String> {
    if a.value.is_finite() && a.value > 0.0 && a.value < 180.0 {
        Ok(())
    } else {
        let inside = |x: f64| x > 0.0 && x < 180.0;
        Err(format!(
            "--crease-angle {} is not within (0, 180) degrees{}",
            a.text,
            a.in_f32_range(inside)
        ))
    }
}

/// Reads what `--heightmap` and `--tags` name for `input`'s mesh, unless `input` carries them
/// already. `any` for the window, whose panel can switch to the surface or displacement they
/// apply to.
pub fn read_surface_files(input: &mut Input, s: &SurfaceOpts, any: bool) -> Result<()> {
    if input.heightmap.is_none() {
        input.heightmap = s.heightmap(any).map_err(anyhow::Error::msg)?;
    }
    if input.tags.is_none() {
        let lines = &input.report.triangle_lines;
        input.tags = (s.tags(&input.mesh, &input.shown, lines, any)).map_err(anyhow::Error::msg)?;
    }
    Ok(())
}

/// [`read_surface_files`]; then with `--surface stpn` and no tags file, says where derived
/// tags cannot keep a crease.
pub fn attach_surface_inputs(input: &mut Input, s: &SurfaceOpts, any: bool) -> Result<()> {
    read_surface_files(input, s, any)?;
    if s.surface.facts().tags && s.drawn.tags.is_none() {
        split_three_creases(input, s.drawn.crease_angle.as_ref())?;
        let (_, corners) = meshrefine::surface::stpn::derive_with_angle(
            &input.mesh,
            s.drawn.crease_angle.as_ref().map(|a| a.value),
        );
        if corners > 0 {
            note(format_args!(
                "warning: '{}': {corners} vertices where three or more hard edges meet stay smooth under stpn (scalar-tagged PN triangles allow one crease per vertex; give tags with --tags)",
                input.shown
            ));
        }
    }
    Ok(())
}

/// Scalar-tagged PN allows two crease corners per triangle: a triangle whose three corners
/// carry derived creases (from split normals or `--crease-angle`) is split at its centroid
/// (`Mesh::split_at_centroids`: the new vertex is smooth, the old edges stay, so the surface
/// stays watertight), with one warning; `input` then carries the tags.
pub fn split_three_creases(
    input: &mut Input,
    crease_angle: Option<&super::numbers::TypedF32>,
) -> Result<()> {
    use meshrefine::surface::stpn;
    let mut tags = match input.tags.take() {
        Some(t) => t,
        None => stpn::derive(&input.mesh).0,
    };
    let which: Vec<usize> = (input.mesh.triangles.iter().enumerate())
        .filter(|(_, t)| t.p.iter().all(|&p| tags[p as usize].crease()))
        .map(|(i, _)| i)
        .collect();
    let source = match crease_angle {
        Some(a) => format!("--crease-angle {}", a.text.trim()),
        None => "the mesh's split normals".to_string(),
    };
    if let Some(&first) = which.first() {
        let face = input.report.face(first);
        let origin = input.mesh.split_at_centroids(&which).map_err(|e| {
            anyhow::anyhow!(
                "'{}': {face} {} (the creases come from {source}), and it cannot be split: {e}",
                input.shown,
                stpn::three_creases_message(&input.mesh, first)
            )
        })?;
        let lines = &input.report.triangle_lines;
        if !lines.is_empty() {
            input.report.triangle_lines = origin.iter().map(|&t| lines[t]).collect();
        }
        tags.resize(input.mesh.positions.len(), stpn::VertexTag::default());
        note(format_args!(
            "warning: '{}': split {} triangle(s) at their centroids, whose three corners are crease vertices (from {source}; scalar-tagged PN triangles allow two; the first: {face})",
            input.shown,
            which.len()
        ));
    }
    input.tags = Some(tags);
    Ok(())
}

/// Gives `scene` the height map and tags `input` carries.
pub fn apply_surface_inputs(
    h: &Headless,
    scene: &mut meshrefine::render::Scene,
    input: &Input,
) -> Result<()> {
    if let Some(map) = input.heightmap.clone() {
        h.set_heightmap(scene, map)?;
    }
    if let Some(tags) = input.tags.clone() {
        scene.set_tags(&h.ctx, &h.pool, &h.renderer, tags)?;
    }
    Ok(())
}

/// The draw configuration for `mesh` (displacement parameters not given are scaled to it, and
/// checked against its scale). An explicit `--submit` with another driver than `pattern` is
/// ignored with a warning (options.rs).
pub fn draw_config(t: &Technique, mesh: &Mesh) -> Result<DrawConfig> {
    Ok(DrawConfig {
        surface: t.surface.surface,
        displace: t.surface.drawn.displace,
        params: t
            .surface
            .drawn
            .params
            .params_for(mesh, &[t.surface.drawn.displace])
            .map_err(anyhow::Error::msg)?,
        build: t.surface.drawn.params.build().map_err(anyhow::Error::msg)?,
        // `--driver pattern` parses as the pattern driver; `--submit` gives its mode.
        driver: match t.driver {
            Driver::Pattern(_) => Driver::Pattern(t.submit()),
            d => d,
        },
        level: t.level,
        // Set with the adaptive options (src/cli/adaptive.rs).
        geomorph: false,
    })
}

/// The mesh as drawn (centred, unit size: [`Mesh::for_viewing`]) and `cfg` with its displacement
/// moved into the same frame, so the surface drawn is the mesh's own, only moved and scaled.
pub fn for_viewing(mesh: &Mesh, cfg: &DrawConfig) -> (Mesh, DrawConfig) {
    let (centre, scale) = mesh.viewing_transform();
    let mut viewed = *cfg;
    viewed.params = cfg.params.in_drawn_frame(centre, scale);
    (mesh.for_viewing(), viewed)
}

impl SurfaceOpts {
    /// The tags `--tags` names for `mesh` (None: the scene's derived ones), parsed over the
    /// derived tags and checked against appendix B's restrictions. With another surface than
    /// stpn, None (the option is ignored with a warning, see options.rs) unless `any_surface`
    /// (the window, which can switch to stpn). `shown` and `lines` (each triangle's line, from
    /// the load report) name the mesh and its faces in messages.
    pub fn tags(
        &self,
        mesh: &meshrefine::mesh::Mesh,
        shown: &str,
        lines: &[usize],
        any_surface: bool,
    ) -> Result<Option<Vec<meshrefine::surface::stpn::VertexTag>>, String> {
        use meshrefine::surface::stpn;
        if !self.surface.facts().tags && !any_surface {
            return Ok(None);
        }
        // Appendix B's restriction, named by the face's line and what made the creases.
        let check = |tags: &[stpn::VertexTag], source: &str| match stpn::three_creases(mesh, tags) {
            Some(t) => {
                let face = match lines.get(t) {
                    Some(l) => format!("the face at line {l}"),
                    None => format!("triangle {} (0-based)", t),
                };
                Err(format!(
                    "'{shown}': {face} {} (the creases come from {source})",
                    stpn::three_creases_message(mesh, t)
                ))
            }
            None => Ok(()),
        };
        // Derived tags are not checked here: the triangles with three crease corners they
        // give are split ([`split_three_creases`]).
        if self.drawn.tags.is_none() && self.drawn.crease_angle.is_none() {
            return Ok(None);
        }
        if let Some(a) = &self.drawn.crease_angle {
            check_crease_angle(a)?;
        }
        let angle = self.drawn.crease_angle.as_ref().map(|a| a.value);
        let (base, _) = stpn::derive_with_angle(mesh, angle);
        let Some(path) = &self.drawn.tags else {
            return Ok(Some(base));
        };
        let shown_tags = path.display().to_string();
        let (file, meta) = meshrefine::paths::open_input(path, "tags file")?;
        const MAX_TAGS_BYTES: u64 = 1 << 28;
        if meta.len() > MAX_TAGS_BYTES {
            return Err(format!(
                "tags file '{shown_tags}' is {} bytes: at most 256 MiB is read",
                meta.len()
            ));
        }
        let mut bytes = Vec::new();
        use std::io::Read as _;
        file.take(MAX_TAGS_BYTES)
            .read_to_end(&mut bytes)
            .map_err(|e| format!("cannot read tags file '{shown_tags}': {e}"))?;
        // Text, or the line where it stops being text.
        let line_of = |at: usize| bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1;
        if bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]) {
            return Err(format!(
                "tags file '{shown_tags}' line 1: is UTF-16 text (it starts with a UTF-16 byte-order mark): save it as UTF-8"
            ));
        }
        if let Some(at) = bytes.iter().position(|&b| b == 0) {
            return Err(format!(
                "tags file '{shown_tags}' line {}: contains a NUL byte, so this is binary data, not a tags file",
                line_of(at)
            ));
        }
        let text = std::str::from_utf8(&bytes).map_err(|e| {
            format!(
                "tags file '{shown_tags}' line {}: is not UTF-8 text",
                line_of(e.valid_up_to())
            )
        })?;
        let tags = stpn::parse(&shown_tags, text, mesh, &base)?;
        let tag_lines =
            (text.lines()).filter(|l| !l.split('#').next().unwrap_or("").trim().is_empty());
        if tag_lines.count() == 0 {
            let holds = if text.is_empty() {
                "it is empty"
            } else {
                "no line but comments"
            };
            crate::note(format_args!(
                "warning: tags file '{shown_tags}' tags no vertex ({holds}): every vertex keeps its derived tags"
            ));
        }
        check(&tags, &format!("tags file '{shown_tags}'"))?;
        Ok(Some(tags))
    }

    /// The height map `--heightmap` names (None: the scene's generated one). With another
    /// displacement, None (ignored with a warning, see options.rs) unless `any_displacement`
    /// (the window, which can switch to it).
    pub fn heightmap(
        &self,
        any_displacement: bool,
    ) -> Result<Option<meshrefine::surface::Heightmap>, String> {
        let Some(path) = &self.drawn.heightmap else {
            return Ok(None);
        };
        if !self.drawn.displace.facts().options.contains(&"heightmap") && !any_displacement {
            return Ok(None);
        }
        meshrefine::surface::Heightmap::load_png(path).map(Some)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use meshrefine::mesh::DegenerateFace;

    #[test]
    fn degenerate_warning_is_one_line_with_the_first_runs() {
        let face = |line, reason| DegenerateFace {
            face: 0,
            line: Some(line),
            reason,
        };
        let mut report = LoadReport::default();
        assert_eq!(degenerate_warning("x.obj", &report), None);
        report.dropped_degenerate = vec![face(7, "has zero area"); 1000];
        report
            .dropped_degenerate
            .extend([8, 9, 10, 11].map(|l| face(l, "repeats a vertex index")));
        let w = degenerate_warning("x.obj", &report).unwrap();
        assert!(!w.contains('\n'));
        assert!(
            w.starts_with("warning: 'x.obj': dropped 1004 degenerate face(s) "),
            "{w}"
        );
        assert!(
            w.ends_with(": at line 7, has zero area (1000 triangles); at line 8, repeats a vertex index; at line 9, repeats a vertex index; and 2 more triangle(s)"),
            "{w}"
        );
    }
}

//! The benchmark table's columns ([`COLUMNS`]), each declared once for every form of the table
//! (src/bench/report.rs writes them).

use super::report::{Align, Cell, Report};
use super::Row;

/// One column of the table, declared once for every form of it.
pub struct Column {
    /// The CSV header and the JSON key.
    pub key: &'static str,
    /// The markdown header; `None` where markdown shows the value elsewhere (the device above
    /// the table, a spread in its median's cell).
    pub markdown: Option<&'static str>,
    /// The summary's header; `None`: left to the full table.
    pub summary: Option<&'static str>,
    pub align: Align,
    /// A name the summary may shorten (with `…`) to fit.
    pub shrinks: bool,
    value: fn(&Report, &Row) -> Cell,
}

impl Column {
    pub fn cell(&self, report: &Report, row: &Row) -> Cell {
        (self.value)(report, row)
    }
}

const fn col(
    key: &'static str,
    markdown: Option<&'static str>,
    summary: Option<&'static str>,
    align: Align,
    value: fn(&Report, &Row) -> Cell,
) -> Column {
    Column {
        key,
        markdown,
        summary,
        align,
        shrinks: false,
        value,
    }
}

use Align::{Left, Right};

/// Every column of the table, in order.
pub static COLUMNS: &[Column] = &[
    col("device", None, None, Left, |p, _| {
        Cell::Prose(p.device.clone())
    }),
    Column {
        shrinks: true,
        ..col("mesh", Some("mesh"), Some("mesh"), Left, |_, r| {
            Cell::Name(r.mesh.clone())
        })
    },
    col(
        "coarse_triangles",
        Some("coarse tris"),
        None,
        Right,
        |_, r| Cell::Count(Some(r.coarse_triangles.into())),
    ),
    col("elements", Some("elements"), None, Right, |_, r| {
        Cell::Count(Some(r.elements.into()))
    }),
    col("level", Some("level"), Some("level"), Right, |_, r| {
        Cell::Count(Some(r.level.into()))
    }),
    col("surface", Some("surface"), Some("surface"), Left, |_, r| {
        Cell::Name(r.surface.name().into())
    }),
    col(
        "displace",
        Some("displace"),
        Some("displace"),
        Left,
        |_, r| Cell::Name(r.displace.name().into()),
    ),
    col("variant", Some("variant"), Some("variant"), Left, |_, r| {
        Cell::Name(r.variant.clone())
    }),
    col(
        "refined_triangles",
        Some("refined tris"),
        Some("refined tris"),
        Right,
        |_, r| Cell::Count(r.shown_triangles()),
    ),
    col(
        "gpu_ms_median",
        Some("GPU ms"),
        Some("GPU ms"),
        Right,
        |_, r| Cell::Spread(r.gpu_ms),
    ),
    col("gpu_ms_min", None, None, Right, |_, r| {
        Cell::Real(r.gpu_ms.map(|s| s.min), 2)
    }),
    col("gpu_ms_max", None, None, Right, |_, r| {
        Cell::Real(r.gpu_ms.map(|s| s.max), 2)
    }),
    col("wall_ms_median", Some("wall ms"), None, Right, |_, r| {
        Cell::Spread(r.wall_ms)
    }),
    col("wall_ms_min", None, None, Right, |_, r| {
        Cell::Real(r.wall_ms.map(|s| s.min), 2)
    }),
    col("wall_ms_max", None, None, Right, |_, r| {
        Cell::Real(r.wall_ms.map(|s| s.max), 2)
    }),
    col(
        "gpu_ns_per_refined_triangle",
        Some("GPU ns / refined tri"),
        Some("ns/tri"),
        Right,
        |_, r| Cell::Real(r.ns_per_triangle(), 2),
    ),
    col(
        "gpu_ratio_vs_static",
        Some("GPU / static"),
        Some("vs static"),
        Right,
        |_, r| Cell::Real(r.gpu_ratio, 2),
    ),
    col(
        "wall_ratio_vs_static",
        Some("wall / static"),
        None,
        Right,
        |_, r| Cell::Real(r.wall_ratio, 2),
    ),
    col(
        "throughput_vs_flat",
        Some("throughput / flat"),
        Some("vs flat"),
        Right,
        |_, r| Cell::Real(r.throughput_vs_flat, 2),
    ),
    col("pre_pass_ms", Some("M0→M1 ms"), None, Right, |_, r| {
        Cell::Real(r.pre_pass_ms, 3)
    }),
    col("table_bytes", Some("table bytes"), None, Right, |_, r| {
        Cell::Count(r.table_bytes)
    }),
    col(
        "stored_vertices",
        Some("stored vertices"),
        None,
        Right,
        |_, r| Cell::Count(Some(r.stored_vertices)),
    ),
    col(
        "stored_indices",
        Some("stored indices"),
        None,
        Right,
        |_, r| Cell::Count(Some(r.stored_indices)),
    ),
    col(
        "geometry_bytes",
        Some("geometry bytes"),
        Some("stored bytes"),
        Right,
        |_, r| Cell::Count(Some(r.geometry_bytes)),
    ),
    col(
        "vertex_invocations",
        Some("VS invocations"),
        None,
        Right,
        |_, r| Cell::Count(r.vertex_invocations),
    ),
    // Adaptive benchmarks' columns (`BenchOptions::adaptive`), empty on other rows.
    col("scene", Some("scene"), Some("scene"), Left, |_, r| {
        Cell::Name(adaptive(r).map_or(String::new(), |a| a.scene.clone()))
    }),
    col("adaptive", Some("adaptive"), None, Left, |_, r| {
        Cell::Flag(adaptive(r).map(|a| a.adaptive))
    }),
    col(
        "pixel_error",
        Some("pixel error"),
        Some("px"),
        Right,
        |_, r| Cell::Given(adaptive(r).map(|a| a.pixel_error)),
    ),
    col(
        "level_from",
        Some("levels from"),
        Some("levels from"),
        Left,
        |_, r| Cell::Name(adaptive(r).map_or(String::new(), |a| a.level_from.clone())),
    ),
    col(
        "level_pass_ms",
        Some("level pass ms"),
        Some("LOD ms"),
        Right,
        |_, r| Cell::Real(adaptive(r).and_then(|a| a.level_pass_ms), 3),
    ),
    col(
        "level_pass_on",
        Some("level pass on"),
        None,
        Left,
        |_, r| {
            Cell::Name(
                adaptive(r)
                    .and_then(|a| a.level_pass_on)
                    .unwrap_or("")
                    .into(),
            )
        },
    ),
    col(
        "culled_elements",
        Some("culled elements"),
        None,
        Right,
        |_, r| Cell::Count(adaptive(r).and_then(|a| a.culled_elements)),
    ),
    col("cpu_ms", Some("CPU ms"), Some("CPU ms"), Right, |_, r| {
        Cell::Real(adaptive(r).and_then(|a| a.cpu_ms), 3)
    }),
    col(
        "upload_bytes",
        Some("upload bytes"),
        Some("upload bytes"),
        Right,
        |_, r| Cell::Count(adaptive(r).and_then(|a| a.upload_bytes)),
    ),
    col(
        "level_histogram",
        Some("levels (L:elements)"),
        None,
        Left,
        |_, r| Cell::Name(adaptive(r).map_or(String::new(), |a| a.histogram.clone())),
    ),
    col("note", Some("note"), None, Left, |_, r| {
        Cell::Prose(r.note.clone())
    }),
];

/// A row's adaptive cells, if it has them.
fn adaptive(r: &Row) -> Option<&super::AdaptiveCells> {
    r.adaptive.as_ref()
}

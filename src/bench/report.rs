//! The benchmark's table: a [`Report`] of measured rows, written as markdown, CSV and JSON.
#![forbid(unsafe_code)]

use super::{Row, Stat};
use std::fmt::Write as _;

/// What one benchmark run measured: the device, the frame size and count, and one row per
/// variant.
pub struct Report {
    pub device: String,
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    pub rows: Vec<Row>,
}

fn fmt_stat(s: &Option<Stat>) -> String {
    s.map(|s| format!("{:.2} ({:.2}–{:.2})", s.median, s.min, s.max))
        .unwrap_or_else(|| "–".into())
}

fn fmt_ratio(r: Option<f64>) -> String {
    r.map(|r| format!("{r:.2}")).unwrap_or_else(|| "–".into())
}

impl Report {
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Device: {}. {}x{} offscreen, median (min–max) of {} timed frames (more where a note says so) after one warm-up frame, taken round the variants (of every surface together; with several surfaces each `static` alone first) in turn; ratios are against `static` at the same mesh and level, and throughput (refined triangles per GPU ms) against `flat` with the same variant, measured in the same run. Elements: the coarse triangles, or M1's faces for `loop`.\n",
            self.device, self.width, self.height, self.frames
        );
        let _ = writeln!(
            s,
            "| mesh | coarse tris | elements | level | surface | displace | variant | refined tris | GPU ms | wall ms | GPU ns / refined tri | GPU / static | wall / static | throughput / flat | M0→M1 ms | table bytes | stored vertices | stored indices | geometry bytes | VS invocations | note |"
        );
        let _ = writeln!(
            s,
            "|---|---:|---:|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
        );
        for r in &self.rows {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r.mesh,
                r.coarse_triangles,
                r.elements,
                r.level,
                r.surface.name(),
                r.displace.name(),
                r.variant,
                r.refined_triangles,
                fmt_stat(&r.gpu_ms),
                fmt_stat(&r.wall_ms),
                r.ns_per_triangle()
                    .map(|v| format!("{v:.2}"))
                    .unwrap_or_else(|| "–".into()),
                fmt_ratio(r.gpu_ratio),
                fmt_ratio(r.wall_ratio),
                fmt_ratio(r.throughput_vs_flat),
                r.pre_pass_ms.map(|v| format!("{v:.3}")).unwrap_or_else(|| "–".into()),
                r.table_bytes.map(|v| v.to_string()).unwrap_or_else(|| "–".into()),
                r.stored_vertices,
                r.stored_indices,
                r.geometry_bytes,
                r.vertex_invocations.map(|v| v.to_string()).unwrap_or_else(|| "–".into()),
                r.note
            );
        }
        s
    }

    /// Write `prefix.md` (headed by the command that made it), `prefix.csv` and `prefix.json`.
    /// The folder must exist: outputs never create folders (the command line checks the prefix up front, `meshrefine::paths`).
    pub fn write_files(&self, prefix: &std::path::Path, command: &str) -> std::io::Result<()> {
        let with = |ext: &str| {
            let mut p = prefix.as_os_str().to_owned();
            p.push(ext);
            std::path::PathBuf::from(p)
        };
        std::fs::write(
            with(".md"),
            format!("Command: `{command}`\n\n{}", self.markdown()),
        )?;
        std::fs::write(with(".csv"), self.csv())?;
        std::fs::write(with(".json"), self.json())
    }

    pub fn csv(&self) -> String {
        let mut s = String::from(
            "device,mesh,coarse_triangles,elements,level,surface,displace,variant,refined_triangles,gpu_ms_median,gpu_ms_min,gpu_ms_max,wall_ms_median,wall_ms_min,wall_ms_max,gpu_ns_per_refined_triangle,gpu_ratio_vs_static,wall_ratio_vs_static,throughput_vs_flat,pre_pass_ms,table_bytes,stored_vertices,stored_indices,geometry_bytes,vertex_invocations,note\n",
        );
        let f = |x: Option<f64>| x.map(|v| format!("{v:.4}")).unwrap_or_default();
        for r in &self.rows {
            let _ = writeln!(
                s,
                "\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\"",
                self.device,
                r.mesh,
                r.coarse_triangles,
                r.elements,
                r.level,
                r.surface.name(),
                r.displace.name(),
                r.variant,
                r.refined_triangles,
                f(r.gpu_ms.map(|s| s.median)),
                f(r.gpu_ms.map(|s| s.min)),
                f(r.gpu_ms.map(|s| s.max)),
                f(r.wall_ms.map(|s| s.median)),
                f(r.wall_ms.map(|s| s.min)),
                f(r.wall_ms.map(|s| s.max)),
                f(r.ns_per_triangle()),
                f(r.gpu_ratio),
                f(r.wall_ratio),
                f(r.throughput_vs_flat),
                f(r.pre_pass_ms),
                r.table_bytes.map(|v| v.to_string()).unwrap_or_default(),
                r.stored_vertices,
                r.stored_indices,
                r.geometry_bytes,
                r.vertex_invocations
                    .map(|v| v.to_string())
                    .unwrap_or_default(),
                r.note
            );
        }
        s
    }

    pub fn json(&self) -> String {
        let f = |x: Option<f64>| {
            x.map(|v| format!("{v:.4}"))
                .unwrap_or_else(|| "null".into())
        };
        let rows: Vec<String> = self
            .rows
            .iter()
            .map(|r| {
                format!(
                    "{{\"mesh\":\"{}\",\"coarse_triangles\":{},\"elements\":{},\"level\":{},\"surface\":\"{}\",\"displace\":\"{}\",\"variant\":\"{}\",\"refined_triangles\":{},\"gpu_ms_median\":{},\"wall_ms_median\":{},\"gpu_ns_per_refined_triangle\":{},\"gpu_ratio_vs_static\":{},\"wall_ratio_vs_static\":{},\"throughput_vs_flat\":{},\"pre_pass_ms\":{},\"table_bytes\":{},\"stored_vertices\":{},\"stored_indices\":{},\"geometry_bytes\":{},\"vertex_invocations\":{},\"note\":\"{}\"}}",
                    r.mesh, r.coarse_triangles, r.elements, r.level, r.surface.name(), r.displace.name(), r.variant, r.refined_triangles,
                    f(r.gpu_ms.map(|s| s.median)), f(r.wall_ms.map(|s| s.median)), f(r.ns_per_triangle()), f(r.gpu_ratio), f(r.wall_ratio),
                    f(r.throughput_vs_flat), f(r.pre_pass_ms), r.table_bytes.map(|v| v.to_string()).unwrap_or_else(|| "null".into()),
                    r.stored_vertices, r.stored_indices, r.geometry_bytes,
                    r.vertex_invocations.map(|v| v.to_string()).unwrap_or_else(|| "null".into()), r.note
                )
            })
            .collect();
        format!(
            "{{\"device\":\"{}\",\"frames\":{},\"width\":{},\"height\":{},\"rows\":[\n{}\n]}}\n",
            self.device.replace('"', "'"),
            self.frames,
            self.width,
            self.height,
            rows.join(",\n")
        )
    }
}

//! The library's enums as command-line values: the CLI adapts them, the library knows nothing
//! of clap.
//!
//! Each option that takes a surface, displacement, driver, submission mode, seam rule or
//! boundary rule parses with [`parser`]: a list of possible values, each with its name and one
//! line of help for `--help`, mapped back to the library's value. Names come from the library
//! where it has them (`Surface::name`, `Driver::name`, ...), since messages and exports use the
//! same words; the help lines, written for the command line, live here. Each help function
//! matches every variant, so a value added to the library is a compile error here until it has
//! its line.
#![forbid(unsafe_code)]

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use meshrefine::render::cage::Wireframe;
use meshrefine::render::{Background, Driver, Submit, View};
use meshrefine::surface::loop_::Boundary;
use meshrefine::surface::{Displace, NormalField, Seams, Surface};

/// A value parser that accepts `name(v)` for every `v` of `values` (listed in `--help` in that
/// order, each with `help(v)`), with the spaces around it left out ([`Trimmed`]), and yields `v`.
pub fn parser<T>(
    values: &[T],
    name: fn(T) -> &'static str,
    help: fn(T) -> &'static str,
) -> impl TypedValueParser<Value = T>
where
    T: Copy + Send + Sync + 'static,
{
    let values = values.to_vec();
    let possible: Vec<PossibleValue> = (values.iter())
        .map(|&v| PossibleValue::new(name(v)).help(help(v)))
        .collect();
    Trimmed(PossibleValuesParser::new(possible)).try_map(move |s: String| {
        (values.iter().copied())
            .find(|&v| name(v) == s)
            .ok_or_else(|| format!("'{s}' is not one of the possible values"))
    })
}

/// `P`, reading each value with the spaces around it removed, as `--eye " 1, 2, 3"` reads: a
/// whole number (`--max-level " 128"`), a name (`--surface "pn "`), an item of a comma-separated
/// list (`--levels "2, 4"`, `--surfaces "flat, pn"`). An empty value, or an empty item of a list
/// (`"flat,,pn"`), is refused as such.
#[derive(Clone)]
pub struct Trimmed<P>(pub P);

impl<P: TypedValueParser> TypedValueParser for Trimmed<P> {
    type Value = P::Value;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &std::ffi::OsStr,
    ) -> Result<Self::Value, clap::Error> {
        let trimmed = value
            .to_str()
            .map_or(value, |s| std::ffi::OsStr::new(s.trim()));
        if trimmed.is_empty() {
            // Rather than the inner parser's "a value is required" or "cannot parse integer
            // from empty string": say what is empty, as clap words a value's error.
            let list = arg.and_then(clap::Arg::get_value_delimiter).is_some();
            let refuse = move |_: &str| -> Result<P::Value, String> { Err(empty(list)) };
            return refuse.parse_ref(cmd, arg, value);
        }
        self.0.parse_ref(cmd, arg, trimmed)
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        self.0.possible_values()
    }
}

/// A path, kept as given (spaces are a path's own); an empty one is refused as every other
/// empty value is.
pub fn path() -> impl TypedValueParser<Value = std::path::PathBuf> {
    clap::builder::OsStringValueParser::new().try_map(|s| match s.is_empty() {
        true => Err(empty(false)),
        false => Ok(std::path::PathBuf::from(s)),
    })
}

/// What an empty value is called: an empty item of a comma-separated list (`"flat,,pn"`, `""`),
/// or an empty value.
fn empty(list: bool) -> String {
    if list {
        "an empty item in the list (items are separated by ',')".into()
    } else {
        "an empty value".into()
    }
}

/// `--surface`, `--surfaces`.
pub fn surface() -> impl TypedValueParser<Value = Surface> {
    parser(&Surface::ALL, Surface::name, |s| s.facts().help)
}

/// `--displace`, `--displacements`.
pub fn displace() -> impl TypedValueParser<Value = Displace> {
    parser(&Displace::ALL, Displace::name, |d| d.facts().help)
}

/// `--driver`, `--drivers`: `pattern` parses as the pattern driver with its default submission
/// (`--submit` picks another). The library says what each driver is.
pub fn driver() -> impl TypedValueParser<Value = Driver> {
    parser(&Driver::ALL, Driver::name, Driver::help)
}

/// `--cull`: `on` or `off`.
pub fn cull() -> impl TypedValueParser<Value = bool> {
    parser(&[true, false], on_off, |b| {
        if b {
            "draw nothing of the elements outside the view or facing away"
        } else {
            "draw every element"
        }
    })
}

/// `--geomorph`: `on` or `off`.
pub fn geomorph() -> impl TypedValueParser<Value = bool> {
    parser(&[true, false], on_off, |b| {
        if b {
            "glide the vertices a level adds into place"
        } else {
            "levels change in steps: the vertices a level adds appear in place"
        }
    })
}

fn on_off(b: bool) -> &'static str {
    if b {
        "on"
    } else {
        "off"
    }
}

/// `--submit`.
pub fn submit() -> impl TypedValueParser<Value = Submit> {
    parser(&Submit::ALL, Submit::name, submit_help)
}

fn submit_help(s: Submit) -> &'static str {
    match s {
        Submit::Push => "Per coarse triangle: push constants, then draw (the paper's loop)",
        Submit::Ubo => {
            "Per coarse triangle: the record read from a uniform-buffer window, then draw"
        }
        Submit::Instanced => {
            "One instanced draw; each record read as instance-rate vertex attributes"
        }
    }
}

/// `--pn-seams`.
pub fn seams() -> impl TypedValueParser<Value = Seams> {
    parser(&[Seams::Closed, Seams::Open], seams_name, seams_help)
}

fn seams_name(s: Seams) -> &'static str {
    match s {
        Seams::Closed => "closed",
        Seams::Open => "open",
    }
}

fn seams_help(s: Seams) -> &'static str {
    match s {
        Seams::Closed => "Crack-free: the geometry uses one normal per split position (its area-weighted normal); shading keeps the corners' own normals",
        Seams::Open => "As the papers: the geometry uses each corner's own normal, which opens cracks there",
    }
}

/// `--normal-field`.
pub fn normal_field() -> impl TypedValueParser<Value = NormalField> {
    parser(&NormalField::ALL, NormalField::name, normal_field_help)
}

fn normal_field_help(f: NormalField) -> &'static str {
    match f {
        NormalField::Paper => "Quadratic, as Boubekeur & Schlick 2005 write it: the fully reflected normal at edge midpoints",
        NormalField::Vlachos => "Quadratic, as Vlachos et al. 2001 write it: normalized reflected mid-edge control normals, a milder turn",
        NormalField::Linear => "The corner normals interpolated linearly (Phong shading)",
    }
}

/// `--boundary`.
pub fn boundary() -> impl TypedValueParser<Value = Boundary> {
    parser(
        &[Boundary::EdgeOnly, Boundary::EdgeAndCorner],
        boundary_name,
        boundary_help,
    )
}

/// The name `--boundary` takes, for messages too (`info`).
pub fn boundary_name(b: Boundary) -> &'static str {
    match b {
        Boundary::EdgeOnly => "edge-only",
        Boundary::EdgeAndCorner => "edge-and-corner",
    }
}

fn boundary_help(b: Boundary) -> &'static str {
    match b {
        Boundary::EdgeOnly => "Boundary edges infinitely sharp (OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY)",
        Boundary::EdgeAndCorner => "As edge-only, and boundary vertices of valence 2 stay fixed (VTX_BOUNDARY_EDGE_AND_CORNER)",
    }
}

/// `--wireframe`.
pub fn wireframe() -> impl TypedValueParser<Value = Wireframe> {
    parser(&Wireframe::ALL, Wireframe::name, |w| match w {
        Wireframe::Refined => "the refined triangles' edges, darker than the surface",
        Wireframe::Cage => "the coarse mesh's edges (Loop's control mesh) in light cyan",
        Wireframe::Both => "both",
    })
}

/// The arguments with `--wireframe` given without its optional value where the next one names
/// a mesh file rather than a value (a path ending in `.obj`, or holding a `/`): so
/// `render --wireframe spot.obj` reads as written, the mesh the mesh and the wireframe the
/// refined edges, where clap would take the path for the wireframe's value.
pub fn wireframe_before_a_path(args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let names_a_file = |a: &std::ffi::OsString| {
        let text = a.to_string_lossy();
        let t = text.trim();
        let value = Wireframe::ALL.iter().any(|w| w.name() == t);
        !value
            && !t.starts_with('-')
            && (t.to_ascii_lowercase().ends_with(".obj") || t.contains('/'))
    };
    let mut out = args.clone();
    for (i, a) in args.iter().enumerate() {
        if a == "--wireframe" && args.get(i + 1).is_some_and(names_a_file) {
            out[i] = "--wireframe=refined".into();
        }
    }
    out
}

/// `--view`.
pub fn view() -> impl TypedValueParser<Value = View> {
    parser(&View::ALL, View::name, |v| match v {
        View::Shaded => "the lit surface",
        View::Normals => "the normal field as colours",
        View::Levels => {
            "the lit surface coloured by each element's level (blue at 1 to red at 256)"
        }
        View::Plain => {
            "the surface in one colour, unlit (its silhouette; the fragment stage does no work)"
        }
    })
}

/// `--background`.
pub fn background() -> impl TypedValueParser<Value = Background> {
    parser(&Background::ALL, Background::name, |b| match b {
        Background::Dark => "near black",
        Background::Light => "pale grey (cracks show as dark spots)",
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Parses `s` with `p` as the value of a bare argument.
    fn parse<T: Send + Sync + Clone + 'static>(
        p: &impl TypedValueParser<Value = T>,
        s: &str,
    ) -> Result<T, clap::Error> {
        let cmd = clap::Command::new("t");
        let arg = clap::Arg::new("x");
        p.parse_ref(&cmd, Some(&arg), std::ffi::OsStr::new(s))
    }

    #[test]
    fn every_library_value_parses_from_its_name_and_nothing_else_does() {
        for s in Surface::ALL {
            assert_eq!(parse(&surface(), s.name()).unwrap(), s);
        }
        for d in Displace::ALL {
            assert_eq!(parse(&displace(), d.name()).unwrap(), d);
        }
        for d in Driver::ALL {
            assert_eq!(parse(&driver(), d.name()).unwrap(), d);
        }
        for s in Submit::ALL {
            assert_eq!(parse(&submit(), s.name()).unwrap(), s);
        }
        for (name, s) in [("closed", Seams::Closed), ("open", Seams::Open)] {
            assert_eq!(parse(&seams(), name).unwrap(), s);
        }
        for (name, b) in [
            ("edge-only", Boundary::EdgeOnly),
            ("edge-and-corner", Boundary::EdgeAndCorner),
        ] {
            assert_eq!(parse(&boundary(), name).unwrap(), b);
            assert_eq!(boundary_name(b), name);
        }
        for (name, f) in [
            ("paper", NormalField::Paper),
            ("vlachos", NormalField::Vlachos),
            ("linear", NormalField::Linear),
        ] {
            assert_eq!(parse(&normal_field(), name).unwrap(), f);
        }
        assert!(parse(&normal_field(), "quadratic").is_err());
        assert!(parse(&surface(), "Flat").is_err());
        assert!(parse(&driver(), "instanced").is_err());
        assert!(parse(&boundary(), "edge").is_err());
    }
}

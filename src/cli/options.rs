//! Options that do not apply to what was chosen: one rule for all of them.
//!
//! An option that only one surface, displacement or driver reads (`--alpha` only phong,
//! `--tags` only stpn, `--submit` only the pattern driver, ...) but was given with another is
//! ignored with one warning line naming the option, what it applies to and what was chosen; the
//! run goes on. A warning, not an error, because nothing about the request is wrong: the
//! option is merely unused (scripts that pass the same options to every surface keep working),
//! and the warning says so where a typo would otherwise go unnoticed. `view` warns about none
//! of them: its panel switches surfaces, displacements and drivers, so every option can apply
//! later.
//!
//! Whether an option was given is read from clap's matches ([`Given`]), so options with a
//! default (`--alpha 0.75`) are told apart from the default itself.
#![forbid(unsafe_code)]

use super::args::{AdaptiveOpts, Cli, SurfaceOpts, Technique};
use clap::parser::ValueSource;
use clap::{CommandFactory as _, FromArgMatches as _};
use meshrefine::render::Driver;
use meshrefine::surface::{Displace, Surface};
use std::collections::HashSet;

/// The ids (field names) of the options given on the command line, not left at their defaults.
#[derive(Debug, Default)]
pub struct Given(HashSet<String>);

impl Given {
    pub fn has(&self, id: &str) -> bool {
        self.0.contains(id)
    }
}

/// The command line's definition: [`Cli`]'s, with the help of the adaptive options
/// ([`AdaptiveOpts`], one struct in four commands) ending in what each command does by default.
pub fn command() -> clap::Command {
    let tess = "the tessellator's limit for tess";
    let mut command = Cli::command();
    for (name, pixel_error, max_level, cull) in [
        (
            "render",
            "Not with --level; default: 1, unless --level is given.".to_string(),
            format!("Default: 64 for the pattern and static drivers, whose largest level is a power of two, and {tess}."),
            "Default: on.",
        ),
        (
            "view",
            "Not with --level; default: 1, unless --level or --lod is given.".to_string(),
            format!("Default: 64 for the pattern and static drivers, whose largest level is a power of two, and {tess}."),
            "Default: on.",
        ),
        (
            "export",
            "Not with --level; without it the export is uniform, at --level.".to_string(),
            format!("With --pixel-error; default: 64 for the pattern driver, whose largest level is a power of two, and {tess}."),
            "Default: off: every element is written.",
        ),
        (
            "bench",
            "Without it every variant is timed uniformly, at each of --levels.".to_string(),
            format!("With --pixel-error; default: 64 for the pattern and static drivers, whose largest level is a power of two, and {tess}."),
            "Default: on.",
        ),
    ] {
        let add = |a: clap::Arg, tail: &str| {
            let help = a.get_help().map(|h| h.to_string()).unwrap_or_default();
            // Clap drops a one-paragraph doc comment's final full stop.
            a.help(format!("{help}. {tail}"))
        };
        command = command.mut_subcommand(name, |c| {
            c.mut_arg("pixel_error", |a| add(a, &pixel_error))
                .mut_arg("max_level", |a| add(a, &max_level))
                .mut_arg("cull", |a| add(a, cull))
        });
    }
    command
}

/// Parses the command line like `Cli::try_parse`, and says which options were given.
pub fn parse() -> Result<(Cli, Given), clap::Error> {
    parse_from(std::env::args_os())
}

/// [`parse`] for the arguments `args` (the program's name first).
pub fn parse_from<I, T>(args: I) -> Result<(Cli, Given), clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let mut command = command();
    let args: Vec<std::ffi::OsString> = args.into_iter().map(Into::into).collect();
    let matches = match command.try_get_matches_from_mut(args.clone()) {
        Ok(matches) => matches,
        // `--wireframe` took a path for its value: read as written, the path the mesh
        // ([`super::choices::wireframe_before_a_path`]).
        Err(e) if wireframe_refused(&e) => {
            let args = super::choices::wireframe_before_a_path(args);
            command.try_get_matches_from_mut(args)?
        }
        Err(e) => return Err(e),
    };
    let cli = Cli::from_arg_matches(&matches).map_err(|e| e.format(&mut command))?;
    let given = matches
        .subcommand()
        .map(|(_, sub)| {
            sub.ids()
                .filter(|id| sub.value_source(id.as_str()) == Some(ValueSource::CommandLine))
                .map(|id| id.as_str().to_string())
                .collect()
        })
        .unwrap_or_default();
    Ok((cli, Given(given)))
}

/// Whether `e` refuses a value of `--wireframe`.
fn wireframe_refused(e: &clap::Error) -> bool {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    e.kind() == ErrorKind::InvalidValue
        && matches!(e.get(ContextKind::InvalidArg),
            Some(ContextValue::String(arg)) if arg.starts_with("--wireframe"))
}

/// What a command chose: the surfaces and displacements it draws (several for `bench`), with
/// the option that chose them for messages, and whether the driver is the pattern driver.
pub struct Chosen<'a> {
    pub surfaces: &'a [Surface],
    /// "--surface pn" or "--surfaces flat,pn".
    pub surface_shown: String,
    pub displaces: &'a [Displace],
    pub displace_shown: String,
    /// `Some((is the pattern driver, "--driver tess"))` where the command has a driver.
    pub driver: Option<(bool, String)>,
}

/// "--surface pn" / "--surfaces flat,pn" for messages.
pub fn shown<T: Copy>(option: &str, values: &[T], name: impl Fn(T) -> &'static str) -> String {
    let names: Vec<&str> = values.iter().map(|&v| name(v)).collect();
    format!("{option} {}", names.join(","))
}

/// Each option that some of `values` read (their facts' `options`, in order of first mention),
/// with the names of those that read it.
fn readers<T: Copy>(
    values: &[T],
    options: impl Fn(T) -> &'static [&'static str],
    name: impl Fn(T) -> &'static str,
) -> Vec<(&'static str, Vec<&'static str>)> {
    let mut out: Vec<(&'static str, Vec<&'static str>)> = Vec::new();
    for &v in values {
        for &id in options(v) {
            match out.iter_mut().find(|(o, _)| *o == id) {
                Some((_, names)) => names.push(name(v)),
                None => out.push((id, vec![name(v)])),
            }
        }
    }
    out
}

/// "phong", "phong or pn", "phong, pn or stpn".
fn or_list(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [rest @ .., last] => format!("{} or {last}", rest.join(", ")),
    }
}

/// One warning line (without "warning: ") for every given option that nothing chosen reads.
/// Which surface or displacement reads which option is what each declares
/// ([`meshrefine::surface::SurfaceFacts::options`]).
pub fn inapplicable(given: &Given, c: &Chosen) -> Vec<String> {
    let surfaces = readers(&Surface::ALL, |s| s.facts().options, Surface::name);
    let displaces = readers(&Displace::ALL, |d| d.facts().options, Displace::name);
    let read_by_surface = |id: &str| c.surfaces.iter().any(|s| s.facts().options.contains(&id));
    let read_by_displace = |id: &str| c.displaces.iter().any(|d| d.facts().options.contains(&id));
    let mut out = Vec::new();
    for (readers, read, kind, chosen) in [
        (
            surfaces,
            &read_by_surface as &dyn Fn(&str) -> bool,
            "--surface",
            &c.surface_shown,
        ),
        (
            displaces,
            &read_by_displace,
            "--displace",
            &c.displace_shown,
        ),
    ] {
        for (id, names) in readers {
            if given.has(id) && !read(id) {
                out.push(format!(
                    "--{} applies only to {kind} {}, not to {chosen}: it is ignored",
                    id.replace('_', "-"),
                    or_list(&names),
                ));
            }
        }
    }
    if let Some((false, driver)) = &c.driver {
        if given.has("submit") {
            out.push(format!(
                "--submit applies only to --driver pattern, not to {driver}: it is ignored"
            ));
        }
    }
    out
}

/// The options of adaptive drawing besides `--pixel-error` and the camera (render, export,
/// view, bench).
const ADAPTIVE: &[&str] = &["max_level", "cull", "geomorph"];

/// The camera's options: render, view and bench draw from the camera asked for, adaptive or
/// uniform; a uniform export writes every element whatever the camera.
const CAMERA: &[&str] = &["eye", "look_at", "fov"];

/// `info`'s options that only its report of adaptive levels reads (`--pixel-error`): the
/// camera, the level options, and what changes the surface drawn (its displacement, inputs and
/// parameters; not Loop's build options, which its Loop report reads too).
const INFO_ADAPTIVE: &[&str] = &[
    "eye",
    "look_at",
    "fov",
    "width",
    "height",
    "max_level",
    "geomorph",
    "driver",
    "cull",
    "displace",
    "heightmap",
    "tags",
    "crease_angle",
    "alpha",
    "amplitude",
    "frequency",
    "octaves",
    "bias",
    "pn_seams",
    "normal_field",
];

/// One warning line for each of `ids` given without `--pixel-error` (`adaptive` false).
fn adaptive_only(given: &Given, adaptive: bool, ids: &[&str]) -> Vec<String> {
    unread_unless(given, adaptive, ids, "with --pixel-error")
}

/// One warning line for each of `ids` given where `read` is false: "applies only `when`".
fn unread_unless(given: &Given, read: bool, ids: &[&str], when: &str) -> Vec<String> {
    (ids.iter())
        .filter(|id| given.has(id) && !read)
        .map(|id| {
            format!(
                "--{} applies only {when}: it is ignored",
                id.replace('_', "-")
            )
        })
        .collect()
}

/// `--geomorph` given for drawing that cannot glide: the static driver never does (it refines
/// on the CPU when the levels change), the tess driver only under a power-of-two largest level.
fn geomorph_unread(
    given: &Given,
    adaptive: bool,
    (geomorph, max_level): (Option<bool>, Option<u32>),
    drivers: &[Driver],
) -> Vec<String> {
    if !adaptive || !given.has("geomorph") {
        return Vec::new();
    }
    let glides = |d: &Driver| {
        let level = max_level.unwrap_or(1).max(1);
        !d.kind().refines_on_cpu() && (!d.kind().integer_levels() || level.is_power_of_two())
    };
    if drivers.iter().any(glides) {
        return Vec::new();
    }
    let names: Vec<&str> = drivers.iter().map(|d| d.name()).collect();
    if drivers.iter().all(|d| d.kind().refines_on_cpu()) {
        return vec![format!(
            "--geomorph applies only to the pattern and tess drivers, not to the {} driver: it is ignored",
            or_list(&names)
        )];
    }
    match (geomorph, max_level) {
        (Some(true), Some(l)) => vec![format!(
            "--geomorph on: the tess driver glides only under a --max-level that is a power of two; at --max-level {l} it draws integer levels without gliding"
        )],
        _ => Vec::new(),
    }
}

/// What a command that draws one surface with `driver` chose.
fn single(s: &SurfaceOpts, driver: Driver) -> Chosen<'_> {
    Chosen {
        surfaces: std::slice::from_ref(&s.surface),
        surface_shown: format!("--surface {}", s.surface.name()),
        displaces: std::slice::from_ref(&s.drawn.displace),
        displace_shown: format!("--displace {}", s.drawn.displace.name()),
        driver: Some((
            driver.submit().is_some(),
            format!("--driver {}", driver.name()),
        )),
    }
}

/// The warnings (without "warning: ") for the options one image drawn with `technique` and
/// `adaptive` ignores, drawn uniformly at `--level` where `uniform` says so (the options that
/// ask for it named in `uniform_by`; else adaptively, at `--pixel-error` or by default): `render`'s, and the headless `view`'s, which has no panel
/// to switch to what they apply to.
pub fn drawn_image(
    given: &Given,
    technique: &Technique,
    adaptive: &AdaptiveOpts,
    (uniform, uniform_by): (bool, &str),
) -> Vec<String> {
    let d = technique.driver;
    let mut out = inapplicable(given, &single(&technique.surface, d));
    let on = adaptive.pixel_error.is_some() || !uniform;
    // Adaptive by default: only the options that ask for uniform levels make them unread.
    let when =
        format!("when drawing adaptively (with --pixel-error, or by default without {uniform_by})");
    out.extend(unread_unless(given, on, ADAPTIVE, &when));
    out.extend(geomorph_unread(given, on, adaptive.geomorph_asked(), &[d]));
    out
}

/// The warnings (without "warning: ") for the options `cli`'s command ignores.
pub fn warnings(cli: &Cli, given: &Given) -> Vec<String> {
    use super::args::Command;
    let check = |c: &Chosen| inapplicable(given, c);
    match &cli.command {
        // The window's panel can switch to whatever an option applies to.
        Command::View(_) => Vec::new(),
        Command::Devices if given.has("device") => vec![
            "--device applies only to the commands that draw, not to devices (which lists every device): it is ignored"
                .to_string(),
        ],
        Command::Devices => Vec::new(),
        // Adaptive by default: only --level draws uniformly.
        Command::Render(a) => {
            let uniform = (given.has("level"), "--level");
            drawn_image(given, &a.technique, &a.adaptive, uniform)
        }
        Command::Export(a) => {
            let d = a.driver.driver();
            let mut out = check(&single(&a.surface, d));
            let adaptive = a.adaptive.pixel_error.is_some();
            out.extend(adaptive_only(given, adaptive, ADAPTIVE));
            out.extend(adaptive_only(given, adaptive, CAMERA));
            out.extend(adaptive_only(given, adaptive, &["width", "height"]));
            out.extend(geomorph_unread(
                given,
                adaptive,
                a.adaptive.geomorph_asked(),
                &[d],
            ));
            out
        }
        Command::Bench(a) => {
            let mut out = check(&Chosen {
                surfaces: &a.surfaces,
                surface_shown: shown("--surfaces", &a.surfaces, Surface::name),
                displaces: &a.displacements,
                displace_shown: shown("--displacements", &a.displacements, Displace::name),
                driver: None,
            });
            let adaptive = a.adaptive.pixel_error.is_some();
            out.extend(adaptive_only(given, adaptive, ADAPTIVE));
            out.extend(adaptive_only(given, adaptive, &["no_bound_levels"]));
            // Adaptively every driver is measured unless some are named.
            let drivers = if a.drivers.is_empty() {
                Driver::ALL.to_vec()
            } else {
                a.drivers.clone()
            };
            out.extend(geomorph_unread(
                given,
                adaptive,
                a.adaptive.geomorph_asked(),
                &drivers,
            ));
            out
        }
        Command::Info(a) => {
            let adaptive = a.pixel_error.is_some();
            // With --pixel-error the levels are reported for --surface, pn by default.
            let surfaces: Vec<Surface> = match a.surface {
                None if adaptive => vec![Surface::Pn],
                s => s.into_iter().collect(),
            };
            let mut out = Vec::new();
            out.extend(adaptive_only(given, adaptive, INFO_ADAPTIVE));
            let asked = (a.geomorph, Some(a.max_level));
            out.extend(geomorph_unread(given, adaptive, asked, &[a.driver]));
            // Each is said once: without --pixel-error, that it applies only with it.
            let given = &Given(
                (given.0.iter())
                    .filter(|id| adaptive || !INFO_ADAPTIVE.contains(&id.as_str()))
                    .cloned()
                    .collect(),
            );
            let check = |c: &Chosen| inapplicable(given, c);
            if let Some(s) = a.surface.filter(|s| !s.uses_loop_faces() && !adaptive) {
                let builders: Vec<&str> = (Surface::ALL.into_iter())
                    .filter(|s| s.uses_loop_faces())
                    .map(Surface::name)
                    .collect();
                out.push(format!(
                    "info --surface reports only what --surface {} builds, not --surface {}: it is ignored",
                    or_list(&builders),
                    s.name()
                ));
            }
            out.extend(check(&Chosen {
                surfaces: &surfaces,
                surface_shown: match (a.surface, adaptive) {
                    (Some(s), _) => format!("--surface {}", s.name()),
                    (None, true) => "--surface pn".to_string(),
                    (None, false) => "info without --surface".to_string(),
                },
                displaces: std::slice::from_ref(&a.drawn.displace),
                displace_shown: format!("--displace {}", a.drawn.displace.name()),
                driver: None,
            }));
            out
        }
    }
}

/// Checks the values of `cli`'s surface and displacement parameters, and its camera's and
/// adaptive drawing's (`adaptive::check_values`), whether or not what is drawn reads them (a
/// value out of its range is refused, not said to be ignored), before any warning or work: one
/// sentence naming the option and its value.
pub fn check_values(cli: &Cli) -> Result<(), String> {
    use super::args::{Command, DrawnOpts};
    let (params, drawn): (&super::args::ParamOpts, Option<&DrawnOpts>) = match &cli.command {
        Command::Render(a) => (
            &a.technique.surface.drawn.params,
            Some(&a.technique.surface.drawn),
        ),
        Command::View(a) => (
            &a.technique.surface.drawn.params,
            Some(&a.technique.surface.drawn),
        ),
        Command::Export(a) => (&a.surface.drawn.params, Some(&a.surface.drawn)),
        Command::Info(a) => (&a.drawn.params, Some(&a.drawn)),
        Command::Bench(a) => (&a.params, None),
        Command::Devices => return Ok(()),
    };
    // The radius only sets the defaults of what is not given.
    params.params(1.0)?;
    params.build()?;
    if let Some(a) = drawn.and_then(|d| d.crease_angle.as_ref()) {
        super::input::check_crease_angle(a)?;
    }
    super::adaptive::check_values(cli).map_err(|e| e.to_string())
}

/// Checks every output path of `cli`'s command by the rules of `meshrefine::paths`, before any
/// work is done.
pub fn check_outputs(cli: &Cli) -> Result<(), String> {
    use super::args::Command;
    use meshrefine::paths::{check_output, Output};
    match &cli.command {
        Command::Render(a) => check_output(&a.output, "-o", Output::File),
        Command::Export(a) => check_output(&a.output, "-o", Output::File),
        Command::View(a) => {
            if let Some(shot) = &a.screenshot {
                check_output(shot, "--screenshot", Output::File)?;
            }
            // Written only where no window opens (then as render writes it).
            check_output(&a.headless_output, "--headless-output", Output::Fallback)
        }
        Command::Bench(a) => match &a.out {
            Some(prefix) => check_output(prefix, "--out", Output::Prefix),
            None => Ok(()),
        },
        Command::Info(_) | Command::Devices => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--wireframe` before the mesh: a path (ending in `.obj`, or with a `/`) is the mesh and
    /// the wireframe the refined edges; a value is the wireframe's; anything else is refused
    /// as a value of `--wireframe`.
    #[test]
    fn wireframe_before_the_mesh_leaves_the_mesh() {
        use super::super::args::Command;
        use meshrefine::render::cage::Wireframe;
        let parsed = |args: &[&str]| {
            let (cli, _) = parse_from([&["meshrefine"][..], args].concat()).unwrap();
            match cli.command {
                Command::Render(r) => (r.mesh, r.wireframe),
                Command::View(v) => (v.mesh, v.wireframe),
                _ => panic!("{args:?}"),
            }
        };
        let mesh = |p: &str| Some(std::path::PathBuf::from(p));
        for path in ["spot.obj", "models/spot", "SPOT.OBJ"] {
            for sub in ["render", "view"] {
                let got = parsed(&[sub, "--wireframe", path]);
                assert_eq!(got, (mesh(path), Some(Wireframe::Refined)), "{sub} {path}");
            }
        }
        let got = parsed(&["render", "--wireframe", "cage", "spot.obj"]);
        assert_eq!(got, (mesh("spot.obj"), Some(Wireframe::Cage)));
        assert_eq!(
            parsed(&["render", "--wireframe"]),
            (None, Some(Wireframe::Refined))
        );
        let e = parse_from(["meshrefine", "render", "--wireframe", "refind"])
            .err()
            .unwrap();
        assert!(e.to_string().contains("for '--wireframe"), "{e}");
        // Only where `--wireframe` is the option, not another's value as typed.
        let e = parse_from(["meshrefine", "render", "--level", "--wireframe", "a.obj"]);
        let e = e.err().unwrap().to_string();
        assert!(e.contains("'--wireframe' for '--level"), "{e}");
    }

    /// The adaptive options' help names each command's own default, and no option the command
    /// lacks (bench has --levels, not --level; only export writes every element by default).
    #[test]
    fn adaptive_help_is_each_commands_own() {
        let command = command();
        let help = |sub: &str, arg: &str| {
            let c = command.find_subcommand(sub).unwrap();
            let a = c.get_arguments().find(|a| a.get_id() == arg).unwrap();
            a.get_help().unwrap().to_string()
        };
        for sub in ["render", "view", "export", "bench"] {
            let has_level = sub != "bench";
            let pixel_error = help(sub, "pixel_error");
            assert_eq!(
                pixel_error.contains("Not with --level"),
                has_level,
                "{pixel_error}"
            );
            assert_eq!(
                pixel_error.contains("default: 1"),
                sub == "render" || sub == "view"
            );
            assert_eq!(
                pixel_error.contains("--lod"),
                sub == "view",
                "{pixel_error}"
            );
            let cull = help(sub, "cull");
            let off = "Default: off: every element is written.";
            let default = if sub == "export" { off } else { "Default: on." };
            assert!(cull.ends_with(default), "{cull}");
            let max_level = help(sub, "max_level");
            assert_eq!(max_level.contains("static"), sub != "export", "{max_level}");
            assert!(!max_level.contains("render and view"), "{max_level}");
        }
    }

    fn given(ids: &[&str]) -> Given {
        Given(ids.iter().map(|s| s.to_string()).collect())
    }

    fn chosen<'a>(surfaces: &'a [Surface], displaces: &'a [Displace]) -> Chosen<'a> {
        Chosen {
            surfaces,
            surface_shown: shown("--surfaces", surfaces, Surface::name),
            displaces,
            displace_shown: shown("--displace", displaces, Displace::name),
            driver: Some((false, "--driver tess".into())),
        }
    }

    #[test]
    fn every_option_warns_only_where_nothing_chosen_reads_it() {
        let all = [
            "alpha",
            "pn_seams",
            "normal_field",
            "tags",
            "crease_angle",
            "boundary",
            "bft_level",
            "amplitude",
            "frequency",
            "octaves",
            "bias",
            "heightmap",
            "submit",
        ];
        let w = inapplicable(&given(&all), &chosen(&[Surface::Flat], &[Displace::None]));
        assert_eq!(w.len(), all.len(), "{w:#?}");
        assert_eq!(
            w[0],
            "--alpha applies only to --surface phong, not to --surfaces flat: it is ignored"
        );
        assert_eq!(
            w[2],
            "--normal-field applies only to --surface pn or stpn, not to --surfaces flat: it is ignored"
        );
        assert_eq!(
            w[12],
            "--submit applies only to --driver pattern, not to --driver tess: it is ignored"
        );
        // Each surface or displacement silences exactly its own options.
        let w = inapplicable(
            &given(&all),
            &chosen(&[Surface::Flat, Surface::Phong], &[Displace::Noise]),
        );
        let named: Vec<&str> = w.iter().map(|l| l.split(' ').next().unwrap()).collect();
        assert_eq!(
            named,
            [
                "--normal-field",
                "--tags",
                "--crease-angle",
                "--boundary",
                "--bft-level",
                "--bias",
                "--heightmap",
                "--submit"
            ]
        );
        // Options not given never warn.
        assert!(inapplicable(&given(&[]), &chosen(&[Surface::Flat], &[Displace::None])).is_empty());
    }

    /// The example commands of the README's quick start and docs/cli.md's examples are
    /// commands a user can paste: each parses, passes the checks of its values and camera made
    /// before any work, draws no warning, and every mesh it names is in the repository.
    #[test]
    fn documented_examples_parse_and_pass_the_checks() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut seen = 0;
        for doc in ["README.md", "docs/cli.md"] {
            let text = std::fs::read_to_string(root.join(doc)).unwrap();
            let mut in_sh = false;
            for line in text.lines() {
                if line.starts_with("```") {
                    in_sh = line == "```sh";
                    continue;
                }
                let Some(rest) = line.strip_prefix("meshrefine ").filter(|_| in_sh) else {
                    continue;
                };
                // A comment starts at " # " (no example quotes anything).
                let command = rest.split(" # ").next().unwrap();
                let words: Vec<&str> = command.split_whitespace().collect();
                let args = [&["meshrefine"][..], &words[..]].concat();
                let (cli, given) =
                    parse_from(&args).unwrap_or_else(|e| panic!("{doc}: {line}: {e}"));
                check_values(&cli).unwrap_or_else(|e| panic!("{doc}: {line}: {e}"));
                super::super::adaptive::check(&cli, &given)
                    .unwrap_or_else(|e| panic!("{doc}: {line}: {e}"));
                assert_eq!(
                    warnings(&cli, &given),
                    Vec::<String>::new(),
                    "{doc}: {line}"
                );
                for path in words
                    .iter()
                    .filter(|w| w.ends_with(".obj") && w.starts_with("assets/"))
                {
                    assert!(root.join(path).is_file(), "{doc}: {line}: no {path}");
                }
                seen += 1;
            }
        }
        // The README's sixteen and cli.md's twelve.
        assert!(seen >= 28, "{seen} examples found");
    }
}

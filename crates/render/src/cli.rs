//! The `strata` command line (a contract: see the design notes), parsed with clap.
//!
//! ```text
//! strata render SCENE.xml [-o|--out OUT.exr] [--spp N] [--time SECONDS]
//!               [--integrator reference|nee|mis|ris|auto|path] [--sampler independent|stratified|bluenoise|sobol]
//!               [--rr on|off] [--lights uniform|power|ris|all] [--adaptive [on|off]] [--light-tracing] [--path-reuse [off|2|4]] [--max-depth N] [--seed N]
//!               [-t|--threads N] [--width W --height H] [--png OUT.png] [--exposure STOPS]
//!               [--stats OUT.json] [--state STATE] [--resume STATE] [--samples START..END]
//!               [-D NAME=VALUE ...] [-q|--quiet]
//! strata diff A.exr B.exr
//! strata merge A.exr B.exr … --out OUT.exr [--png OUT.png] [--exposure STOPS]
//! ```
//!
//! Without `--out`, `strata render` writes `SCENE.exr` (the scene file's name with `.exr` for
//! its extension) in the working directory, as Mitsuba does; it never writes over the scene
//! file. After a successful render it prints one summary line on standard error, e.g.
//!
//! ```text
//! cbox.exr: 256×256, 128 spp, 1.84 s, 9.61 M rays/s, auto: bsdf-sampling+nee+…
//! ```
//!
//! (see [`crate::summary`]); `--quiet` leaves it and the progress bar out. `path`, Mitsuba's
//! name for its integrator, is another name for `auto`.
//!
//! Bad flags and values make clap print a message and exit with status 2.

use std::path::PathBuf;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand, ValueEnum};
use sampling::SamplerKind;
use scene::IntegratorPreset;

/// The parsed command line.
#[derive(Debug, Parser, PartialEq)]
#[command(
    name = "strata",
    version,
    about = "A path tracer for Mitsuba 3 scenes that measures its own noise"
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand, PartialEq)]
pub enum Command {
    /// Render a Mitsuba 3 XML scene to a linear float32 RGB EXR image.
    Render(RenderArgs),
    /// Compare two EXR images; print one JSON line {"rmse", "relmse", "mean_a", "mean_b"}.
    Diff(DiffArgs),
    /// Add up renders of disjoint samples of one render (--samples pieces, or renders with
    /// different --seed values) into the image of all their samples, exactly; refuse inputs of
    /// different scenes or settings, and samples given twice.
    Merge(MergeArgs),
}

/// `--integrator`'s values: [`IntegratorPreset`]'s names (and its aliases, which the help does
/// not list), each with its help line, parsed by its [`FromStr`](std::str::FromStr).
fn integrator_preset() -> impl TypedValueParser<Value = IntegratorPreset> {
    let help = |preset| match preset {
        IntegratorPreset::Reference => {
            "No tricks: uniform direction sampling, emission counted on hit (the oracle)"
        }
        IntegratorPreset::Nee => {
            "BSDF sampling plus next event estimation with power-proportional light selection \
             and Russian roulette, no MIS"
        }
        IntegratorPreset::Mis => "`nee` plus MIS (power heuristic) between light and BSDF samples",
        IntegratorPreset::Ris => "`mis` with RIS light selection",
        IntegratorPreset::Auto => {
            "The best of these for the scene, leaving out what it does not need, with caustics \
             by light tracing where they apply (see --light-tracing). Also called `path`, \
             Mitsuba's name for its integrator"
        }
    };
    PossibleValuesParser::new(IntegratorPreset::ALL.map(|preset| {
        let aliases = IntegratorPreset::ALIASES
            .into_iter()
            .filter(move |&(_, named)| named == preset)
            .map(|(alias, _)| alias);
        PossibleValue::new(preset.name())
            .help(help(preset))
            .aliases(aliases)
    }))
    .map(|name| {
        name.parse::<IntegratorPreset>()
            .expect("clap checked the name")
    })
}

/// `--sampler`'s values: [`SamplerKind`]'s names, each with its summary as help, parsed by its
/// [`FromStr`](std::str::FromStr).
fn sampler_kind() -> impl TypedValueParser<Value = SamplerKind> {
    PossibleValuesParser::new(
        SamplerKind::ALL.map(|kind| PossibleValue::new(kind.name()).help(kind.summary())),
    )
    .map(|name| name.parse::<SamplerKind>().expect("clap checked the name"))
}

/// An on/off switch (`--rr on|off`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Switch {
    /// Enabled.
    On,
    /// Disabled.
    Off,
}

impl Switch {
    /// Whether the switch is on.
    pub fn is_on(self) -> bool {
        self == Self::On
    }
}

/// How next event estimation chooses the light it samples (`--lights`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LightsFlag {
    /// Every light equally likely.
    Uniform,
    /// In proportion to the lights' emitted power.
    Power,
    /// Resampled importance sampling: 4 candidates drawn by power, one kept by the light it
    /// could bring to the shading point.
    Ris,
    /// No choice: a sample of every light at every vertex, one shadow ray per light.
    All,
}

impl LightsFlag {
    /// The light selection this flag names.
    pub fn selection(self) -> integrators::LightSelection {
        use integrators::LightSelection;
        match self {
            Self::Uniform => LightSelection::Uniform,
            Self::Power => LightSelection::Power,
            Self::Ris => LightSelection::Ris {
                candidates: crate::plan::RIS_CANDIDATES,
            },
            Self::All => LightSelection::All,
        }
    }
}

/// `strata render`: flags override the scene file's settings; absent flags keep them.
#[derive(Debug, Args, PartialEq)]
pub struct RenderArgs {
    /// The Mitsuba 3 XML scene file.
    pub scene: PathBuf,
    /// Output image: linear RGB float32 OpenEXR, top row first; written whole or not at all.
    /// Default: the scene file's name with the extension `.exr`, in the working directory
    /// (see [`RenderArgs::out_path`]).
    #[arg(short, long, value_name = "OUT.exr")]
    pub out: Option<PathBuf>,
    /// Samples per pixel (1 to 2^24); with --time, whichever limit comes first stops. With
    /// --resume, the total including the resumed samples.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=i64::from(scene::limits::MAX_SAMPLE_COUNT)))]
    pub spp: Option<u32>,
    /// Rendering time budget in seconds (fractions allowed); stops at a pass boundary. Ctrl-C
    /// also stops at the next pass boundary and writes the image of the samples done so far
    /// (exit status 130); a second Ctrl-C quits at once without writing.
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    pub time: Option<f64>,
    /// Integrator preset; default: the scene's `<integrator type>` where it names a preset,
    /// else auto
    #[arg(long, value_parser = integrator_preset())]
    pub integrator: Option<IntegratorPreset>,
    /// Sample generator; default from the scene's sampler.
    #[arg(long, value_parser = sampler_kind())]
    pub sampler: Option<SamplerKind>,
    /// Russian roulette on or off, on top of the preset.
    #[arg(long, value_enum)]
    pub rr: Option<Switch>,
    /// How next event estimation chooses its light, over the preset's: in proportion to
    /// power, uniformly, by RIS, or `all` (a sample of every light at every vertex). `auto`
    /// measures these on the scene unless this is given.
    #[arg(long, value_enum)]
    pub lights: Option<LightsFlag>,
    /// Adaptive sampling (`on` when given without a value): a pilot render (1/16 of the
    /// budget, 2 to 16 samples per pixel, not part of the image) estimates each pixel's
    /// relative noise, and pixels get samples in proportion to it, which minimises the relative
    /// MSE. --spp is then the mean over pixels, the pilot's samples included. `auto` turns it on
    /// by itself wherever the budget pays for the pilot (32 spp or more, or a time budget),
    /// other presets only when asked. Not with --state or --resume.
    #[arg(long, value_enum, value_name = "on|off", num_args = 0..=1, default_missing_value = "on",
          conflicts_with_all = ["state", "resume"])]
    pub adaptive: Option<Switch>,
    /// Caustics by light tracing: light seen on a diffuse or glossy surface after mirrors or
    /// glass (light → specular → surface → camera) is traced from the lights and connected to
    /// the camera instead of being found by chance, splatting into the pixels the filter
    /// reaches (through a sampled aperture point with a thin lens). Needs a delta BSDF and an
    /// area light, and emitters not hidden (`hide_emitters`); ignored otherwise.
    /// `auto` turns it on where it applies (and measures one light path per 4 samples against
    /// one per sample); with another preset, this flag does. N: camera samples per light path
    /// (one sample in N also traces one; 1 when no value is given).
    #[arg(long, value_name = "N", num_args = 0..=1, default_missing_value = "1",
          value_parser = clap::value_parser!(u32).range(1..=64))]
    pub light_tracing: Option<u32>,
    /// Delta splitting on or off: where the camera sees glass or a smooth plastic (directly or
    /// through mirrors and glass), the light seen through each of its delta lobes by a ray of
    /// its own, instead of through the one lobe a path chooses. `auto` turns it on where such
    /// materials are; other presets only when asked.
    #[arg(long, value_enum, value_name = "on|off", num_args = 0..=1, default_missing_value = "on")]
    pub delta_splitting: Option<Switch>,
    /// Path reuse: connect each pixel's first path vertex to the second vertices of the other
    /// paths of its BLOCK × BLOCK pixel block (2 or 4; 4 when no value is given), where both
    /// are diffuse (not with light tracing). `auto` turns 4 × 4 blocks on where they pay;
    /// `off` keeps it off.
    #[arg(long, value_name = "BLOCK", num_args = 0..=1, default_missing_value = "4",
          value_parser = reuse_block)]
    pub path_reuse: Option<ReuseFlag>,
    /// Maximum number of path vertices after the camera, as in Mitsuba (1: emitters seen
    /// directly; 2: adds direct lighting).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub max_depth: Option<u32>,
    /// Seed of the sample generator.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Rendering threads (default: all cores).
    #[arg(short, long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub threads: Option<u32>,
    /// Image width in pixels (with --height).
    #[arg(long, value_name = "W", requires = "height", value_parser = clap::value_parser!(u32).range(1..))]
    pub width: Option<u32>,
    /// Image height in pixels (with --width).
    #[arg(long, value_name = "H", requires = "width", value_parser = clap::value_parser!(u32).range(1..))]
    pub height: Option<u32>,
    /// Also write an 8-bit sRGB PNG preview.
    #[arg(long, value_name = "OUT.png")]
    pub png: Option<PathBuf>,
    /// Exposure of the PNG preview in stops: its pixels are sRGB(linear × 2^STOPS). The EXR
    /// is not affected.
    #[arg(long, value_name = "STOPS", default_value_t = 0.0, allow_hyphen_values = true,
          value_parser = parse_exposure)]
    pub exposure: f32,
    /// Also write render statistics as JSON.
    #[arg(long, value_name = "OUT.json")]
    pub stats: Option<PathBuf>,
    /// Also save the render's state (every pixel's sums, the samples done, the settings) to
    /// STATE when it ends or is interrupted, for --resume. Written atomically.
    #[arg(long, value_name = "STATE")]
    pub state: Option<PathBuf>,
    /// Continue the render saved in STATE (by --state) up to --spp (a total) or for --time
    /// more seconds; the result has the same bits as one uninterrupted render. The scene file
    /// and every setting that changes sample values (integrator, sampler, seed, size) must be
    /// the same as when STATE was saved.
    #[arg(long, value_name = "STATE")]
    pub resume: Option<PathBuf>,
    /// Set the scene's parameter `$NAME` to VALUE, over its `<default name="NAME">`, as
    /// Mitsuba's `-D NAME=VALUE` does (repeatable). A name no attribute of the scene uses is an
    /// error.
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    pub defines: Vec<(String, String)>,
    /// Render only the sample indices START..END (END excluded) of the render that --spp N
    /// makes (N is --spp, or END without it): a piece of one render split over processes or
    /// machines, which `strata merge` adds up into that render's very image. Not with --time,
    /// --adaptive, --state or --resume.
    #[arg(long, value_name = "START..END", value_parser = crate::shard::parse_sample_range,
          conflicts_with_all = ["time", "adaptive", "state", "resume"])]
    pub samples: Option<std::ops::Range<u32>>,
    /// Print nothing on success: no progress bar and no summary line (warnings and errors
    /// still go to standard error).
    #[arg(short, long)]
    pub quiet: bool,
}

impl RenderArgs {
    /// The image file to write: `--out`, or else the scene file's name with the extension
    /// `.exr` in the working directory (`scenes/cbox.xml` → `cbox.exr`), as Mitsuba names its
    /// output. `None` when the scene path has no file name to take (e.g. `..`).
    pub fn out_path(&self) -> Option<PathBuf> {
        match &self.out {
            Some(out) => Some(out.clone()),
            None => self.scene.file_stem().map(|stem| {
                // Not `with_extension`, which would also drop a dotted stem's last part.
                let mut name = stem.to_os_string();
                name.push(".exr");
                PathBuf::from(name)
            }),
        }
    }
}

/// `strata merge`.
#[derive(Debug, Args, PartialEq)]
pub struct MergeArgs {
    /// The EXR images to merge, as written by `strata render` or `strata merge` (with the sums
    /// and the "strata" header they record).
    #[arg(required = true, num_args = 1.., value_name = "IN.exr")]
    pub inputs: Vec<PathBuf>,
    /// The merged image (linear RGB float32 OpenEXR, with the sums and the union of the sample
    /// ranges, so it can be merged again).
    #[arg(long, value_name = "OUT.exr")]
    pub out: PathBuf,
    /// Also write an 8-bit sRGB PNG preview.
    #[arg(long, value_name = "OUT.png")]
    pub png: Option<PathBuf>,
    /// Exposure of the PNG preview in stops: its pixels are sRGB(linear × 2^STOPS). The EXR
    /// is not affected.
    #[arg(long, value_name = "STOPS", default_value_t = 0.0, allow_hyphen_values = true,
          value_parser = parse_exposure)]
    pub exposure: f32,
}

/// `strata diff`.
#[derive(Debug, Args, PartialEq)]
pub struct DiffArgs {
    /// The image to assess.
    pub a: PathBuf,
    /// The reference image (the denominator of relmse).
    pub b: PathBuf,
}

/// Parses a positive, finite number of seconds.
fn parse_seconds(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(s) if s.is_finite() && s > 0.0 => Ok(s),
        Ok(_) => Err(format!(
            "'{text}' is not a positive, finite number of seconds"
        )),
        Err(e) => Err(format!("'{text}' is not a number: {e}")),
    }
}

/// Largest exposure magnitude in stops: 2^±64 is far beyond any useful preview and well
/// inside `f32`'s range, so the scale factor is always finite and non-zero.
pub const MAX_EXPOSURE_STOPS: f32 = 64.0;

/// Parses an exposure in stops: a finite number of magnitude at most [`MAX_EXPOSURE_STOPS`].
fn parse_exposure(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(stops) if stops.is_finite() && stops.abs() <= MAX_EXPOSURE_STOPS => Ok(stops),
        Ok(_) => Err(format!(
            "'{text}' is not a finite number of stops from -{MAX_EXPOSURE_STOPS} to \
             {MAX_EXPOSURE_STOPS}"
        )),
        Err(e) => Err(format!("'{text}' is not a number of stops: {e}")),
    }
}

/// Splits a `-D` argument at its first `=` into a parameter name (letters, digits and `_`, as
/// `$name` references take) and its value.
fn parse_define(text: &str) -> Result<(String, String), String> {
    let Some((name, value)) = text.split_once('=') else {
        return Err(format!("'{text}' is not NAME=VALUE"));
    };
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(format!(
            "'{name}' is not a parameter name (letters, digits and _)"
        ));
    }
    Ok((name.to_string(), value.to_string()))
}

/// What `--path-reuse` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReuseFlag {
    /// No path reuse, even with `auto`.
    Off,
    /// Blocks of this edge in pixels (2 or 4, which divide every tile size).
    Block(u32),
}

/// Parses a `--path-reuse` value: `off`, 2 or 4.
fn reuse_block(value: &str) -> Result<ReuseFlag, String> {
    match value {
        "off" => Ok(ReuseFlag::Off),
        "2" => Ok(ReuseFlag::Block(2)),
        "4" => Ok(ReuseFlag::Block(4)),
        other => Err(format!("{other} is not off, 2 or 4")),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    /// Parses `strata` followed by `args`.
    fn parse(args: &[&str]) -> Result<Cli, clap::Error> {
        Cli::try_parse_from(std::iter::once("strata").chain(args.iter().copied()))
    }

    /// The render arguments of a command line that must parse.
    fn render_args(args: &[&str]) -> RenderArgs {
        match parse(args).unwrap().command {
            Command::Render(r) => r,
            other => panic!("not a render command: {other:?}"),
        }
    }

    #[test]
    fn path_reuse_takes_off_or_an_optional_block_edge_of_2_or_4() {
        fn with<'a>(extra: &[&'a str]) -> Vec<&'a str> {
            [&["render", "s.xml", "--out", "o.exr"][..], extra].concat()
        }
        let reuse = |extra: &[&str]| render_args(&with(extra)).path_reuse;
        assert_eq!(reuse(&[]), None);
        assert_eq!(reuse(&["--path-reuse"]), Some(ReuseFlag::Block(4)));
        assert_eq!(reuse(&["--path-reuse", "2"]), Some(ReuseFlag::Block(2)));
        assert_eq!(reuse(&["--path-reuse=4"]), Some(ReuseFlag::Block(4)));
        assert_eq!(reuse(&["--path-reuse", "off"]), Some(ReuseFlag::Off));
        let refused = parse(&with(&["--path-reuse", "3"])).unwrap_err();
        assert!(
            refused.to_string().contains("3 is not off, 2 or 4"),
            "{refused}"
        );
    }

    #[test]
    fn the_full_flag_set_parses() {
        let r = render_args(&[
            "render",
            "scene.xml",
            "--out",
            "o.exr",
            "--spp",
            "64",
            "--time",
            "0.5",
            "--integrator",
            "mis",
            "--sampler",
            "bluenoise",
            "--rr",
            "off",
            "--max-depth",
            "8",
            "--seed",
            "7",
            "--threads",
            "2",
            "--width",
            "320",
            "--height",
            "240",
            "--png",
            "o.png",
            "--stats",
            "s.json",
            "--adaptive",
            "--light-tracing",
        ]);
        assert_eq!(r.scene, Path::new("scene.xml"));
        assert!(r.adaptive == Some(Switch::On) && r.light_tracing == Some(1));
        assert_eq!(r.out.as_deref(), Some(Path::new("o.exr")));
        assert_eq!((r.spp, r.time), (Some(64), Some(0.5)));
        assert_eq!(r.integrator, Some(IntegratorPreset::Mis));
        assert_eq!(r.sampler, Some(SamplerKind::BlueNoise));
        assert_eq!(r.rr, Some(Switch::Off));
        assert!(!Switch::Off.is_on() && Switch::On.is_on());
        assert_eq!(
            (r.max_depth, r.seed, r.threads),
            (Some(8), Some(7), Some(2))
        );
        assert_eq!((r.width, r.height), (Some(320), Some(240)));
        assert_eq!(r.png.as_deref(), Some(Path::new("o.png")));
        assert_eq!(r.stats.as_deref(), Some(Path::new("s.json")));
    }

    #[test]
    fn defaults_leave_the_scene_in_charge() {
        let r = render_args(&["render", "s.xml", "--out", "o.exr"]);
        assert_eq!(r.integrator, None);
        assert_eq!(
            (r.spp, r.time, r.sampler, r.rr, r.max_depth, r.seed),
            (None, None, None, None, None, None)
        );
        assert_eq!(
            (r.threads, r.width, r.height, r.png, r.stats),
            (None, None, None, None, None)
        );
        assert_eq!((r.state, r.resume), (None, None));
        assert!(r.adaptive.is_none() && r.light_tracing.is_none() && !r.quiet);
        assert_eq!(r.exposure, 0.0);
    }

    #[test]
    fn without_out_the_image_is_named_after_the_scene_in_the_working_directory() {
        let r = render_args(&["render", "scenes/cbox.xml"]);
        assert_eq!(r.out, None);
        assert_eq!(r.out_path(), Some(PathBuf::from("cbox.exr")));
        let dotted = render_args(&["render", "/tmp/a.b/veach.mis.xml"]);
        assert_eq!(dotted.out_path(), Some(PathBuf::from("veach.mis.exr")));
        let given = render_args(&["render", "scenes/cbox.xml", "--out", "x/y.exr"]);
        assert_eq!(given.out_path(), Some(PathBuf::from("x/y.exr")));
        assert_eq!(render_args(&["render", ".."]).out_path(), None);
    }

    #[test]
    fn short_flags_are_the_long_ones() {
        let r = render_args(&["render", "s.xml", "-o", "o.exr", "-t", "3", "-q"]);
        assert_eq!(r.out.as_deref(), Some(Path::new("o.exr")));
        assert_eq!(r.threads, Some(3));
        assert!(r.quiet);
        let long = render_args(&[
            "render",
            "s.xml",
            "--out",
            "o.exr",
            "--threads",
            "3",
            "--quiet",
        ]);
        assert_eq!(r, long);
    }

    #[test]
    fn path_is_another_name_for_auto() {
        let r = render_args(&["render", "s.xml", "--integrator", "path"]);
        assert_eq!(r.integrator, Some(IntegratorPreset::Auto));
        // The alias is not a sixth preset: the help lists the five names.
        use clap::CommandFactory;
        let command = Cli::command();
        let render = command.find_subcommand("render").expect("render");
        let argument = render
            .get_arguments()
            .find(|a| a.get_id() == "integrator")
            .expect("--integrator");
        let names: Vec<String> = argument
            .get_possible_values()
            .iter()
            .filter(|v| !v.is_hide_set())
            .map(|v| v.get_name().to_string())
            .collect();
        assert_eq!(names, ["reference", "nee", "mis", "ris", "auto"]);
    }

    #[test]
    fn exposure_takes_finite_stops_of_either_sign() {
        let exposure = |value: &str| {
            parse(&["render", "s.xml", "--exposure", value]).map(|cli| match cli.command {
                Command::Render(r) => r.exposure,
                other => panic!("not a render command: {other:?}"),
            })
        };
        assert_eq!(exposure("1").unwrap(), 1.0);
        assert_eq!(exposure("-2.5").unwrap(), -2.5);
        assert_eq!(exposure("64").unwrap(), 64.0);
        for bad in ["NaN", "inf", "-inf", "64.5", "1e9", "bright"] {
            let error = exposure(bad).expect_err(&format!("--exposure {bad} must not parse"));
            assert_eq!(error.exit_code(), 2, "{bad}: {error}");
            assert!(error.to_string().contains(bad), "{bad}: {error}");
        }
        let merge = parse(&["merge", "a.exr", "--out", "m.exr", "--exposure", "-1"]).unwrap();
        assert!(
            matches!(
                merge.command,
                Command::Merge(MergeArgs { exposure: -1.0, .. })
            ),
            "{merge:?}"
        );
    }

    #[test]
    fn state_resume_and_merge_parse() {
        let r = render_args(&[
            "render", "s.xml", "--out", "o.exr", "--state", "a.state", "--resume", "b.state",
        ]);
        assert_eq!(r.state.as_deref(), Some(Path::new("a.state")));
        assert_eq!(r.resume.as_deref(), Some(Path::new("b.state")));
        let cli = parse(&["merge", "a.exr", "b.exr", "c.exr", "--out", "m.exr"]).unwrap();
        assert_eq!(
            cli.command,
            Command::Merge(MergeArgs {
                inputs: vec!["a.exr".into(), "b.exr".into(), "c.exr".into()],
                out: "m.exr".into(),
                png: None,
                exposure: 0.0,
            })
        );
        assert!(parse(&["merge", "--out", "m.exr"]).is_err());
        assert!(parse(&["merge", "a.exr"]).is_err());
    }

    #[test]
    fn every_preset_and_sampler_name_parses() {
        for (name, preset) in [
            ("reference", IntegratorPreset::Reference),
            ("nee", IntegratorPreset::Nee),
            ("mis", IntegratorPreset::Mis),
            ("ris", IntegratorPreset::Ris),
            ("auto", IntegratorPreset::Auto),
        ] {
            assert_eq!(
                render_args(&["render", "s.xml", "--out", "o.exr", "--integrator", name])
                    .integrator,
                Some(preset)
            );
        }
        for sampler in SamplerKind::ALL {
            assert_eq!(
                render_args(&[
                    "render",
                    "s.xml",
                    "--out",
                    "o.exr",
                    "--sampler",
                    sampler.name()
                ])
                .sampler,
                Some(sampler)
            );
        }
    }

    #[test]
    fn bad_values_are_usage_errors_with_status_2() {
        for bad in [
            &["render"][..],
            &["render", "s.xml", "-o"],
            &["render", "s.xml", "--out", "o.exr", "--time", "0"],
            &["render", "s.xml", "--out", "o.exr", "--time", "-1"],
            &["render", "s.xml", "--out", "o.exr", "--time", "NaN"],
            &["render", "s.xml", "--out", "o.exr", "--time", "soon"],
            &["render", "s.xml", "--out", "o.exr", "--spp", "0"],
            &["render", "s.xml", "--out", "o.exr", "--spp", "-4"],
            &["render", "s.xml", "--out", "o.exr", "--spp", "16777217"],
            &["render", "s.xml", "--out", "o.exr", "--integrator", "bdpt"],
            &["render", "s.xml", "--out", "o.exr", "--rr", "maybe"],
            &["render", "s.xml", "--out", "o.exr", "--threads", "0"],
            &["render", "s.xml", "--out", "o.exr", "--width", "64"],
            &["render", "s.xml", "--out", "o.exr", "--frobnicate"],
            &[
                "render",
                "s.xml",
                "--out",
                "o.exr",
                "--adaptive",
                "--state",
                "a.state",
            ],
            &[
                "render",
                "s.xml",
                "--out",
                "o.exr",
                "--adaptive",
                "--resume",
                "a.state",
            ],
            &["diff", "a.exr"],
            &["explode"],
        ] {
            let error = parse(bad).expect_err(&format!("{bad:?} must not parse"));
            assert_eq!(error.exit_code(), 2, "{bad:?}: {error}");
        }
    }

    #[test]
    fn defines_collect_in_order_split_at_the_first_equals_sign() {
        let args = render_args(&[
            "render", "s.xml", "--out", "o.exr", "-D", "spp=4", "--define", "name=a=b", "-Dempty=",
        ]);
        let pair = |n: &str, v: &str| (n.to_string(), v.to_string());
        assert_eq!(
            args.defines,
            [pair("spp", "4"), pair("name", "a=b"), pair("empty", "")]
        );
        for bad in ["spp", "=4", "s p=4", "$spp=4"] {
            let error = parse(&["render", "s.xml", "--out", "o.exr", "-D", bad])
                .expect_err(&format!("-D {bad} must not parse"));
            assert_eq!(error.exit_code(), 2, "-D {bad}: {error}");
        }
    }

    #[test]
    fn diff_takes_two_images() {
        let cli = parse(&["diff", "a.exr", "b.exr"]).unwrap();
        assert_eq!(
            cli.command,
            Command::Diff(DiffArgs {
                a: "a.exr".into(),
                b: "b.exr".into()
            })
        );
    }

    #[test]
    fn samples_take_a_range_and_exclude_time_adaptive_and_states() {
        let base = ["render", "s.xml", "--out", "o.exr", "--samples"];
        let samples = |range: &str| render_args(&[&base[..], &[range]].concat()).samples;
        assert_eq!(samples("4..12"), Some(4..12));
        assert_eq!(render_args(&base[..4]).samples, None);
        for extra in [
            &["--time", "1"][..],
            &["--adaptive"],
            &["--state", "a.state"],
            &["--resume", "a.state"],
        ] {
            let line = [&base[..], &["0..4"], extra].concat();
            let error = parse(&line).expect_err(&format!("{line:?} must not parse"));
            assert_eq!(error.exit_code(), 2, "{line:?}: {error}");
            assert!(error.to_string().contains("--samples"), "{error}");
        }
        let error = parse(&[&base[..], &["4..4"]].concat()).unwrap_err();
        assert_eq!(error.exit_code(), 2);
    }

    #[test]
    fn clap_configuration_is_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}

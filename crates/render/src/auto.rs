//! `auto`, the default integrator: the techniques a scene gets are chosen by measuring them on
//! the scene itself.
//!
//! `auto` starts from the MIS preset minus what the scene cannot use (no light sampling without
//! lights or without a non-delta BSDF, no MIS where no light can be hit, uniform light choice for
//! one light: [`crate::plan::auto_settings`]). Each technique whose payoff depends on the
//! scene is then a *trial* ([`Trials`]): RIS light selection, uniform light selection and a
//! sample of every light against power-proportional selection (two or more lights), Russian
//! roulette off against on (paths bounded beyond the roulette's start), path reuse (diffuse
//! materials), and light tracing off or sparse against on.
//!
//! Caustics by light tracing are in the base wherever they apply (a delta BSDF, an area light, a
//! camera that light paths can reach), one light path per camera sample, and the trial is to switch
//! them *off*, because a caustic path found by chance is rare (on the glass Cornell box about one
//! pilot sample in a thousand in the caustic's pixels), so a short pilot of the path tracer alone
//! mostly misses the variance it causes and would underrate the technique that removes it.
//! Switching light tracing off must therefore prove itself, like every trial, and a candidate
//! without it (light tracing off, or path reuse) is measured without those paths, with the variance
//! they add estimated from light paths instead ([`crate::caustic_variance`]): the expected
//! variance, which a few samples per pixel would mostly miss. Before that estimate, switching light
//! tracing off looked a third cheaper at no cost in noise, and `auto` rejected it where it halved
//! the error. Another trial traces one light path per four camera samples instead
//! ([`LightTracing::SPARSE`]): cheaper, where caustics are a small share of the noise.
//!
//! A
//! *technique pilot* renders a thumbnail of the image (about [`PILOT_PIXELS`] pixels) with each
//! candidate: the base, and the base with one trial switched. Each candidate is rendered twice
//! with independent seeds at [`PILOT_SPP`] samples per pixel, and
//!
//! - its relative variance is `V = mean over pixels and channels of (a − b)² / 2 / (m² + ε)`,
//!   where `a` and `b` are the two renders and `m` the mean of every candidate's renders at the
//!   pixel (so every candidate is weighed by the same denominator, that of relMSE);
//!   `(a − b)² / 2` is an unbiased estimate of a pixel's variance whatever the pixels share
//!   (light tracing splats into many pixels, path reuse correlates the pixels of a block).
//!   The two renders take the same camera samples (film position, lens point, time:
//!   [`camera_sample_seed`]), so this is the variance of the paths alone: the noise of where
//!   in a pixel (on the lens, in the shutter) a sample falls, the same for every candidate and
//!   mostly removed by the image's many stratified samples, is left out;
//! - its cost `C` is counted, not timed, so that the choice, and so the image, is the same on any
//!   machine and thread count: closest-hit rays, occlusion rays, samples and RIS candidate
//!   evaluations weighted by [`Cost`];
//! - its efficiency is `1 / (V · C)`: the lecture's figure of merit, error × time.
//!
//! A trial is kept when its efficiency beats the base's by more than 2.4 standard errors of
//! their log ratio (independent units: 4 × 4 pixel blocks, so that path reuse's correlated
//! blocks count once) and by at least 1%. A trial that looks better but not by that much is
//! *undecided*: it and the base get another round of two renders (new seeds, the same for
//! both), and the comparison is made again on all their rounds, up to [`MAX_PILOT_ROUNDS`]
//! rounds and as many renders again as the first round took, within the pilot's share of the
//! budget. 2.4 is Pocock's bound for four
//! looks: repeated looks at one comparison would otherwise stop on noise more often than one
//! look at 2 standard errors does. Heavy-tailed noise is why more rounds matter: on Veach's
//! scene one round's estimate of sampling every light ranged 0.9–1.9× the base's efficiency
//! with the pilot's seed. A trial still undecided after its last round is kept when it beats
//! the base by one standard error (`LAST_LOOK_ERRORS`): the choice is made for the lower
//! expected error, not to guard the base, since a trial no better than the base costs nothing
//! when kept, and one truly better, left undecided, costs what it would have gained. Trials
//! that exclude each other (the light selections; light tracing
//! off and path reuse) keep only the best. When
//! two or more trials are kept their combination is measured too, and the best measured
//! candidate wins. The pilot's samples are not in the image (its seeds differ from the image's),
//! so the image stays unbiased whatever is chosen; its time counts in the render's.
//!
//! A budget too small to pay for the pilot (it would take more than [`MAX_PILOT_SHARE`] of the
//! samples) keeps the base, and says so.

use crate::image::Image;
use crate::metrics::RELMSE_EPSILON;
use glam::{DVec3, Vec3};
use integrators::{LightSelection, LightTracing, PathReuse, PathSettings};
use world::RayCounters;

/// Pixels of the pilot's thumbnail, about: the image is scaled down by a whole factor until it
/// has at most this many.
pub const PILOT_PIXELS: u32 = 64 * 64;

/// The fewest thumbnail pixels a pilot is worth: below, the budget keeps the base settings.
pub const MIN_PILOT_PIXELS: u32 = 16 * 16;

/// Samples per pixel of each of a candidate's two pilot renders.
pub const PILOT_SPP: u32 = 4;

/// Most rounds of two renders a candidate gets: the first, and more for trials the first leaves
/// undecided.
pub const MAX_PILOT_ROUNDS: u32 = 4;

/// The fewest standard errors of their log ratio by which a trial's efficiency must beat the
/// base's: Pocock's constant bound for up to [`MAX_PILOT_ROUNDS`] looks at the same comparison,
/// which keeps the chance that noise alone ends the rounds with a switch near a single look's
/// 2.3%.
const SIGNIFICANT_ERRORS: f64 = 2.4;

/// The fewest standard errors of their log ratio by which a trial still undecided after its
/// last round must beat the base's efficiency to be kept. The choice is then made for the lower
/// expected error, not to guard the base: a trial equal to the base, which costs nothing either
/// way, is kept about one time in six, while one truly better by two standard errors, which the
/// 2.4-error rule leaves undecided two times in three, is kept five times in six.
const LAST_LOOK_ERRORS: f64 = 1.0;

/// The smallest gain in efficiency worth a switch (1%), as a log ratio: an identical render
/// (uniform light choice among lights of equal power) ties and keeps the base.
const MIN_LOG_GAIN: f64 = 0.01;

/// The pilot may take at most this share of a sample budget (counted in samples at the
/// image's size); a smaller budget keeps the base settings.
pub const MAX_PILOT_SHARE: f64 = 0.1;

/// Block edge of path reuse when `auto` tries it (4 × 4 blocks share the most paths).
pub const REUSE_BLOCK: u32 = 4;

/// Edge, in thumbnail pixels, of the blocks whose mean variance terms are the independent
/// units of the pilot's standard errors (path reuse correlates the pixels of a 4 × 4 block).
const UNIT_BLOCK: u32 = 4;

/// What a candidate's pilot costs, in units of one occlusion ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cost {
    /// A closest-hit ray with the shading at its hit.
    pub closest_ray: f64,
    /// A camera sample apart from its rays (camera ray set-up, sampler, film).
    pub sample: f64,
    /// One RIS candidate: a light chosen, a point sampled on it and its contribution estimated,
    /// per shadow ray of the path tracer.
    pub ris_candidate: f64,
    /// One connection of path reuse: an occlusion ray between two path vertices and two diffuse
    /// BSDF evaluations, but no light sample.
    pub reuse_connection: f64,
}

/// The costs the pilot counts with, from callgrind's instruction counts of 4-spp one-thread
/// renders of the 128 × 128 Cornell box and Veach's scene: an occlusion ray took 615 and 536
/// instructions; a closest-hit ray 828 and 580, plus the shading and sampling at its hit, about
/// 900 and 1,250 (3.0 and 3.2 occlusion rays in all); a RIS candidate 371 and 403 (0.7); a
/// camera sample's set-up and film update about 660 (1.1). A connection of path reuse took
/// 0.63–1.01 occlusion rays' instructions on four scenes (the Cornell box, `gen-7-01`,
/// `gen-9-03`, `gen-10-01`; 8 spp, one thread, callgrind, against the same render without it):
/// counted as a shadow ray, it had overrated path reuse's cost by up to 14%.
pub const COST: Cost = Cost {
    closest_ray: 3.0,
    sample: 1.0,
    ris_candidate: 0.7,
    reuse_connection: 0.8,
};

/// The techniques `auto` measures on the scene before rendering it: each `true` one is tried
/// against the base settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Trials {
    /// RIS light selection ([`crate::plan::RIS_CANDIDATES`] candidates) instead of power-proportional.
    pub ris: bool,
    /// Uniform light selection instead of power-proportional (Mitsuba's default): power
    /// overrates lights whose power mostly misses the scene, such as an environment around a
    /// large open scene, whose power grows with the scene's bounding sphere.
    pub uniform_lights: bool,
    /// A light sample of every light at every vertex instead of a choice of one
    /// ([`LightSelection::All`]; up to [`integrators::MAX_EVERY_LIGHT`] lights).
    pub every_light: bool,
    /// Russian roulette off (only where `max_depth` bounds the paths).
    pub no_roulette: bool,
    /// Caustics by light tracing off (it is in the base wherever it applies: see the module
    /// documentation).
    pub no_light_tracing: bool,
    /// One light path per [`LightTracing::SPARSE_SAMPLES_PER_PATH`] camera samples instead of
    /// one per sample ([`LightTracing::SPARSE`]): cheaper, with noisier caustics.
    pub sparse_light_paths: bool,
    /// Path reuse in [`REUSE_BLOCK`]-pixel blocks (and so light tracing off).
    pub path_reuse: bool,
}

impl Trials {
    /// Whether anything is to be measured.
    pub fn any(&self) -> bool {
        self.ris
            || self.uniform_lights
            || self.every_light
            || self.no_roulette
            || self.no_light_tracing
            || self.sparse_light_paths
            || self.path_reuse
    }

    /// The trials in their fixed order, each with its label and the settings it changes.
    fn switches(&self) -> Vec<Switch> {
        [
            (self.ris, Switch::Ris),
            (self.uniform_lights, Switch::UniformLights),
            (self.every_light, Switch::EveryLight),
            (self.no_roulette, Switch::NoRoulette),
            (self.no_light_tracing, Switch::NoLightTracing),
            (self.sparse_light_paths, Switch::SparseLightPaths),
            (self.path_reuse, Switch::PathReuse),
        ]
        .into_iter()
        .filter_map(|(on, switch)| on.then_some(switch))
        .collect()
    }
}

/// One technique switched by a trial.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Switch {
    Ris,
    UniformLights,
    EveryLight,
    NoRoulette,
    NoLightTracing,
    SparseLightPaths,
    PathReuse,
}

impl Switch {
    fn label(self) -> &'static str {
        match self {
            Switch::Ris => "+ris",
            Switch::UniformLights => "+uniform-lights",
            Switch::EveryLight => "+every-light",
            Switch::NoRoulette => "-roulette",
            Switch::NoLightTracing => "-light-tracing",
            Switch::SparseLightPaths => "+sparse-light-paths",
            Switch::PathReuse => "+path-reuse",
        }
    }

    fn apply(self, settings: PathSettings) -> PathSettings {
        match self {
            Switch::Ris => PathSettings {
                light_selection: LightSelection::Ris {
                    candidates: crate::plan::RIS_CANDIDATES,
                },
                ..settings
            },
            Switch::UniformLights => PathSettings {
                light_selection: LightSelection::Uniform,
                ..settings
            },
            Switch::EveryLight => PathSettings {
                light_selection: LightSelection::All,
                ..settings
            },
            Switch::NoRoulette => PathSettings {
                russian_roulette: None,
                ..settings
            },
            Switch::NoLightTracing => PathSettings {
                light_tracing: None,
                ..settings
            },
            Switch::SparseLightPaths => PathSettings {
                light_tracing: Some(LightTracing::SPARSE),
                ..settings
            },
            Switch::PathReuse => PathSettings {
                path_reuse: Some(PathReuse { block: REUSE_BLOCK }),
                light_tracing: None,
                ..settings
            },
        }
    }
}

/// What one candidate's pilot produced: its two independent renders (thumbnail images, splats
/// included) and the rays they traced.
#[derive(Clone, Debug, PartialEq)]
pub struct PilotRenders {
    /// The two renders, from independent seeds.
    pub images: [Image; 2],
    /// Rays traced by both renders.
    pub rays: RayCounters,
    /// Camera samples taken by both renders.
    pub samples: u64,
    /// For a candidate without light tracing whose renders leave caustic paths out: per pixel
    /// (row order) and channel, the variance those paths add to one render, estimated from
    /// light paths ([`crate::caustic_variance`]).
    pub caustic_variance: Option<Vec<Vec3>>,
}

/// One measured candidate.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// `base`, or the switched trials joined, e.g. `+ris+path-reuse`.
    pub label: String,
    /// Its settings.
    pub settings: PathSettings,
    /// Relative variance of one pilot render (mean over pixels and channels).
    pub variance: f64,
    /// Relative standard error of `variance`, from independent pixel blocks.
    pub variance_error: f64,
    /// The variance terms' means over each block (the independent units), in row order.
    units: Vec<f64>,
    /// Cost of one pilot render, in occlusion-ray units ([`Cost`]).
    pub cost: f64,
    /// Rounds of two renders measured.
    pub rounds: u32,
    /// The base's variance and cost measured on the same rounds (a trial's comparison with it);
    /// `None` for the base.
    pub base_on_same_rounds: Option<(f64, f64)>,
}

impl Measured {
    /// Efficiency, `1 / (variance × cost)`; infinite for a noiseless candidate.
    pub fn efficiency(&self) -> f64 {
        1.0 / (self.variance * self.cost)
    }

    /// Efficiency relative to the base's on the same rounds (1 for the base).
    pub fn relative_efficiency(&self) -> f64 {
        self.base_on_same_rounds
            .map_or(1.0, |(variance, cost)| self.efficiency() * variance * cost)
    }
}

/// What `auto` chose and why.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoChoice {
    /// The settings the image is rendered with.
    pub settings: PathSettings,
    /// Label of the chosen candidate (`base` when nothing was switched).
    pub label: String,
    /// Every measured candidate, in the order measured (empty when the pilot was skipped).
    pub measured: Vec<Measured>,
    /// Why no pilot ran, when none did.
    pub skipped: Option<String>,
    /// Thumbnail size of the pilot, pixels.
    pub thumbnail: (u32, u32),
}

impl AutoChoice {
    /// The base, kept without a pilot for `reason`.
    pub fn unmeasured(base: PathSettings, reason: String) -> Self {
        Self {
            settings: base,
            label: "base".to_string(),
            measured: Vec::new(),
            skipped: Some(reason),
            thumbnail: (0, 0),
        }
    }

    /// One line for logs and stats: each candidate's efficiency relative to the base, and the
    /// choice.
    pub fn reason(&self) -> String {
        if let Some(reason) = &self.skipped {
            return format!("no pilot ({reason}): base");
        }
        let Some(base) = self.measured.first() else {
            return format!("chose {}", self.label);
        };
        let figures: Vec<String> = self
            .measured
            .iter()
            .skip(1)
            .map(|m| {
                let (variance, cost) = m.base_on_same_rounds.unwrap_or((base.variance, base.cost));
                let rounds = if m.rounds > 1 {
                    format!(", {} rounds", m.rounds)
                } else {
                    String::new()
                };
                format!(
                    "{} {:.2} (variance {:.2}, cost {:.2}{rounds})",
                    m.label,
                    m.relative_efficiency(),
                    m.variance / variance,
                    m.cost / cost
                )
            })
            .collect();
        format!(
            "pilot {}x{} px, 2x{} spp each; efficiency relative to base (±{:.2}): {}; chose {}",
            self.thumbnail.0,
            self.thumbnail.1,
            PILOT_SPP,
            base.variance_error,
            figures.join(", "),
            self.label
        )
    }
}

/// `auto`'s choice of techniques, made by the technique pilot, with what the pilot cost.
#[derive(Clone, Debug, PartialEq)]
pub struct TechniquePilot {
    /// The choice and the measurements behind it.
    pub choice: AutoChoice,
    /// Wall-clock seconds the pilot took.
    pub seconds: f64,
    /// Rays the pilot traced.
    pub rays: RayCounters,
}

/// Seed of render `replica` for a render seeded with `seed`: streams apart from the image's and
/// from each other. Replicas 0 and 1 are the first round's two renders of every candidate; 2
/// and 3 serve the pilot's other needs; round `r` > 0 renders replicas `2r + 2` and `2r + 3`
/// ([`round_replicas`]). Every candidate of a round uses the same two seeds (common random
/// numbers), so that where candidates draw the same numbers their errors are alike and their
/// ratio is known better than either.
pub fn pilot_seed(seed: u32, replica: u32) -> u32 {
    sampling::rng::wang_hash(seed ^ 0x5EED_0A70 ^ (replica << 4))
}

/// Seed of the camera samples of pilot round `round` for a render seeded with `seed`: both
/// renders of a round, and every candidate, take their camera samples (film position, lens
/// point, time; independent uniform numbers) from it, so that `(a − b)² / 2` measures the noise
/// of the paths alone. The noise of where in a pixel, on the lens and in the shutter a sample
/// falls, which every candidate shares, is left out: the image's many stratified samples remove
/// most of it, and in the pilot's few samples and large thumbnail pixels it drowned what tells
/// candidates apart.
pub fn camera_sample_seed(seed: u32, round: u32) -> u32 {
    pilot_seed(seed ^ 0xF11E_0000, round_replicas(round)[0])
}

/// The replicas ([`pilot_seed`]) of the two renders of pilot round `round`.
pub fn round_replicas(round: u32) -> [u32; 2] {
    if round == 0 {
        [0, 1]
    } else {
        [2 * round + 2, 2 * round + 3]
    }
}

/// Camera samples the first round of the pilot takes per thumbnail pixel for `trials`, at most:
/// every candidate's two renders, and a combination.
pub fn pilot_samples_per_pixel(trials: &Trials) -> f64 {
    (2.0 + trials.switches().len() as f64) * 2.0 * f64::from(PILOT_SPP)
}

/// The camera samples a pilot may take for a `width × height` image rendered at `spp` samples
/// per pixel: [`MAX_PILOT_SHARE`] of the image's.
pub fn pilot_sample_share(width: u32, height: u32, spp: u32) -> f64 {
    MAX_PILOT_SHARE * f64::from(spp) * f64::from(width) * f64::from(height)
}

/// How many candidate renders (pairs of [`PILOT_SPP`]-spp renders) of further rounds the pilot
/// of `trials` on `thumbnail` may add when it may take `affordable` camera samples in all: what
/// the first round leaves, at most as many as the first round renders.
pub fn extension_renders(trials: &Trials, (width, height): (u32, u32), affordable: f64) -> usize {
    let per_render = 2.0 * f64::from(PILOT_SPP) * f64::from(width) * f64::from(height);
    let first = pilot_samples_per_pixel(trials) * f64::from(width) * f64::from(height);
    // A float's conversion saturates: an unbounded budget leaves `usize::MAX`.
    let left = ((affordable - first) / per_render).floor().max(0.0) as usize;
    left.min(first_round_renders(trials))
}

/// How many candidate renders of further rounds fit in `seconds_left` of the pilot's time when
/// the first round's renders of `trials` took `first_round_seconds`: at most as many as the
/// first round renders. Under a time budget this counts what the pilot's renders take, where
/// the thumbnail's size could only estimate it beforehand.
pub fn extension_renders_in_time(
    trials: &Trials,
    first_round_seconds: f64,
    seconds_left: f64,
) -> usize {
    let first = first_round_renders(trials);
    let per_render = first_round_seconds / first as f64;
    // NaN (no time measured, none left) and negative times leave none.
    let left = (seconds_left / per_render).floor().max(0.0) as usize;
    left.min(first)
}

/// Candidate renders (pairs of [`PILOT_SPP`]-spp renders) of the pilot's first round for
/// `trials`: the base and one per trial.
fn first_round_renders(trials: &Trials) -> usize {
    1 + trials.switches().len()
}

/// The pilot's thumbnail for a `width × height` image rendered with `trials` at `spp` samples
/// per pixel (`None`: a time budget), of at most `most_pixels` pixels: the image divided by the
/// smallest whole factor that leaves at most that many and at most [`PILOT_PIXELS`], and few
/// enough that the pilot's samples stay within [`MAX_PILOT_SHARE`] of the image's. `None` when
/// that leaves fewer than [`MIN_PILOT_PIXELS`]: the budget cannot pay for a pilot.
pub fn thumbnail_size(
    width: u32,
    height: u32,
    trials: &Trials,
    spp: Option<u32>,
    most_pixels: f64,
) -> Option<(u32, u32)> {
    let affordable = spp.map_or(f64::INFINITY, |spp| {
        pilot_sample_share(width, height, spp) / pilot_samples_per_pixel(trials)
    });
    let most = affordable.min(f64::from(PILOT_PIXELS)).min(most_pixels);
    let mut factor = 1;
    let size = |factor: u32| (width.div_ceil(factor), height.div_ceil(factor));
    while {
        let (w, h) = size(factor);
        f64::from(w) * f64::from(h) > most && w * h > 1
    } {
        factor += 1;
    }
    let (w, h) = size(factor);
    (f64::from(w) * f64::from(h) <= most && w * h >= MIN_PILOT_PIXELS).then_some((w, h))
}

/// Measures the candidates of `trials` on top of `base` with `render` (which renders a
/// candidate's two pilot images of a round, from the seeds of [`round_replicas`]) and returns
/// the best, as the module documentation describes. Further rounds render at most
/// `extension_renders()` candidates ([`extension_renders`], [`extension_renders_in_time`]),
/// asked once the first round is rendered, so that a time budget can count what it took.
pub fn choose<E>(
    base: PathSettings,
    trials: &Trials,
    thumbnail: (u32, u32),
    extension_renders: impl FnOnce() -> usize,
    mut render: impl FnMut(&PathSettings, u32) -> Result<PilotRenders, E>,
) -> Result<AutoChoice, E> {
    let switches = trials.switches();
    let mut candidates = vec![("base".to_string(), base)];
    candidates.extend(
        switches
            .iter()
            .map(|s| (s.label().to_string(), s.apply(base))),
    );
    // Each candidate's rounds of renders, the first for all.
    let mut rounds: Vec<Vec<PilotRenders>> = Vec::with_capacity(candidates.len() + 1);
    for (_, settings) in &candidates {
        rounds.push(vec![render(settings, 0)?]);
    }
    // Undecided trials and the base get more rounds, within as many renders as the first took
    // and the budget allows.
    let mut renders_left = extension_renders().min(candidates.len());
    for round in 1..MAX_PILOT_ROUNDS {
        let means = pooled_means(&rounds);
        let base_rounds = &rounds[0];
        let undecided: Vec<usize> = (1..candidates.len())
            .filter(|&i| rounds[i].len() == base_rounds.len())
            .filter(|&i| {
                let (trial, base) = compare(&candidates, &rounds, i, &means, thumbnail);
                verdict(&trial, &base, SIGNIFICANT_ERRORS) == Verdict::Undecided
            })
            .collect();
        if undecided.is_empty() || 1 + undecided.len() > renders_left {
            break;
        }
        renders_left -= 1 + undecided.len();
        for i in std::iter::once(0).chain(undecided) {
            let renders = render(&candidates[i].1, round)?;
            rounds[i].push(renders);
        }
    }
    // Each trial on all its rounds, against the base on the same rounds: the last look, where an
    // undecided trial that looks better by a standard error is kept.
    let means = pooled_means(&rounds);
    let (label, settings) = &candidates[0];
    let mut measured = vec![measure(label, *settings, &rounds[0], &means, thumbnail)];
    let mut verdicts = Vec::with_capacity(switches.len());
    for i in 1..candidates.len() {
        let (trial, base) = compare(&candidates, &rounds, i, &means, thumbnail);
        verdicts.push(verdict(&trial, &base, LAST_LOOK_ERRORS));
        measured.push(Measured {
            base_on_same_rounds: Some((base.variance, base.cost)),
            ..trial
        });
    }

    // The trials that beat the base beyond noise. Trials of one group exclude each other (two
    // light selections; light tracing off, sparse, or path reuse, which turns it off), so only
    // the best of a group stays.
    let mut kept: Vec<(Switch, f64)> = switches
        .iter()
        .zip(&verdicts)
        .zip(&measured[1..])
        .filter(|((_, verdict), _)| **verdict == Verdict::Better)
        .map(|((&s, _), m)| (s, m.relative_efficiency()))
        .collect();
    let groups: [&[Switch]; 2] = [
        &[Switch::Ris, Switch::UniformLights, Switch::EveryLight],
        &[
            Switch::NoLightTracing,
            Switch::SparseLightPaths,
            Switch::PathReuse,
        ],
    ];
    for group in groups {
        let best = kept
            .iter()
            .filter(|(s, _)| group.contains(s))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(s, _)| *s);
        kept.retain(|(s, _)| !group.contains(s) || Some(*s) == best);
    }
    // Candidates that may win: the kept trials (their index in `measured`) and their
    // combination, measured when there are two or more.
    let mut eligible: Vec<usize> = kept
        .iter()
        .filter_map(|(kept, _)| switches.iter().position(|s| s == kept))
        .map(|i| i + 1)
        .collect();
    if kept.len() >= 2 {
        let settings = kept.iter().fold(base, |s, (switch, _)| switch.apply(s));
        let label: String = kept.iter().map(|(s, _)| s.label()).collect();
        let pilot = [render(&settings, 0)?];
        let base = measure("base", base, &rounds[0][..1], &means, thumbnail);
        measured.push(Measured {
            base_on_same_rounds: Some((base.variance, base.cost)),
            ..measure(&label, settings, &pilot, &means, thumbnail)
        });
        eligible.push(measured.len() - 1);
    }
    let best = eligible
        .into_iter()
        .max_by(|&a, &b| {
            measured[a]
                .relative_efficiency()
                .total_cmp(&measured[b].relative_efficiency())
        })
        .unwrap_or(0);
    Ok(AutoChoice {
        settings: measured[best].settings,
        label: measured[best].label.clone(),
        measured,
        skipped: None,
        thumbnail,
    })
}

/// What one comparison of a trial with the base says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Verdict {
    /// More efficient beyond noise (the standard errors asked) and by at least [`MIN_LOG_GAIN`].
    Better,
    /// Looks more efficient, but not beyond noise: worth another round.
    Undecided,
    /// Not more efficient.
    Worse,
}

/// Trial `trial` (an index into `candidates`) and the base, measured on the rounds the trial
/// has, for [`verdict`].
fn compare(
    candidates: &[(String, PathSettings)],
    rounds: &[Vec<PilotRenders>],
    trial: usize,
    means: &[[f64; 3]],
    thumbnail: (u32, u32),
) -> (Measured, Measured) {
    let n = rounds[trial].len();
    let measured = |i: usize| {
        let (label, settings) = &candidates[i];
        measure(label, *settings, &rounds[i][..n], means, thumbnail)
    };
    (measured(trial), measured(0))
}

/// How `candidate`'s efficiency compares with `base`'s, both measured on the same rounds, when it
/// must beat it by `errors` standard errors. The noise is the standard error of the log ratio of
/// the two variances' block means, paired block by block (the delta method): both were rendered
/// from the same seeds, so their blocks' errors are correlated, and the covariance narrows the
/// ratio's error.
fn verdict(candidate: &Measured, base: &Measured, errors: f64) -> Verdict {
    let ratio = candidate.efficiency() / base.efficiency();
    if !ratio.is_finite() || ratio == 0.0 {
        // A noiseless candidate against a noisy base wins; a noisy one against a noiseless base
        // loses; two noiseless ones tie (the base stays).
        return if candidate.variance == 0.0 && base.variance > 0.0 {
            Verdict::Better
        } else {
            Verdict::Worse
        };
    }
    let gain = ratio.ln();
    if gain <= MIN_LOG_GAIN {
        Verdict::Worse
    } else if gain > errors * log_ratio_error(&candidate.units, &base.units) {
        Verdict::Better
    } else {
        Verdict::Undecided
    }
}

/// Standard error of `ln(mean(a) / mean(b))` for paired units `a` and `b` (delta method).
fn log_ratio_error(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len()) as f64;
    if n < 2.0 {
        return f64::INFINITY;
    }
    let mean = |x: &[f64]| x.iter().sum::<f64>() / n;
    let (ma, mb) = (mean(a), mean(b));
    let (mut vaa, mut vbb, mut vab) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        vaa += (x - ma) * (x - ma);
        vbb += (y - mb) * (y - mb);
        vab += (x - ma) * (y - mb);
    }
    let scale = 1.0 / ((n - 1.0) * n);
    let variance = scale * (vaa / (ma * ma) + vbb / (mb * mb) - 2.0 * vab / (ma * mb));
    variance.max(0.0).sqrt()
}

/// Per pixel and channel, the mean of every render of every candidate, every round.
fn pooled_means(rounds: &[Vec<PilotRenders>]) -> Vec<[f64; 3]> {
    let images: Vec<&Image> = rounds.iter().flatten().flat_map(|r| &r.images).collect();
    let count = images.len() as f64;
    (0..images[0].data.len())
        .map(|i| {
            let mut sum = [0.0; 3];
            for image in &images {
                let value = image.data[i].as_dvec3();
                sum[0] += value.x;
                sum[1] += value.y;
                sum[2] += value.z;
            }
            sum.map(|s| s / count)
        })
        .collect()
}

/// The relative variance, its standard error and the cost of one candidate's pilot render,
/// from its `rounds` (one or more).
fn measure(
    label: &str,
    settings: PathSettings,
    rounds: &[PilotRenders],
    means: &[[f64; 3]],
    (width, height): (u32, u32),
) -> Measured {
    // Per pixel and channel, (a − b)² / 2 estimates a render's variance, averaged over the
    // rounds; the variance of the caustic paths the renders leave out, where they do, is added.
    let unseen = rounds[0].caustic_variance.as_deref();
    let per_round = 1.0 / rounds.len() as f64;
    let term = |i: usize| -> f64 {
        let mut variance = unseen.map_or(DVec3::ZERO, |v| v[i].as_dvec3());
        for pilot in rounds {
            let [a, b] = &pilot.images;
            let d = a.data[i].as_dvec3() - b.data[i].as_dvec3();
            variance += d * d / 2.0 * per_round;
        }
        let m = means[i];
        (variance.x / (m[0] * m[0] + RELMSE_EPSILON)
            + variance.y / (m[1] * m[1] + RELMSE_EPSILON)
            + variance.z / (m[2] * m[2] + RELMSE_EPSILON))
            / 3.0
    };
    // Block means are the independent units.
    let mut units = Vec::new();
    for by in (0..height).step_by(UNIT_BLOCK as usize) {
        for bx in (0..width).step_by(UNIT_BLOCK as usize) {
            let (mut sum, mut count) = (0.0, 0.0);
            for y in by..(by + UNIT_BLOCK).min(height) {
                for x in bx..(bx + UNIT_BLOCK).min(width) {
                    sum += term((y * width + x) as usize);
                    count += 1.0;
                }
            }
            units.push(sum / count);
        }
    }
    let n = units.len() as f64;
    let variance = units.iter().sum::<f64>() / n;
    let spread = units.iter().map(|u| (u - variance).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    let variance_error = if variance > 0.0 {
        (spread / n).sqrt() / variance
    } else {
        0.0
    };
    // Light evaluations beyond the one a vertex's shading includes: RIS's candidates, and with
    // every light sampled one per shadow ray.
    let ris_candidates = match settings.light_selection {
        LightSelection::Ris { candidates } => f64::from(candidates),
        LightSelection::All => 1.0,
        _ => 0.0,
    };
    let cost = rounds
        .iter()
        .map(|pilot| {
            let rays = pilot.rays;
            let light_samples = rays.shadow_rays - rays.connection_rays;
            COST.closest_ray * rays.rays as f64
                + (1.0 + COST.ris_candidate * ris_candidates) * light_samples as f64
                + COST.reuse_connection * rays.connection_rays as f64
                + COST.sample * pilot.samples as f64
        })
        .sum::<f64>()
        / (2.0 * rounds.len() as f64);
    Measured {
        label: label.to_string(),
        settings,
        variance,
        variance_error,
        cost,
        units,
        rounds: rounds.len() as u32,
        base_on_same_rounds: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use integrators::{LightTracing, RussianRoulette};

    const SIZE: (u32, u32) = (16, 16);

    fn base() -> PathSettings {
        PathSettings {
            max_depth: Some(8),
            sample_lights: true,
            russian_roulette: Some(RussianRoulette { start_depth: 5 }),
            ..PathSettings::default()
        }
    }

    /// [`choose`] on a thumbnail of [`SIZE`] with no limit on further rounds.
    fn choose_unbounded<E>(
        base: PathSettings,
        trials: &Trials,
        render: impl FnMut(&PathSettings, u32) -> Result<PilotRenders, E>,
    ) -> Result<AutoChoice, E> {
        choose(base, trials, SIZE, || usize::MAX, render)
    }

    /// Two renders whose pixels are 1 ± `spread` (independent per pixel, from `seed`), at cost
    /// `rays` closest-hit rays.
    fn renders(spread: f32, rays: u64, seed: u32) -> PilotRenders {
        let mut state = seed.wrapping_mul(2_654_435_761).max(1);
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            if state & 1 == 0 { 1.0 } else { -1.0 }
        };
        let pixels = (SIZE.0 * SIZE.1) as usize;
        let mut image = || Image {
            width: SIZE.0,
            height: SIZE.1,
            data: (0..pixels)
                .map(|_| Vec3::splat(1.0 + spread * next()))
                .collect(),
        };
        PilotRenders {
            images: [image(), image()],
            rays: RayCounters {
                rays,
                ..RayCounters::default()
            },
            samples: 0,
            caustic_variance: None,
        }
    }

    #[test]
    fn a_trial_that_halves_the_variance_at_the_same_cost_is_kept() {
        let trials = Trials {
            ris: true,
            path_reuse: true,
            ..Trials::default()
        };
        let choice = choose_unbounded(base(), &trials, |s, round| {
            Ok::<_, ()>(if s.path_reuse.is_some() {
                renders(0.1 / 2f32.sqrt(), 100, 2 + 16 * round)
            } else {
                renders(0.1, 100, 1 + 16 * round)
            })
        })
        .unwrap();
        assert_eq!(choice.label, "+path-reuse");
        assert!(choice.settings.path_reuse.is_some());
        assert_eq!(choice.settings.light_selection, LightSelection::Power);
        let gain = choice.measured[2].efficiency() / choice.measured[0].efficiency();
        assert!((gain - 2.0).abs() < 0.5, "efficiency gain {gain}");
    }

    #[test]
    fn a_trial_with_lower_variance_but_higher_cost_is_refused() {
        // Variance halved for four times the cost: half as efficient.
        let trials = Trials {
            path_reuse: true,
            ..Trials::default()
        };
        let choice = choose_unbounded(base(), &trials, |s, round| {
            Ok::<_, ()>(if s.path_reuse.is_some() {
                renders(0.1 / 2f32.sqrt(), 400, 2 + 16 * round)
            } else {
                renders(0.1, 100, 1 + 16 * round)
            })
        })
        .unwrap();
        assert_eq!(choice.label, "base");
        assert_eq!(choice.settings, base());
    }

    /// Of 400 seeded pilots of one trial (RIS) at `ratio` times the base's variance and the same
    /// cost, how many keep the trial.
    fn pilots_keeping_a_trial(ratio: f32) -> u32 {
        let trials = Trials {
            ris: true,
            ..Trials::default()
        };
        (0..400)
            .filter(|seed| {
                let choice = choose_unbounded(base(), &trials, |s, round| {
                    let ris = s.light_selection != LightSelection::Power;
                    let spread = if ris { 0.1 * ratio.sqrt() } else { 0.1 };
                    let seed = seed * 2 + u32::from(ris) + 1 + 1000 * round;
                    Ok::<_, ()>(renders(spread, 100, seed))
                })
                .unwrap();
                choice.label != "base"
            })
            .count() as u32
    }

    #[test]
    fn a_trial_no_better_than_the_base_is_kept_at_most_one_time_in_six() {
        // Noise alone keeps a trial when its last look beats the base by a standard error (about
        // 16% of pilots) or an earlier one by 2.4 (about 2% more). Binomial tails at that rate:
        // 90 or more of 400 has probability 0.2%, and a trial worse by a tenth (kept about 1.5%
        // of the time) reaches 16 with probability below 1e-4. Choosing by the estimate alone
        // keeps the equal trial in about a third of the pilots.
        let equal = pilots_keeping_a_trial(1.0);
        assert!(equal < 90, "equal trial kept in {equal} of 400 pilots");
        let worse = pilots_keeping_a_trial(1.1);
        assert!(
            worse < 16,
            "trial at 1.1x the variance kept in {worse} of 400 pilots"
        );
    }

    #[test]
    fn a_trial_better_by_a_tenth_is_kept_in_most_pilots() {
        // At 0.9 times the base's variance one round's gain is about two standard errors: the
        // last look keeps it about 73% of the time, a 2.4-error rule alone only about 32%. Below
        // 240 of 400 (60%) has a binomial probability under 1e-6 at 73%.
        let kept = pilots_keeping_a_trial(0.9);
        assert!(
            kept >= 240,
            "trial at 0.9x the variance kept in {kept} of 400 pilots"
        );
    }

    #[test]
    fn an_undecided_trial_gets_more_rounds_and_a_worse_one_none() {
        // RIS at 0.8 of the base's variance, the same cost: a gain of about 2.5 standard errors
        // of one round's log ratio, which one round often leaves undecided and three decide.
        // Roulette off and path reuse at 1.5 times the variance are worse and get no more
        // rounds. Four renders in the first round allow two more rounds of two.
        let trials = Trials {
            ris: true,
            no_roulette: true,
            path_reuse: true,
            ..Trials::default()
        };
        let (mut chosen, mut extended) = (0, 0);
        for seed in 0..20 {
            let mut calls = 0;
            let choice = choose_unbounded(base(), &trials, |s, round| {
                calls += 1;
                let ris = s.light_selection != LightSelection::Power;
                let worse = s.russian_roulette.is_none() || s.path_reuse.is_some();
                let spread = match (ris, worse) {
                    (false, false) => 0.1,
                    (true, false) => 0.1 * 0.8f32.sqrt(),
                    (false, true) => 0.1 * 1.5f32.sqrt(),
                    (true, true) => unreachable!("no combination is kept"),
                };
                let which = u32::from(ris)
                    + 2 * u32::from(s.russian_roulette.is_none())
                    + 4 * u32::from(s.path_reuse.is_some());
                Ok::<_, ()>(renders(spread, 100, 1 + seed * 8 + which + 400 * round))
            })
            .unwrap();
            let [base, ris, roulette, reuse] = &choice.measured[..] else {
                panic!("seed {seed}: {}", choice.reason());
            };
            assert_eq!(roulette.rounds, 1, "seed {seed}: {}", choice.reason());
            assert_eq!(reuse.rounds, 1, "seed {seed}: {}", choice.reason());
            assert_eq!(base.rounds, ris.rounds, "seed {seed}: {}", choice.reason());
            // The first round's four renders may be followed by at most four more.
            assert!(calls <= 8, "seed {seed}: {calls} renders");
            chosen += u32::from(choice.label == "+ris");
            extended += u32::from(ris.rounds > 1);
        }
        // One round decides about half the pilots; with more rounds nearly all should choose RIS.
        assert!(chosen >= 17, "RIS chosen in {chosen} of 20");
        assert!(extended >= 3, "{extended} of 20 pilots took more rounds");
    }

    #[test]
    fn further_rounds_take_what_the_first_leaves_of_the_budget() {
        let one = Trials {
            ris: true,
            ..Trials::default()
        };
        // The first round of 64 x 64 pixels takes 24 samples per pixel; a render 8.
        let first = 24.0 * 4096.0;
        assert_eq!(extension_renders(&one, (64, 64), first), 0);
        assert_eq!(extension_renders(&one, (64, 64), first + 8.0 * 4096.0), 1);
        // At most as many as the first round renders (base and trial).
        assert_eq!(extension_renders(&one, (64, 64), 10.0 * first), 2);
        assert_eq!(extension_renders(&one, (64, 64), f64::INFINITY), 2);
        assert_eq!(extension_renders(&one, (64, 64), 0.0), 0);
    }

    #[test]
    fn a_connection_of_path_reuse_costs_less_than_a_light_sample() {
        let pilot = |shadow_rays, connection_rays| PilotRenders {
            rays: RayCounters {
                rays: 10,
                shadow_rays,
                connection_rays,
            },
            ..renders(0.1, 10, 1)
        };
        let cost = |p: PilotRenders| measure("x", base(), &[p], &[[1.0; 3]; 256], SIZE).cost;
        // Ten closest-hit rays (30 units) and forty occlusion rays, twenty of them connections.
        let light_samples_only = cost(pilot(40, 0));
        let with_connections = cost(pilot(40, 20));
        assert_eq!(light_samples_only, (30.0 + 40.0) / 2.0);
        assert_eq!(
            with_connections,
            (30.0 + 20.0 + 20.0 * COST.reuse_connection) / 2.0
        );
        assert!(with_connections < light_samples_only);
    }

    #[test]
    fn further_rounds_in_time_take_what_the_first_round_leaves() {
        let two = Trials {
            ris: true,
            no_roulette: true,
            ..Trials::default()
        };
        // Three renders (base and two trials) took 0.3 s: 0.1 s a render.
        assert_eq!(extension_renders_in_time(&two, 0.3, 0.25), 2);
        assert_eq!(extension_renders_in_time(&two, 0.3, 0.05), 0);
        // At most as many as the first round renders.
        assert_eq!(extension_renders_in_time(&two, 0.3, 10.0), 3);
        // Time already spent past the pilot's share, or none measured, leaves none.
        assert_eq!(extension_renders_in_time(&two, 0.3, -1.0), 0);
        assert_eq!(extension_renders_in_time(&two, 0.0, 0.0), 0);
    }

    #[test]
    fn two_kept_trials_are_measured_together() {
        let trials = Trials {
            ris: true,
            no_roulette: true,
            ..Trials::default()
        };
        let mut calls = 0;
        let choice = choose_unbounded(base(), &trials, |s, round| {
            calls += 1;
            let better = u32::from(s.russian_roulette.is_none())
                + u32::from(s.light_selection != LightSelection::Power);
            Ok::<_, ()>(renders(
                0.1 / 2f32.powi(better as i32),
                100,
                calls + 16 * round,
            ))
        })
        .unwrap();
        assert_eq!(calls, 4, "base, two trials and their combination");
        assert_eq!(choice.label, "+ris-roulette");
        assert!(choice.settings.russian_roulette.is_none());
    }

    /// Switching light tracing off saves cost and, in renders that leave its caustics out,
    /// shows no more noise; it wins unless the variance of the caustics it leaves out counts.
    #[test]
    fn the_caustics_a_candidate_leaves_out_count_in_its_variance() {
        let traced = PathSettings {
            light_tracing: Some(LightTracing::DENSE),
            ..base()
        };
        let trials = Trials {
            no_light_tracing: true,
            ..Trials::default()
        };
        let pixels = (SIZE.0 * SIZE.1) as usize;
        let choose_with = |unseen: f32| {
            choose_unbounded(traced, &trials, |s, round| {
                Ok::<_, ()>(if s.light_tracing.is_some() {
                    renders(0.1, 150, 1 + 16 * round)
                } else {
                    PilotRenders {
                        caustic_variance: Some(vec![Vec3::splat(unseen); pixels]),
                        ..renders(0.1, 100, 2 + 16 * round)
                    }
                })
            })
            .unwrap()
        };
        // The renders' pixels are 1 ± 0.1: a variance of 0.01. Without caustics the candidate
        // at two thirds of the cost wins; caustics of that variance again double its variance
        // and make it three quarters as efficient.
        assert_eq!(choose_with(0.0).label, "-light-tracing");
        let choice = choose_with(0.01);
        assert_eq!(choice.label, "base", "{}", choice.reason());
        let variance = choice.measured[1].variance / choice.measured[0].variance;
        assert!((variance - 2.0).abs() < 0.3, "variance ratio {variance}");
    }

    #[test]
    fn sparse_light_paths_are_kept_where_they_pay_and_exclude_light_tracing_off() {
        // Sparse light paths cost 60% of dense ones at 1.1 times the variance (efficiency
        // 1.5×); switching light tracing off costs half at 1.4 times the variance (1.43×): only
        // the better of the two is kept, and no combination of them is rendered.
        let traced = PathSettings {
            light_tracing: Some(LightTracing::DENSE),
            ..base()
        };
        let trials = Trials {
            no_light_tracing: true,
            sparse_light_paths: true,
            ..Trials::default()
        };
        let spread = |variance: f32| 0.1 * variance.sqrt();
        let choice = choose_unbounded(traced, &trials, |s, round| {
            let seed = 16 * round;
            Ok::<_, ()>(match s.light_tracing {
                Some(LightTracing::DENSE) => renders(spread(1.0), 100, seed + 1),
                Some(LightTracing::SPARSE) => renders(spread(1.1), 60, seed + 2),
                None => renders(spread(1.4), 50, seed + 3),
                Some(other) => panic!("{other:?} was rendered"),
            })
        })
        .unwrap();
        assert_eq!(choice.label, "+sparse-light-paths");
        assert_eq!(choice.settings.light_tracing, Some(LightTracing::SPARSE));
        assert_eq!(
            choice.measured.len(),
            3,
            "no combination of exclusive trials"
        );
        // Where caustics are most of the noise (4 times the variance at a quarter of the light
        // paths), dense ones stay.
        let choice = choose_unbounded(traced, &trials, |s, round| {
            let seed = 16 * round;
            Ok::<_, ()>(match s.light_tracing {
                Some(LightTracing::DENSE) => renders(spread(1.0), 100, seed + 1),
                Some(_) => renders(spread(3.0), 60, seed + 2),
                None => renders(spread(8.0), 50, seed + 3),
            })
        })
        .unwrap();
        assert_eq!(choice.settings.light_tracing, Some(LightTracing::DENSE));
    }

    #[test]
    fn light_tracing_and_path_reuse_are_never_chosen_together() {
        // Light tracing is in the base; both switching it off and reusing paths (which switches
        // it off) beat it, reuse by more.
        let traced = PathSettings {
            light_tracing: Some(LightTracing::DENSE),
            ..base()
        };
        let trials = Trials {
            no_light_tracing: true,
            path_reuse: true,
            ..Trials::default()
        };
        let choice = choose_unbounded(traced, &trials, |s, round| {
            Ok::<_, ()>(match (s.light_tracing.is_some(), s.path_reuse.is_some()) {
                (true, false) => renders(0.1, 100, 1 + 16 * round),
                (false, false) => renders(0.05, 100, 2 + 16 * round),
                (false, true) => renders(0.03, 100, 3 + 16 * round),
                (true, true) => panic!("light tracing with path reuse was rendered"),
            })
        })
        .unwrap();
        assert_eq!(choice.label, "+path-reuse");
        assert!(choice.settings.path_reuse.is_some() && choice.settings.light_tracing.is_none());
        assert_eq!(
            choice.measured.len(),
            3,
            "no combination of exclusive trials"
        );
    }

    #[test]
    fn one_light_selection_is_kept_of_three_that_beat_power() {
        let trials = Trials {
            ris: true,
            uniform_lights: true,
            every_light: true,
            ..Trials::default()
        };
        let choice = choose_unbounded(base(), &trials, |s, round| {
            Ok::<_, ()>(match s.light_selection {
                LightSelection::Power => renders(0.1, 100, 1 + 16 * round),
                LightSelection::Ris { .. } => renders(0.05, 100, 2 + 16 * round),
                LightSelection::Uniform => renders(0.03, 100, 3 + 16 * round),
                LightSelection::All => renders(0.02, 100, 4 + 16 * round),
            })
        })
        .unwrap();
        assert_eq!(choice.label, "+every-light");
        assert_eq!(choice.settings.light_selection, LightSelection::All);
        assert_eq!(
            choice.measured.len(),
            4,
            "no combination of light selections"
        );
    }

    #[test]
    fn thumbnails_keep_the_aspect_and_fit_the_pixel_and_sample_budgets() {
        let one = Trials {
            ris: true,
            ..Trials::default()
        };
        assert_eq!(
            thumbnail_size(256, 256, &one, None, f64::INFINITY),
            Some((64, 64))
        );
        assert_eq!(
            thumbnail_size(40, 30, &one, None, f64::INFINITY),
            Some((40, 30))
        );
        let (w, h) = thumbnail_size(1920, 1080, &one, None, f64::INFINITY).unwrap();
        assert!(w * h <= PILOT_PIXELS, "{w}x{h}");
        assert!(w * h > PILOT_PIXELS / 2, "{w}x{h}");
        assert!((w as f64 / h as f64 - 1920.0 / 1080.0).abs() < 0.05);
        // One trial: 2 candidates and a combination, each 2 x 4 spp, 24 samples per thumbnail
        // pixel, may take a tenth of the image's samples. 128 x 128 at 64 spp allows 4369
        // pixels: the 4096 cap holds.
        assert_eq!(pilot_samples_per_pixel(&one), 24.0);
        assert_eq!(
            thumbnail_size(128, 128, &one, Some(64), f64::INFINITY),
            Some((64, 64))
        );
        // At 8 spp 546 pixels: 22 x 22 is the largest whole division under it.
        let (w, h) = thumbnail_size(128, 128, &one, Some(8), f64::INFINITY).unwrap();
        assert_eq!((w, h), (22, 22));
        let pilot = pilot_samples_per_pixel(&one) * f64::from(w * h);
        assert!(pilot <= MAX_PILOT_SHARE * 8.0 * 128.0 * 128.0, "{w}x{h}");
        // At 1 spp not even 16 x 16 pixels fit.
        assert_eq!(thumbnail_size(128, 128, &one, Some(1), f64::INFINITY), None);
        // A time budget's cap on the pixels.
        let (w, h) = thumbnail_size(256, 256, &one, None, 1000.0).unwrap();
        assert!(w * h <= 1000 && w * h > 500, "{w}x{h}");
        assert_eq!(thumbnail_size(256, 256, &one, None, 100.0), None);
    }
}

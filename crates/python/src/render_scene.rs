//! `strata.Scene`: a scene loaded and built once, rendered as often as asked.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};
use std::time::Instant;

use numpy::{PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use render::driver::RenderOptions;
use render::film_exr::write_film_exr;
use render::filter::Filter;
use render::fingerprint::scene_fingerprint;
use render::image::Image;
use render::plan::plan_from_flags;
use render::session::{film_filter, render_scene};
use render::shard;
use render::stats::RenderStats;
use render::stop::StopSignal;
use scene::{LoadError, RenderScene};

use crate::errors::{file_error, os_error, scene_error, value_error};
use crate::interrupt;

/// A Mitsuba 3 scene, parsed and built once (BVH included); `render` renders it again and again.
#[pyclass(module = "strata", frozen)]
pub struct Scene {
    /// The built scene.
    scene: RenderScene,
    /// Its reconstruction filter.
    filter: Filter,
    /// Its fingerprint, as render EXRs record it.
    fingerprint: String,
    /// The scene file.
    path: PathBuf,
    /// Seconds the load took (parsing, reading meshes and textures, building the BVH).
    load_seconds: f64,
    /// The last render's statistics as the JSON of `strata render --stats`.
    last_stats: Mutex<Option<String>>,
}

/// Everything `Scene.render` takes besides the scene.
struct RenderRequest {
    spp: Option<u32>,
    time: Option<f64>,
    integrator: Option<String>,
    sampler: Option<String>,
    seed: Option<u64>,
    threads: Option<usize>,
    adaptive: Option<bool>,
    max_depth: Option<u32>,
    samples: Option<(u32, u32)>,
    out: Option<PathBuf>,
}

impl RenderRequest {
    /// The `strata render` flags that ask for this render.
    fn flags(&self) -> Vec<String> {
        let mut flags = Vec::new();
        let mut flag = |name: &str, value: Option<String>| {
            if let Some(value) = value {
                flags.push(name.to_string());
                flags.push(value);
            }
        };
        flag("--integrator", self.integrator.clone());
        flag("--spp", self.spp.map(|s| s.to_string()));
        flag("--time", self.time.map(|t| t.to_string()));
        flag("--sampler", self.sampler.clone());
        flag("--seed", self.seed.map(|s| s.to_string()));
        flag(
            "--adaptive",
            self.adaptive
                .map(|a| if a { "on" } else { "off" }.to_string()),
        );
        flag("--max-depth", self.max_depth.map(|d| d.to_string()));
        flag("--samples", self.samples.map(|(a, b)| format!("{a}..{b}")));
        flags
    }
}

/// The message of a refused command line: clap's first paragraph, without its usage lines.
fn flag_message(text: &str) -> String {
    let first = text.split("\n\n").next().unwrap_or(text).trim();
    first.strip_prefix("error: ").unwrap_or(first).to_string()
}

impl Scene {
    /// Reads, parses and builds the scene at `path` with the `-D` overrides `defines`.
    fn open(path: &Path, defines: &[(String, String)]) -> Result<Self, LoadError> {
        let start = Instant::now();
        let bytes = scene::read_scene_file(path)?;
        let desc = scene::parse_bytes(&bytes, path, defines)?;
        let fingerprint = scene_fingerprint(&desc);
        let scene = scene::build(desc)?;
        let filter = film_filter(scene.desc.film.filter).map_err(|e| LoadError {
            file: path.to_path_buf(),
            line: 0,
            column: 0,
            element: String::new(),
            message: format!("the film's filter: {e}"),
        })?;
        Ok(Self {
            scene,
            filter,
            fingerprint,
            path: path.to_path_buf(),
            load_seconds: start.elapsed().as_secs_f64(),
            last_stats: Mutex::new(None),
        })
    }

    /// Renders as `request` asks: the image, and the stats as JSON. A signal's exception
    /// (`KeyboardInterrupt`) is raised after the render stopped, with the stats kept.
    fn render_request<'py>(
        &self,
        py: Python<'py>,
        request: &RenderRequest,
    ) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let flags = request.flags();
        let flag_refs: Vec<&str> = flags.iter().map(String::as_str).collect();
        let mut plan =
            plan_from_flags(&self.scene, &flag_refs).map_err(|e| value_error(flag_message(&e)))?;
        let (width, height) = (self.scene.desc.film.width, self.scene.desc.film.height);
        let piece = match request.samples {
            Some((start, end)) => Some(
                shard::start_piece(start..end, request.spp, &mut plan, width, height)
                    .map_err(|e| value_error(e.to_string()))?,
            ),
            None => None,
        };
        if request.threads == Some(0) {
            return Err(value_error("threads must be at least 1 (None: all cores)"));
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(request.threads.unwrap_or(0))
            .build()
            .map_err(|e| os_error(format!("cannot start the render threads: {e}")))?;
        let stop = StopSignal::new();
        let options = RenderOptions {
            stop: Some(stop.clone()),
            resume: piece,
            max_pass_seconds: interrupt::PASS_SECONDS,
            ..RenderOptions::quiet()
        };
        let (scene, filter) = (&self.scene, &self.filter);
        let outcome = interrupt::run(py, &stop, || {
            pool.install(|| render_scene(scene, &plan, filter, &options))
        })?;
        let (output, counters) = outcome
            .result
            .map_err(|e| value_error(format!("{}: {e}", self.path.display())))?;
        let mut stats = RenderStats::of_render(&output, counters, &plan, scene.camera.has_lens());
        stats.load_seconds = self.load_seconds;
        *self
            .last_stats
            .lock()
            .unwrap_or_else(PoisonError::into_inner) = Some(stats.to_json());
        if let Some(interrupt) = outcome.interrupt {
            return Err(interrupt);
        }
        if let Some(out) = &request.out {
            let first = request.samples.map_or(0, |(start, _)| start);
            let record = shard::film_record(
                self.fingerprint.clone(),
                &plan,
                &self.scene.desc,
                first,
                &output,
            );
            write_film_exr(out, &output.film, &record).map_err(os_error)?;
        }
        image_array(py, &output.film.to_image())
    }
}

/// `image` as a `float32` array of shape `(height, width, 3)`.
pub fn image_array<'py>(py: Python<'py>, image: &Image) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let values: Vec<f32> = image.data.iter().flat_map(|v| v.to_array()).collect();
    numpy::PyArray1::from_vec(py, values).reshape([image.height as usize, image.width as usize, 3])
}

#[pymethods]
impl Scene {
    /// Loads the scene at `path`, with `defines` a list of (name, value) strings overriding its
    /// `<default>` parameters as `strata render -D name=value` does. Raises `SceneError` (file,
    /// line, element, message) when the scene cannot be loaded.
    #[staticmethod]
    #[pyo3(signature = (path, defines = Vec::new()))]
    fn load(py: Python<'_>, path: PathBuf, defines: Vec<(String, String)>) -> PyResult<Self> {
        let mut seen = std::collections::HashSet::new();
        for (name, _) in &defines {
            if !seen.insert(name.as_str()) {
                return Err(file_error(
                    py,
                    &path,
                    format!("the parameter '{name}' is defined twice"),
                ));
            }
        }
        py.detach(|| Self::open(&path, &defines))
            .map_err(|e| scene_error(py, &e))
    }

    /// Renders the scene as `strata render` would with the same flags, and returns the image as
    /// a `float32` array of shape `(height, width, 3)`: the very values the command writes to
    /// its EXR. The GIL is released while rendering; Ctrl-C stops the render at its next pass
    /// boundary and raises `KeyboardInterrupt`.
    ///
    /// - `spp`: samples per pixel; `time`: a time budget in seconds (either or both; neither:
    ///   the scene's sample count).
    /// - `integrator`: `auto` (or `path`), `reference`, `nee`, `mis` or `ris`; `None`: the
    ///   scene's `<integrator type>` where it names one of these, else `auto` (as `strata
    ///   render` without `--integrator`).
    /// - `sampler`: `independent`, `stratified`, `bluenoise`, `sobol`, or `None` for the
    ///   scene's (`auto` takes Sobol for Mitsuba's `independent`).
    /// - `seed`: the sampler seed (`None`: the scene's).
    /// - `threads`: Rayon threads (`None`: all cores); the image does not depend on it.
    /// - `adaptive`: adaptive sampling on or off (`None`: the preset's choice).
    /// - `max_depth`: path vertices after the camera (`None`: the scene's).
    /// - `samples`: `(start, end)` renders only those sample indices of the `spp` render, a
    ///   piece that `strata.merge` (or `strata merge`) adds up exactly.
    /// - `out`: also write the EXR `strata render --out` writes (with the sums and the record
    ///   that merging needs), atomically.
    #[pyo3(signature = (spp = Some(64), time = None, integrator = None,
        sampler = None, seed = Some(0), threads = None, adaptive = None, max_depth = None,
        samples = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        spp: Option<u32>,
        time: Option<f64>,
        integrator: Option<String>,
        sampler: Option<String>,
        seed: Option<u64>,
        threads: Option<usize>,
        adaptive: Option<bool>,
        max_depth: Option<u32>,
        samples: Option<(u32, u32)>,
        out: Option<PathBuf>,
    ) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let request = RenderRequest {
            spp,
            time,
            integrator,
            sampler,
            seed,
            threads,
            adaptive,
            max_depth,
            samples,
            out,
        };
        self.render_request(py, &request)
    }

    /// The last render's statistics, as `strata render --stats` writes them: `spp`, `seconds`,
    /// `load_seconds`, `rays`, `shadow_rays`, `techniques` (those that rendered the image:
    /// `auto`'s choice where it chose), `auto_choice` (what `auto`'s pilot measured and why it
    /// chose), `passes`, `threads`, `interrupted`, … `None` before the first render.
    #[getter]
    fn last_stats<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let json = self
            .last_stats
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone();
        match json {
            Some(text) => {
                let loads = py.import("json")?.getattr("loads")?;
                Ok(Some(loads.call1((text,))?))
            }
            None => Ok(None),
        }
    }

    /// The image size in pixels, `(width, height)`.
    #[getter]
    fn size(&self) -> (u32, u32) {
        (self.scene.desc.film.width, self.scene.desc.film.height)
    }

    /// The scene's fingerprint (16 hex digits): its content with every file it reads, as the
    /// render EXRs record it; a piece is merged only with pieces of the same fingerprint.
    #[getter]
    fn fingerprint(&self) -> &str {
        &self.fingerprint
    }

    /// The scene file this was loaded from.
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// Seconds the load took.
    #[getter]
    fn load_seconds(&self) -> f64 {
        self.load_seconds
    }

    /// A few facts about the scene, for looking at it in a notebook.
    fn __repr__(&self) -> String {
        let (width, height) = self.size();
        format!(
            "strata.Scene('{}', {width}x{height}, fingerprint {})",
            self.path.display(),
            self.fingerprint
        )
    }
}

//! The switches of the variance-reduction path tracer, one struct with affirmative names.

use lights::LightSelection;

/// How light-sampled and BSDF-sampled estimates of the same light are combined.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mis {
    /// No combination: with light sampling on, emission found by BSDF sampling is ignored
    /// except where light sampling could not have found it (first hit, after a delta bounce).
    Off,
    /// Veach's balance heuristic.
    Balance,
    /// Veach's power heuristic with exponent 2.
    Power,
}

/// Russian roulette on the indirect part of the path: after each sampled bounce from
/// `start_depth` on, the path survives with probability clamp(max(r, g, b) of throughput × η²),
/// and a survivor's throughput is divided by it. The throughput rather than the albedo, because
/// it is what the rest of the path is multiplied by: a path that already carries little
/// contributes little whatever it meets next. η² is the product over the refractions so far,
/// so the 1/η² radiance scaling of entering glass is not mistaken for absorption (as in pbrt-v4
/// and Mitsuba 3). Emission and next event estimation at the vertex are added before the
/// decision, so they are never lost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RussianRoulette {
    /// First path vertex (1 = the camera ray's hit) after which paths may be terminated.
    pub start_depth: u32,
}

/// Mitsuba's `direct` integrator: at the camera ray's hit, `light` light samples and `bsdf`
/// BSDF samples, each kind weighted by its count (the power or balance heuristic over `count ×
/// density`, each sample divided by its count), and nothing after the next vertex. Zero samples
/// of a kind leave out what only that kind reaches, as in Mitsuba: no light samples, no delta
/// lights; no BSDF samples, nothing seen by way of a mirror or glass. Meant for light sampling
/// on (every preset does); without it the light samples are only the delta lights' shadow rays
/// and the BSDF samples find all other light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DirectSamples {
    /// Light (emitter) samples: Mitsuba's `emitter_samples`.
    pub light: u32,
    /// BSDF samples, each traced to the emission it finds: Mitsuba's `bsdf_samples`.
    pub bsdf: u32,
}

/// Every switch of [`crate::path`]. The default is the plain BSDF-sampled path tracer with
/// Mitsuba's roulette start depth; turn techniques on one by one to measure each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PathSettings {
    /// Largest number of path vertices after the camera (Mitsuba's `max_depth`); `None` is
    /// unbounded (then roulette should be on, or paths run to the safety cap).
    pub max_depth: Option<u32>,
    /// Hide emitters seen directly by the camera, as Mitsuba 3 does: camera rays pass through
    /// area emitters to the first surface that does not emit, and find no environment.
    pub hide_emitters: bool,
    /// Next event estimation: a shadow ray to a chosen light at every non-delta vertex.
    pub sample_lights: bool,
    /// Importance-sample the BSDF for the next direction; when off, directions are uniform over
    /// the hemisphere (sphere for transmissive BSDFs), delta lobes still by their delta.
    pub sample_bsdf: bool,
    /// Combination of light and BSDF samples (only meaningful with `sample_lights`).
    pub mis: Mis,
    /// How a light is chosen for next event estimation.
    pub light_selection: LightSelection,
    /// Russian roulette, `None` for off.
    pub russian_roulette: Option<RussianRoulette>,
    /// Caustics by light tracing: paths whose first vertex after the camera is non-delta and
    /// whose last vertex before an area light is delta (light → mirror or glass → … → diffuse
    /// → camera) are left to [`crate::LightTracer`], which traces them from the lights and
    /// connects them to the camera; the path tracer drops the emission it would find along
    /// them. The renderer must then run the light tracer too. `None` for off.
    pub light_tracing: Option<LightTracing>,
    /// Mitsuba's `direct` integrator's sample counts at the first vertex (see [`DirectSamples`]);
    /// `None` walks the path. With counts, `max_depth` must be 2 and roulette and light tracing
    /// have nothing to act on.
    pub direct_samples: Option<DirectSamples>,
    /// Mitsuba's volumetric path tracers (`volpath`, `volpathmis`, `prbvolpath`): a pass straight
    /// through a null lobe ([`materials::BsdfSample::is_null`]: `null`, a mask's transparency, a
    /// thin dielectric's transmission) is not a path vertex, so it does not count towards
    /// `max_depth` (a path goes on through one at its last vertex), the camera's first segment
    /// goes on through it (hidden emitters stay hidden behind it), and it draws a vertex's
    /// sampler dimensions again. Mitsuba's shadow rays pass null surfaces too; here they stop at
    /// them, as in `path`, so light behind one is found by BSDF samples alone: the same image,
    /// with other noise. Light tracing does not know the rule and must be off where null lobes
    /// are.
    pub skip_null_vertices: bool,
    /// Delta splitting ([`crate::path`]'s `delta_splitting`): at vertices seen from the camera
    /// through delta bounces only, the emission seen through every delta lobe of a BSDF that
    /// chooses among lobes (glass, smooth plastic), one ray per lobe not chosen.
    pub delta_splitting: bool,
    /// Path reuse (see [`PathReuse`]), `None` for off. Only with BSDF sampling, a `max_depth`
    /// of at least 3, roulette from depth 2 or later, and neither light tracing,
    /// `direct_samples` nor `skip_null_vertices` (see [`PathSettings::reuse_applies`]).
    pub path_reuse: Option<PathReuse>,
}

/// Path reuse (see [`crate::path_reuse`]): the renderer traces the camera samples of each block
/// of `block × block` pixels together, and each pixel's first vertex is connected by a shadow
/// ray to the second vertex of every other path of the block, so that each pixel's indirect
/// light is estimated from all the block's paths. Applies where both vertices are diffuse.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PathReuse {
    /// Block edge in pixels: 2 or 4 (blocks must tile the renderer's tiles).
    pub block: u32,
}

/// Caustics by light tracing (see [`crate::LightTracer`]): how many light paths the renderer
/// traces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightTracing {
    /// Camera samples per light path: one camera sample in this many (1 or more) also traces a
    /// light path, and the caustic paths both strategies find are weighted for that rate
    /// (`caustic_mis`). Fewer light paths cost less and leave the caustics noisier.
    pub samples_per_path: u32,
}

impl LightTracing {
    /// One light path per camera sample.
    pub const DENSE: Self = Self {
        samples_per_path: 1,
    };

    /// One light path per [`Self::SPARSE_SAMPLES_PER_PATH`] camera samples, which `auto`'s pilot
    /// measures against [`Self::DENSE`]: where caustics are a small share of the noise, fewer
    /// light paths buy more camera samples.
    pub const SPARSE: Self = Self {
        samples_per_path: Self::SPARSE_SAMPLES_PER_PATH,
    };

    /// Camera samples per light path of [`Self::SPARSE`].
    pub const SPARSE_SAMPLES_PER_PATH: u32 = 4;

    /// Light paths per camera sample, 1 / [`Self::samples_per_path`].
    pub fn paths_per_sample(&self) -> f32 {
        1.0 / self.samples_per_path as f32
    }
}

impl Default for PathSettings {
    fn default() -> Self {
        Self {
            max_depth: None,
            hide_emitters: false,
            sample_lights: false,
            sample_bsdf: true,
            mis: Mis::Off,
            light_selection: LightSelection::Power,
            russian_roulette: None,
            light_tracing: None,
            direct_samples: None,
            skip_null_vertices: false,
            delta_splitting: false,
            path_reuse: None,
        }
    }
}

impl PathSettings {
    /// Whether [`PathSettings::path_reuse`] can act with the other settings: BSDF sampling (the
    /// densities it combines are the BSDF's), at least 3 vertices (else the second vertex
    /// reflects nothing), roulette not before the second vertex (so that every first vertex
    /// continues its path), and none of the settings that change what a path's second vertex
    /// is or what it finds: light tracing, `direct_samples`, `skip_null_vertices`.
    pub fn reuse_applies(&self) -> bool {
        self.sample_bsdf
            && self.max_depth.is_none_or(|d| d >= 3)
            && self.russian_roulette.is_none_or(|r| r.start_depth >= 2)
            && self.light_tracing.is_none()
            && self.direct_samples.is_none()
            && !self.skip_null_vertices
    }

    /// Names of the techniques these settings switch on, for reports.
    pub fn technique_names(&self) -> Vec<String> {
        let mut names = Vec::new();
        names.push(
            if self.sample_bsdf {
                "bsdf-sampling"
            } else {
                "uniform-directions"
            }
            .to_string(),
        );
        if self.sample_lights {
            names.push("nee".to_string());
            names.push(match self.light_selection {
                LightSelection::Uniform => "light-selection-uniform".to_string(),
                LightSelection::Power => "light-selection-power".to_string(),
                LightSelection::Ris { candidates } => {
                    format!("light-selection-ris-{candidates}")
                }
                LightSelection::All => "light-selection-all".to_string(),
            });
            match self.mis {
                Mis::Off => {}
                Mis::Balance => names.push("mis-balance".to_string()),
                Mis::Power => names.push("mis-power".to_string()),
            }
        }
        if let Some(rr) = self.russian_roulette {
            names.push(format!("russian-roulette-from-{}", rr.start_depth));
        }
        if let Some(LightTracing { samples_per_path }) = self.light_tracing {
            names.push(match samples_per_path {
                1 => "light-tracing-caustics".to_string(),
                n => format!("light-tracing-caustics-1-per-{n}"),
            });
        }
        if self.delta_splitting {
            names.push("delta-splitting".to_string());
        }
        if let Some(PathReuse { block }) = self.path_reuse {
            names.push(format!("path-reuse-{block}x{block}"));
        }
        if let Some(DirectSamples { light, bsdf }) = self.direct_samples {
            names.push(format!("direct-{light}-light-{bsdf}-bsdf-samples"));
        }
        names
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_reuse_applies_only_where_every_first_vertex_continues_its_path() {
        let base = PathSettings {
            max_depth: Some(8),
            russian_roulette: Some(RussianRoulette { start_depth: 5 }),
            ..PathSettings::default()
        };
        assert!(base.reuse_applies());
        assert!(
            PathSettings {
                max_depth: None,
                ..base
            }
            .reuse_applies()
        );
        let refused = [
            PathSettings {
                max_depth: Some(2),
                ..base
            },
            PathSettings {
                sample_bsdf: false,
                ..base
            },
            PathSettings {
                russian_roulette: Some(RussianRoulette { start_depth: 1 }),
                ..base
            },
            PathSettings {
                light_tracing: Some(LightTracing::DENSE),
                ..base
            },
            PathSettings {
                skip_null_vertices: true,
                ..base
            },
            PathSettings {
                direct_samples: Some(DirectSamples { light: 1, bsdf: 1 }),
                ..base
            },
        ];
        for settings in refused {
            assert!(!settings.reuse_applies(), "{settings:?}");
        }
    }
}

//! EXR files and images: reading, the render record, exact merging, and `strata diff`'s metrics.

use std::path::PathBuf;

use glam::Vec3;
use numpy::{PyArray3, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use render::diff::DiffReport;
use render::film_exr::{RenderRecord, read_film_exr, write_film_exr};
use render::image::Image;
use render::merge::merge_files;

use crate::errors::{MergeError, os_error, value_error};
use crate::render_scene::image_array;

/// Reads the RGB image of the EXR at `path` (any EXR with R, G, B channels, e.g. one that
/// `strata render` or Mitsuba wrote) as a `float32` array of shape `(height, width, 3)`.
#[pyfunction]
pub fn read_exr(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyArray3<f32>>> {
    let image = py
        .detach(|| Image::read_exr(&path))
        .map_err(|e| os_error(e.to_string()))?;
    image_array(py, &image)
}

/// The record of a render EXR that `strata render` or `strata merge` wrote, as a dict:
/// `scene` (the fingerprint), `settings` (everything that decides a sample's value besides the
/// scene and seed), `samples` (the sample ranges by seed, e.g. `seed 0: 0..64`) and `spp`.
/// Raises `MergeError` for a file without one.
#[pyfunction]
pub fn read_record(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let (_, record) = py
        .detach(|| read_film_exr(&path))
        .map_err(MergeError::new_err)?;
    record_dict(py, &record)
}

/// `record` as the dict [`read_record`] returns.
fn record_dict<'py>(py: Python<'py>, record: &RenderRecord) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("scene", &record.scene)?;
    dict.set_item("settings", &record.settings)?;
    dict.set_item("samples", record.samples.to_string())?;
    dict.set_item("spp", record.samples.total())?;
    Ok(dict)
}

/// Adds up the render EXRs at `paths` (pieces of one render, `strata render --samples`) exactly,
/// as `strata merge` does, and returns `(image, record)`; writes the merged EXR to `out` when
/// given (the very file `strata merge --out` writes). Raises `MergeError`, naming the files,
/// for pieces that do not belong together.
#[pyfunction]
#[pyo3(signature = (paths, out = None))]
pub fn merge(
    py: Python<'_>,
    paths: Vec<PathBuf>,
    out: Option<PathBuf>,
) -> PyResult<(Bound<'_, PyArray3<f32>>, Bound<'_, PyDict>)> {
    let (film, record) = py
        .detach(|| merge_files(&paths))
        .map_err(|e| MergeError::new_err(e.to_string()))?;
    if let Some(out) = &out {
        py.detach(|| write_film_exr(out, &film, &record))
            .map_err(os_error)?;
    }
    Ok((
        image_array(py, &film.to_image())?,
        record_dict(py, &record)?,
    ))
}

/// `array` (shape `(height, width, 3)`) as an image.
fn image_of(array: &PyReadonlyArray3<'_, f32>, name: &str) -> PyResult<Image> {
    let shape = array.shape();
    if shape[2] != 3 {
        return Err(value_error(format!(
            "{name} has shape {shape:?}; an image is (height, width, 3)"
        )));
    }
    let (height, width) = (
        u32::try_from(shape[0]).map_err(|_| value_error(format!("{name} is too high")))?,
        u32::try_from(shape[1]).map_err(|_| value_error(format!("{name} is too wide")))?,
    );
    let view = array.as_array();
    let data = (0..shape[0])
        .flat_map(|y| (0..shape[1]).map(move |x| (y, x)))
        .map(|(y, x)| Vec3::new(view[[y, x, 0]], view[[y, x, 1]], view[[y, x, 2]]))
        .collect();
    Ok(Image {
        width,
        height,
        data,
    })
}

/// The error metrics of `strata diff` for image `a` against the reference `b` (`float32` arrays
/// of shape `(height, width, 3)`): a dict of `rmse`, `relmse` (mean of (a − b)² / (b² + 0.01)
/// over pixels and channels), `mean_a` and `mean_b`.
#[pyfunction]
pub fn diff<'py>(
    py: Python<'py>,
    a: PyReadonlyArray3<'py, f32>,
    b: PyReadonlyArray3<'py, f32>,
) -> PyResult<Bound<'py, PyDict>> {
    let (a, b) = (image_of(&a, "a")?, image_of(&b, "b")?);
    let report = DiffReport::of_images(&a, &b).map_err(|e| value_error(e.to_string()))?;
    let dict = PyDict::new(py);
    dict.set_item("rmse", report.rmse)?;
    dict.set_item("relmse", report.relmse)?;
    dict.set_item("mean_a", report.mean_a)?;
    dict.set_item("mean_b", report.mean_b)?;
    Ok(dict)
}

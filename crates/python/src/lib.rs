//! The native part of the Python package `strata` (`strata._strata`): Mitsuba 3 scenes loaded
//! once and rendered to NumPy arrays as `strata render` renders them, the render EXRs' reader
//! and exact merge, image metrics, and the `sampling` crate's generators and warps.
//!
//! The Python layer (`python/strata/`) adds the keyword-argument conveniences, the one-call
//! `strata.render`, `strata.sampling` and `strata.distributed`; see the book's page "Python and
//! Dask" (`docs/src/guide/python.md`).
//! Images are `float32` arrays of shape `(height, width, 3)`, top row first, linear RGB.

#![warn(missing_docs)]

mod errors;
mod files;
mod interrupt;
mod render_scene;
mod sampling_api;

use pyo3::prelude::*;

/// The module `strata._strata`.
#[pymodule]
fn _strata(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("MergeError", py.get_type::<errors::MergeError>())?;
    m.add_class::<render_scene::Scene>()?;
    m.add_function(wrap_pyfunction!(files::read_exr, m)?)?;
    m.add_function(wrap_pyfunction!(files::read_record, m)?)?;
    m.add_function(wrap_pyfunction!(files::merge, m)?)?;
    m.add_function(wrap_pyfunction!(files::diff, m)?)?;
    sampling_api::register(m)?;
    Ok(())
}

//! The package's exceptions, and how the render crates' errors become Python's.

use std::path::Path;

use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use scene::LoadError;

pyo3::create_exception!(
    strata,
    SceneError,
    pyo3::exceptions::PyValueError,
    "A scene that cannot be loaded. Its attributes say where: `file` (the XML file holding the \
     offending element, an included one where it came from an include), `line` and `column` \
     (1-based; 0 when the problem concerns the whole file), `element` (the element's opening \
     tag, or '') and `message` (what is wrong). `str()` gives all of them on one line."
);

pyo3::create_exception!(
    strata,
    MergeError,
    pyo3::exceptions::PyValueError,
    "Render pieces that cannot be merged: files without Strata's render record, the same \
     samples twice, or pieces of different scenes, settings or sizes. The message names the \
     files."
);

/// A [`SceneError`] for `error`, with its location as attributes.
pub fn scene_error(py: Python<'_>, error: &LoadError) -> PyErr {
    let err = SceneError::new_err(error.to_string());
    let set = || -> PyResult<()> {
        let value = err.value(py);
        value.setattr("file", error.file.to_string_lossy().as_ref())?;
        value.setattr("line", error.line)?;
        value.setattr("column", error.column)?;
        value.setattr("element", error.element.as_str())?;
        value.setattr("message", error.message.as_str())?;
        Ok(())
    };
    match set() {
        Ok(()) => err,
        Err(e) => e,
    }
}

/// A [`SceneError`] about the whole of `file` (line 0, no element).
pub fn file_error(py: Python<'_>, file: &Path, message: String) -> PyErr {
    scene_error(
        py,
        &LoadError {
            file: file.to_path_buf(),
            line: 0,
            column: 0,
            element: String::new(),
            message,
        },
    )
}

/// A `ValueError` with `message`.
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}

/// An `OSError` with `message`.
pub fn os_error(message: impl Into<String>) -> PyErr {
    PyOSError::new_err(message.into())
}

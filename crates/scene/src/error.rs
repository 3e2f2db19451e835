//! The one error type of the loader and the source locations it carries.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Why a scene could not be loaded, and where.
///
/// Every problem — XML syntax, an unsupported plugin or parameter, a bad number, a missing or corrupt
/// mesh file — is reported with the scene file, the 1-based line and column of the XML element
/// responsible, and that element's opening tag. Displays as
/// `scene.xml:12:5: <shape type="foo">: unknown shape type "foo" (supported: ...)`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoadError {
    /// The XML file containing the offending element (an included file when the element came from an
    /// `<include>`).
    pub file: PathBuf,
    /// 1-based line of the element; 0 when the problem concerns the whole load (e.g. an override that
    /// the scene never uses, or a file that cannot be read).
    pub line: u32,
    /// 1-based column of the element; 0 together with `line`.
    pub column: u32,
    /// The element's opening tag with its identifying attributes, e.g. `<bsdf type="diffuse" id="white">`;
    /// empty when no element is involved.
    pub element: String,
    /// What is wrong, including what is supported where that helps.
    pub message: String,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if self.line > 0 {
            write!(f, ":{}:{}", self.line, self.column)?;
        }
        if !self.element.is_empty() {
            write!(f, ": {}", self.element)?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for LoadError {}

/// Where an element sits: file, position and a printable opening tag.
#[derive(Debug, Clone)]
pub(crate) struct Loc {
    pub file: Arc<PathBuf>,
    pub line: u32,
    pub column: u32,
    pub element: String,
}

impl Loc {
    /// A location that names only a file (no element, line 0).
    pub fn file_only(file: &Path) -> Self {
        Self {
            file: Arc::new(file.to_path_buf()),
            line: 0,
            column: 0,
            element: String::new(),
        }
    }

    /// An error at this location.
    pub fn error(&self, message: impl Into<String>) -> LoadError {
        LoadError {
            file: self.file.as_ref().clone(),
            line: self.line,
            column: self.column,
            element: self.element.clone(),
            message: message.into(),
        }
    }
}

/// Shorthand for loader results.
pub(crate) type Result<T> = std::result::Result<T, LoadError>;

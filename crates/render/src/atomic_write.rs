//! Atomic file output: a file appears complete at its final path or not at all.

use std::fmt;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// A file that could not be written; nothing was left at `path`.
#[derive(Debug)]
pub struct WriteError {
    /// The file that was being written.
    pub path: PathBuf,
    /// What went wrong.
    pub source: io::Error,
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write '{}': {}", self.path.display(), self.source)
    }
}

impl std::error::Error for WriteError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.source)
    }
}

/// Writes `bytes` to `path` atomically (see [`write_atomically`]).
pub fn write_bytes_atomically(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_atomically(path, |w| w.write_all(bytes)).map_err(|source| WriteError {
        path: path.to_path_buf(),
        source,
    })
}

/// Writes `path` atomically. `write` fills a buffered temporary file created in the same
/// directory as `path`; only if it succeeds is the file flushed, synced to disk and renamed over
/// `path`. On any error the temporary file is removed and whatever was at `path` before is left
/// untouched, so readers never see a partial file.
///
/// The writer passed to `write` is seekable, as the EXR encoder requires.
pub fn write_atomically<E, F>(path: &Path, write: F) -> Result<(), E>
where
    E: From<io::Error>,
    F: FnOnce(&mut BufWriter<&mut File>) -> Result<(), E>,
{
    let dir = directory_of(path);
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            "the output path does not name a file",
        )
    })?;
    let mut prefix = std::ffi::OsString::from(".");
    prefix.push(name);
    prefix.push(".");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    // Temporary files are private (0600) by default; the output gets the usual 0666 less the
    // umask, as a file created directly would.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut temp = builder.tempfile_in(dir)?;
    {
        let mut writer = BufWriter::new(temp.as_file_mut());
        write(&mut writer)?;
        writer.flush()?;
    }
    temp.as_file().sync_all()?;
    temp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// The directory that holds `path`: its parent, or `.` for a bare file name.
fn directory_of(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Names of the files in `dir`, sorted.
    fn listing(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn success_writes_the_whole_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        write_atomically::<io::Error, _>(&path, |w| w.write_all(b"hello")).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"hello");
        assert_eq!(listing(dir.path()), ["out.txt"]);
    }

    #[cfg(unix)]
    #[test]
    fn outputs_get_the_mode_of_a_directly_created_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode();
        let path = dir.path().join("out.txt");
        write_bytes_atomically(&path, b"x").unwrap();
        let direct = dir.path().join("direct.txt");
        std::fs::write(&direct, b"x").unwrap();
        assert_eq!(mode(&path), mode(&direct), "0666 less the umask, not 0600");
    }

    #[test]
    fn byte_writes_name_the_file_on_failure() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.json");
        write_bytes_atomically(&path, b"{}").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"{}");
        let missing = dir.path().join("no").join("s.json");
        let message = write_bytes_atomically(&missing, b"{}")
            .unwrap_err()
            .to_string();
        assert!(message.contains("s.json"), "{message}");
    }

    #[test]
    fn a_failing_writer_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        std::fs::write(&path, b"old").unwrap();
        let result = write_atomically::<io::Error, _>(&path, |w| {
            w.write_all(b"partial")?;
            Err(io::Error::other("encoder failed"))
        });
        assert_eq!(result.unwrap_err().to_string(), "encoder failed");
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert_eq!(listing(dir.path()), ["out.txt"]);
    }

    #[test]
    fn a_missing_directory_is_an_error_and_creates_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing").join("out.txt");
        let result = write_atomically::<io::Error, _>(&path, |w| w.write_all(b"x"));
        assert_eq!(result.unwrap_err().kind(), io::ErrorKind::NotFound);
        assert!(listing(dir.path()).is_empty());
    }

    #[test]
    fn a_bare_file_name_is_written_in_the_current_directory() {
        assert_eq!(directory_of(Path::new("a.exr")), Path::new("."));
        assert_eq!(directory_of(Path::new("x/a.exr")), Path::new("x"));
    }

    #[test]
    fn a_path_without_a_file_name_is_an_error() {
        let result = write_atomically::<io::Error, _>(Path::new("/"), |w| w.write_all(b"1"));
        assert_eq!(result.unwrap_err().kind(), io::ErrorKind::InvalidInput);
    }
}

//! Writing through a temporary file and a rename, and the fallback name.

use crate::{check_output, folder_of, io, FileError, Result};
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// A new file named `base` + `.PID.N.tmp`, created exclusively (an existing file or symbolic
/// link of that name is never written through).
pub(crate) fn create_temp(base: &Path) -> std::io::Result<(PathBuf, File)> {
    let mut tries = 0;
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut name = base.as_os_str().to_owned();
        name.push(format!(".{}.{n}.tmp", std::process::id()));
        let tmp = PathBuf::from(name);
        match File::options().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && tries < 100 => tries += 1,
            Err(e) => return Err(e),
        }
    }
}

/// Writes `bytes` to `path` through a new temporary file next to it and a rename, as `mv`
/// does, after [`check_output`]: only a missing path or a regular file is replaced. A failure,
/// or a crash (the data is synced before the rename), leaves any old file at `path` whole; the
/// temporary file is removed on failure. The new file has default permissions.
///
/// # Errors
/// As [`check_output`], or [`FileError::Io`] when writing or renaming fails.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    check_output(path)?;
    let (tmp, mut file) = create_temp(path).map_err(io(path, "create a temporary file for"))?;
    let written = file.write_all(bytes).and_then(|()| file.sync_all());
    drop(file);
    // Checked again just before the rename: something may have appeared at `path` meanwhile.
    let result = written
        .map_err(io(path, "write"))
        .and_then(|()| check_output(path))
        .and_then(|()| {
            std::fs::rename(&tmp, path).map_err(io(path, "rename the temporary file to"))
        });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Where [`write_or_fallback`] wrote.
#[derive(Debug)]
pub struct Written {
    /// The file written: the path asked for, or the fallback.
    pub path: PathBuf,
    /// Why the path asked for was not written (`None` when it was).
    pub failed: Option<FileError>,
}

/// Writes `bytes` to `path` ([`write_atomic`]); if that fails, to a fresh name next to it
/// (`NAME.recovered-PID-N`), or else in the system's temporary folder, so that the result of
/// a long run is not lost. The caller reports [`Written::failed`] and [`Written::path`].
///
/// # Errors
/// The first error, when no fallback could be written either.
pub fn write_or_fallback(path: &Path, bytes: &[u8]) -> Result<Written> {
    let first = match write_atomic(path, bytes) {
        Ok(()) => {
            return Ok(Written {
                path: path.to_path_buf(),
                failed: None,
            })
        }
        Err(e) => e,
    };
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    for dir in [folder_of(path), std::env::temp_dir()] {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let fresh = dir.join(format!("{name}.recovered-{}-{n}", std::process::id()));
        let created = File::options().write(true).create_new(true).open(&fresh);
        let Ok(mut file) = created else { continue };
        if file.write_all(bytes).and_then(|()| file.sync_all()).is_ok() {
            return Ok(Written {
                path: fresh,
                failed: Some(first),
            });
        }
        drop(file);
        let _ = std::fs::remove_file(&fresh);
    }
    Err(first)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("osrl-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_directory_is_refused_and_the_fallback_is_next_to_it() {
        let d = scratch("dir");
        let target = d.join("taken");
        std::fs::create_dir(&target).unwrap();
        let err = write_atomic(&target, b"x").unwrap_err().to_string();
        assert!(err.contains("is a directory"), "{err}");
        assert!(check_output(&target).is_err());
        let w = write_or_fallback(&target, b"data").unwrap();
        assert!(w.failed.is_some());
        assert_eq!(w.path.parent(), Some(d.as_path()));
        assert_eq!(std::fs::read(&w.path).unwrap(), b"data");
        assert!(target.is_dir(), "the directory is still there");
        // Only the fallback and the directory: no temporary files left.
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 2);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn regular_files_are_replaced_and_missing_folders_refused() {
        let d = scratch("reg");
        let p = d.join("f");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"two");
        assert!(check_output(&d.join("no").join("f")).is_err());
        assert!(check_output(&d.join("sub/")).is_err());
        assert!(check_output_dir_ok(&d));
        std::fs::remove_dir_all(&d).unwrap();
    }

    fn check_output_dir_ok(d: &Path) -> bool {
        crate::check_output_dir(&d.join("new"), &["a.csv"]).is_ok()
            && crate::check_output_dir(&d.join("f"), &[]).is_err()
    }
}

//! Writing through a temporary file and a rename, and the fallback name.

use crate::{check_output, folder_of, io, FileError, Result};
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Longest file name kept whole in a temporary file's name: with the `.PID.N.tmp` suffix it
/// stays within the 255 bytes a file name may have on common file systems.
const TEMP_STEM_BYTES: usize = 200;

/// The file name of `path` (`output` without one), cut to at most [`TEMP_STEM_BYTES`] bytes at
/// a character boundary: the stem of the temporary and the fallback names.
fn short_name(path: &Path) -> String {
    let Some(name) = path.file_name() else {
        return "output".into();
    };
    let name = name.to_string_lossy();
    let mut end = name.len().min(TEMP_STEM_BYTES);
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    name[..end].to_string()
}

/// A new file named like `base` + `.PID.N.tmp` in `base`'s folder (a file name longer than
/// [`TEMP_STEM_BYTES`] cut to that many characters first), created exclusively (an existing
/// file or symbolic link of that name is never written through).
pub(crate) fn create_temp(base: &Path) -> std::io::Result<(PathBuf, File)> {
    let stem = short_name(base);
    let mut tries = 0;
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = folder_of(base).join(format!("{stem}.{}.{n}.tmp", std::process::id()));
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
/// temporary file is removed on failure. A replaced file's permissions are kept; a new file
/// has default permissions.
///
/// # Errors
/// As [`check_output`], or [`FileError::Io`] when writing or renaming fails.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    check_output(path)?;
    let (tmp, mut file) = create_temp(path).map_err(io(path, "create a temporary file for"))?;
    // A replaced file keeps its permissions.
    let mode = std::fs::symlink_metadata(path).map(|m| m.permissions());
    let written = file
        .write_all(bytes)
        .and_then(|()| match mode {
            Ok(p) => file.set_permissions(p),
            Err(_) => Ok(()),
        })
        .and_then(|()| file.sync_all());
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
/// (`NAME.recovered-PID-N`, `NAME` cut as in the temporary file's name), or else in the system's temporary folder, so that the result of
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
    let name = short_name(path);
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

    /// A name of 250 bytes is written (its temporary file's name is cut to fit); a replaced
    /// file keeps its permissions; a read-only one is refused and kept.
    #[test]
    fn long_names_permissions_and_read_only_files() {
        let d = scratch("modes");
        let long = d.join(format!("{}.json", "é".repeat(123)));
        assert_eq!(long.file_name().unwrap().len(), 251);
        write_atomic(&long, b"one").unwrap();
        assert_eq!(std::fs::read(&long).unwrap(), b"one");
        assert_eq!(short_name(&long).len(), 200);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let p = d.join("private");
            write_atomic(&p, b"one").unwrap();
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o600)).unwrap();
            write_atomic(&p, b"two").unwrap();
            let mode = std::fs::metadata(&p).unwrap().permissions().mode() & 0o777;
            assert_eq!((std::fs::read(&p).unwrap(), mode), (b"two".to_vec(), 0o600));
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o444)).unwrap();
            let e = write_atomic(&p, b"three").unwrap_err().to_string();
            assert!(e.contains("is read-only"), "{e}");
            assert_eq!(std::fs::read(&p).unwrap(), b"two");
        }
        // Nothing but the two files: no temporary file left.
        assert_eq!(
            std::fs::read_dir(&d).unwrap().count(),
            1 + cfg!(unix) as usize
        );
        std::fs::remove_dir_all(&d).unwrap();
    }

    fn check_output_dir_ok(d: &Path) -> bool {
        crate::check_output_dir(&d.join("new"), &["a.csv"]).is_ok()
            && crate::check_output_dir(&d.join("f"), &[]).is_err()
    }
}

//! Reading and writing the files a user names, carefully (issue 30).
//!
//! - Outputs: [`check_output`] and [`check_output_dir`] refuse, before any work starts, a path
//!   that exists and is not a regular file (a directory where a file is expected, a FIFO, a
//!   device, a socket, a symbolic link) or whose folder cannot be written; [`write_atomic`]
//!   writes through a temporary file and a rename, only over a regular file or a missing path;
//!   [`write_or_fallback`] writes next to the path under a fresh name when that fails, so a long
//!   run's result is never lost. [`check_not_input`] refuses an output that is one of the run's
//!   inputs (under any name); [`check_output_tree`] refuses, before a run writes many files
//!   under a folder, any special file or link below it.
//! - Inputs: [`read_limited`] reads only a regular file of at most a given size (a FIFO would
//!   block, `/dev/zero` would never end).
//!
//! ```
//! let dir = std::env::temp_dir().join(format!("osrl-files-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let p = dir.join("a.txt");
//! osrl_files::write_atomic(&p, b"hello")?;
//! assert_eq!(osrl_files::read_limited(&p, 5)?, b"hello");
//! assert!(osrl_files::read_limited(&p, 4).is_err());
//! // A directory is not replaced.
//! assert!(osrl_files::write_atomic(&dir, b"x").is_err());
//! std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), osrl_files::FileError>(())
//! ```

mod write;

pub use write::{write_atomic, write_or_fallback, Written};

use std::fs::Metadata;
use std::io::Read;
use std::path::{Path, PathBuf};

/// What went wrong with a file; every message starts with the path.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The path exists and is not a regular file.
    #[error("{path}: is a {kind}, not a regular file: {why}")]
    NotRegular {
        path: String,
        kind: &'static str,
        why: &'static str,
    },
    /// The path exists and is not a folder, where a folder is needed.
    #[error("{path}: is a {kind}, not a folder: a folder is needed here")]
    NotFolder { path: String, kind: &'static str },
    /// An output file that exists and is read-only: its owner protected it.
    #[error("{path}: is read-only; not replaced (make it writable or give another name)")]
    ReadOnly { path: String },
    /// The folder an output file would go in does not exist.
    #[error("{path}: the folder does not exist")]
    MissingFolder { path: String },
    /// An output path that is one of the run's own inputs.
    #[error(
        "{path}: is also the input {input}; give the output another name (it would be replaced)"
    )]
    IsInput { path: String, input: String },
    /// A file larger than its limit.
    #[error("{path}: {size} bytes, at most {limit} are accepted")]
    TooLarge { path: String, size: u64, limit: u64 },
    /// An operating-system error.
    #[error("{path}: cannot {action}: {source}")]
    Io {
        path: String,
        action: &'static str,
        source: std::io::Error,
    },
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, FileError>;

pub(crate) fn io(path: &Path, action: &'static str) -> impl FnOnce(std::io::Error) -> FileError {
    let path = path.display().to_string();
    move |source| FileError::Io {
        path,
        action,
        source,
    }
}

/// What kind of file `meta` (from [`std::fs::symlink_metadata`]) describes, in words.
pub fn kind(meta: &Metadata) -> &'static str {
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "FIFO (named pipe)";
        }
        if t.is_char_device() {
            return "character device";
        }
        if t.is_block_device() {
            return "block device";
        }
        if t.is_socket() {
            return "socket";
        }
    }
    if t.is_dir() {
        "directory"
    } else if t.is_symlink() {
        "symbolic link"
    } else if t.is_file() {
        "regular file"
    } else {
        "special file"
    }
}

/// Checks that `path` can be written as a file: missing or a writable regular file (not a
/// directory, FIFO, device, socket or symbolic link), in an existing folder this process can
/// create a file in (probed with a temporary file, removed at once). Changes nothing.
///
/// # Errors
/// [`FileError::NotRegular`] naming the kind of file, [`FileError::ReadOnly`] for a read-only
/// file, or [`FileError::Io`] for a folder that is missing or not writable.
pub fn check_output(path: &Path) -> Result<()> {
    if let Ok(meta) = std::fs::symlink_metadata(path) {
        if !meta.file_type().is_file() {
            return Err(FileError::NotRegular {
                path: path.display().to_string(),
                kind: kind(&meta),
                why: "not replaced (give the name of a new or regular file)",
            });
        }
        if meta.permissions().readonly() {
            return Err(FileError::ReadOnly {
                path: path.display().to_string(),
            });
        }
    }
    if path.as_os_str().to_string_lossy().ends_with(['/', '\\']) || path.file_name().is_none() {
        return Err(FileError::NotRegular {
            path: path.display().to_string(),
            kind: "folder name",
            why: "give a file name",
        });
    }
    probe_folder(&folder_of(path))
}

/// Most entries [`check_output_tree`] looks at.
pub const MAX_TREE_ENTRIES: usize = 100_000;

/// Checks, before a long run writes many files under `dir`, that nothing already there is in
/// the way: no FIFO, device, socket or symbolic link anywhere below `dir`, and no folder named
/// like one of the files it writes (a name ending in `.EXT` for EXT in `extensions`). A
/// missing `dir` passes.
///
/// # Errors
/// [`FileError::NotRegular`] naming the first such path; [`FileError::TooLarge`] (counting
/// entries) beyond [`MAX_TREE_ENTRIES`]; [`FileError::Io`] if a folder cannot be listed.
pub fn check_output_tree(dir: &Path, extensions: &[&str]) -> Result<()> {
    let mut stack = vec![dir.to_path_buf()];
    let mut seen = 0u64;
    while let Some(d) = stack.pop() {
        let entries = match std::fs::read_dir(&d) {
            Ok(entries) => entries,
            Err(e) if d == dir && e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
            Err(e) => return Err(io(&d, "list the folder")(e)),
        };
        for e in entries {
            let path = e.map_err(io(&d, "list the folder"))?.path();
            seen += 1;
            if seen > MAX_TREE_ENTRIES as u64 {
                return Err(FileError::TooLarge {
                    path: dir.display().to_string(),
                    size: seen,
                    limit: MAX_TREE_ENTRIES as u64,
                });
            }
            let meta = std::fs::symlink_metadata(&path).map_err(io(&path, "inspect"))?;
            let named_like_output = path
                .extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| extensions.contains(&x));
            if meta.is_dir() && named_like_output {
                return Err(FileError::NotRegular {
                    path: path.display().to_string(),
                    kind: kind(&meta),
                    why: "the run writes a file of this name (not replaced)",
                });
            } else if meta.is_dir() {
                stack.push(path);
            } else if !meta.is_file() {
                return Err(FileError::NotRegular {
                    path: path.display().to_string(),
                    kind: kind(&meta),
                    why: "in the output folder, where the run may write (not replaced)",
                });
            }
        }
    }
    Ok(())
}

/// Checks that the output `out` is not the same file as any of `inputs` (same device and
/// inode, so other names of it — `./a`, a hard link, a symbolic link — count too). Paths that
/// do not exist yet cannot be inputs; `None` stands for an input the run does not have.
///
/// # Errors
/// [`FileError::IsInput`] naming the output and the input.
pub fn check_not_input(out: &Path, inputs: &[Option<&Path>]) -> Result<()> {
    if std::fs::metadata(out).is_err() {
        return Ok(());
    }
    match inputs.iter().flatten().find(|input| same_file(out, input)) {
        Some(input) => Err(FileError::IsInput {
            path: out.display().to_string(),
            input: input.display().to_string(),
        }),
        None => Ok(()),
    }
}

/// Whether the existing paths `a` and `b` name the same file.
#[cfg(unix)]
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => (a.dev(), a.ino()) == (b.dev(), b.ino()),
        _ => false,
    }
}

/// Whether the existing paths `a` and `b` name the same file.
#[cfg(not(unix))]
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// Checks that `dir` can hold output files: missing (it is created, with its parents) or a
/// directory this process can create files in, and that none of `files` in it exists as
/// anything but a regular file.
///
/// # Errors
/// As [`check_output`], for the folder and each file.
pub fn check_output_dir(dir: &Path, files: &[&str]) -> Result<()> {
    if let Ok(meta) = std::fs::metadata(dir) {
        if !meta.is_dir() {
            return Err(FileError::NotFolder {
                path: dir.display().to_string(),
                kind: kind(&std::fs::symlink_metadata(dir).unwrap_or(meta)),
            });
        }
    }
    std::fs::create_dir_all(dir).map_err(io(dir, "create the folder"))?;
    probe_folder(dir)?;
    files.iter().try_for_each(|f| check_output(&dir.join(f)))
}

/// The folder of `path` (`.` for a bare file name).
pub(crate) fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Creates and removes a temporary file in `dir`.
fn probe_folder(dir: &Path) -> Result<()> {
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(m) => {
            return Err(FileError::NotFolder {
                path: dir.display().to_string(),
                kind: kind(&m),
            })
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(FileError::MissingFolder {
                path: dir.display().to_string(),
            })
        }
        Err(e) => return Err(io(dir, "use the folder")(e)),
    }
    let (tmp, file) = write::create_temp(&dir.join(".osrl-write-probe"))
        .map_err(io(dir, "create a file in the folder"))?;
    drop(file);
    let _ = std::fs::remove_file(tmp);
    Ok(())
}

/// Reads `path`, a regular file (symbolic links followed) of at most `limit` bytes.
///
/// # Errors
/// [`FileError::NotRegular`] for a directory, FIFO, device or socket (checked before opening
/// it); [`FileError::TooLarge`] beyond `limit`; [`FileError::Io`] if it cannot be read.
pub fn read_limited(path: &Path, limit: u64) -> Result<Vec<u8>> {
    read_from(path, limit, None)
}

/// As [`read_limited`], but the whole file only if it starts with one of `starts` (a format's
/// magic bytes): otherwise only its first bytes (as many as the longest of `starts`), on which
/// the caller's decoder gives its own error at once, without reading a large file that is not
/// of its format.
///
/// # Errors
/// As [`read_limited`].
pub fn read_limited_if_starts(path: &Path, limit: u64, starts: &[&[u8]]) -> Result<Vec<u8>> {
    read_from(path, limit, Some(starts))
}

/// [`read_limited`] through one open file; with `starts`, the file's first bytes are read
/// first and the rest only if they begin with one of `starts`.
fn read_from(path: &Path, limit: u64, starts: Option<&[&[u8]]>) -> Result<Vec<u8>> {
    let (mut file, meta) = open_regular(path)?;
    let mut bytes = Vec::new();
    if let Some(starts) = starts {
        let head = starts.iter().map(|s| s.len()).max().unwrap_or(0) as u64;
        file.by_ref()
            .take(head.min(limit))
            .read_to_end(&mut bytes)
            .map_err(io(path, "read"))?;
        if !starts.iter().any(|s| bytes.starts_with(s)) {
            return Ok(bytes);
        }
    }
    let too_large = |size| FileError::TooLarge {
        path: path.display().to_string(),
        size,
        limit,
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    bytes.reserve((meta.len() as usize).saturating_sub(bytes.len()));
    // A file that grew since: read one byte beyond the limit to notice.
    let rest = limit.saturating_add(1) - bytes.len() as u64;
    file.take(rest)
        .read_to_end(&mut bytes)
        .map_err(io(path, "read"))?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// `path` opened for reading, with its metadata, if it is a regular file (symbolic links
/// followed; checked before opening, so a FIFO is never opened).
fn open_regular(path: &Path) -> Result<(std::fs::File, Metadata)> {
    let meta = std::fs::metadata(path).map_err(io(path, "read"))?;
    if !meta.is_file() {
        return Err(FileError::NotRegular {
            path: path.display().to_string(),
            kind: kind(&meta),
            why: "only regular files are read",
        });
    }
    let file = std::fs::File::open(path).map_err(io(path, "read"))?;
    Ok((file, meta))
}

/// As [`read_limited`], as UTF-8 text.
///
/// # Errors
/// As [`read_limited`], or [`FileError::Io`] (kind `InvalidData`) for text that is not UTF-8.
pub fn read_text_limited(path: &Path, limit: u64) -> Result<String> {
    let bytes = read_limited(path, limit)?;
    String::from_utf8(bytes).map_err(|e| {
        let line = e.as_bytes()[..e.utf8_error().valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        FileError::Io {
            path: format!("{}:{line}", path.display()),
            action: "read the text",
            source: std::io::Error::new(std::io::ErrorKind::InvalidData, "not UTF-8"),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file that does not start with the format's magic is read no further than it.
    #[test]
    fn a_file_of_another_format_is_not_read_whole() {
        let d = std::env::temp_dir().join(format!("osrl-files-head-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let (ours, other) = (d.join("ours"), d.join("other"));
        std::fs::write(&ours, b"MAGICrest of it").unwrap();
        std::fs::write(&other, b"NOTMAGIC and much more").unwrap();
        let starts: &[&[u8]] = &[b"MAGIC", b"OLD"];
        let read = |p: &Path, limit| read_limited_if_starts(p, limit, starts);
        assert_eq!(read(&ours, 100).unwrap(), b"MAGICrest of it");
        assert_eq!(read(&other, 100).unwrap(), b"NOTMA");
        assert!(matches!(read(&ours, 10), Err(FileError::TooLarge { .. })));
        assert!(matches!(read(&d, 10), Err(FileError::NotRegular { .. })));
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// An output that is an input under any of its names is refused; others pass.
    #[cfg(unix)]
    #[test]
    fn an_output_that_is_an_input_is_refused() {
        let dir = std::env::temp_dir().join(format!("osrl-files-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
        std::fs::write(&a, "1,2\n").unwrap();
        std::fs::write(&b, "1,2\n").unwrap();
        let other_name = dir.join(".").join("a.csv");
        let e = check_not_input(&other_name, &[Some(&b), None, Some(&a)])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("is also the input") && e.contains("a.csv"),
            "{e}"
        );
        let link = dir.join("link.csv");
        std::fs::hard_link(&a, &link).unwrap();
        assert!(check_not_input(&link, &[Some(&a)]).is_err());
        assert!(check_not_input(&b, &[Some(&a)]).is_ok());
        assert!(check_not_input(&dir.join("new.osrl"), &[Some(&a)]).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A missing or ordinary output tree passes; a link or a folder named like an output, at
    /// any depth, is refused with its path.
    #[cfg(unix)]
    #[test]
    fn an_output_tree_with_a_link_or_a_misnamed_folder_is_refused() {
        let dir = std::env::temp_dir().join(format!("osrl-files-tree-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        assert!(check_output_tree(&dir, &["png"]).is_ok());
        let deep = dir.join("E1").join("a");
        std::fs::create_dir_all(&deep).unwrap();
        std::fs::write(deep.join("x.png"), "old").unwrap();
        assert!(check_output_tree(&dir, &["png"]).is_ok());
        std::os::unix::fs::symlink(deep.join("x.png"), deep.join("y.png")).unwrap();
        let e = check_output_tree(&dir, &["png"]).unwrap_err().to_string();
        assert!(e.contains("y.png") && e.contains("symbolic link"), "{e}");
        std::fs::remove_file(deep.join("y.png")).unwrap();
        std::fs::create_dir(deep.join("z.png")).unwrap();
        let e = check_output_tree(&dir, &["png"]).unwrap_err().to_string();
        assert!(e.contains("z.png"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

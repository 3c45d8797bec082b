//! Writing a replay's files without harm to anything else on the disk.
//!
//! A trace names its dump files, so a hostile trace picks names in the output folder. A
//! [`DumpDir`] therefore writes each dump to a new temporary file in the folder (created
//! exclusively, so never through a link or into a FIFO) and renames it over the dump's
//! name, and replaces nothing there but an *earlier dump*:
//!
//! * nothing at that name: the dump is created;
//! * a regular file (not a symbolic link) with no other hard link, that is not a file the
//!   folder was told to protect ([`DumpDir::protect`], e.g. the trace being replayed): it
//!   is taken for an earlier dump (of this run or an earlier one) and replaced;
//! * anything else (a symbolic link, a FIFO, a directory, a device, a socket, a file with
//!   other hard links, a protected file): refused with [`OutputError::Refused`].
//!
//! The rename replaces the name in the folder, never the file behind it: a link at the
//! name is never followed, and no file is ever opened for writing but the new temporary
//! one. A folder made by [`DumpDir::create_fresh`] starts empty, so everything in it is
//! this run's; in a folder the user names (`--out`), the user has given the trace leave to
//! replace regular files there by the names it dumps to.
//!
//! [`write_file_replacing`] writes a file the user named (a PNG, a JSON report) the same
//! way: a temporary file beside it, renamed over it, and nothing but an absent name or a
//! regular file replaced.

use std::fs::{File, Metadata, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::{check_dump_name, quote, DUMP_NAME_RULE};

/// A file could not be written, or was not because something else is at its name.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The OS refused.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What the OS said.
        source: std::io::Error,
    },
    /// Something that is not ours to replace is at the name.
    #[error("{path}: {reason}; not replaced")]
    Refused {
        /// The name.
        path: PathBuf,
        /// What is there.
        reason: &'static str,
    },
    /// A dump name that is not a bare file name.
    #[error("dump name {name}: expected {DUMP_NAME_RULE}")]
    BadName {
        /// The name, quoted.
        name: String,
    },
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io {
        path: path.to_owned(),
        source,
    }
}

/// The identity of a file: device and inode.
#[cfg(unix)]
fn identity(meta: &Metadata) -> (u64, u64) {
    use std::os::unix::fs::MetadataExt;
    (meta.dev(), meta.ino())
}

#[cfg(not(unix))]
fn identity(_meta: &Metadata) -> (u64, u64) {
    (0, 0)
}

/// How many names a file has.
#[cfg(unix)]
fn links(meta: &Metadata) -> u64 {
    use std::os::unix::fs::MetadataExt;
    meta.nlink()
}

#[cfg(not(unix))]
fn links(_meta: &Metadata) -> u64 {
    1
}

/// What is at a name, if it is not a plain regular file: the reason to refuse it.
fn not_regular(meta: &Metadata) -> Option<&'static str> {
    let kind = meta.file_type();
    if kind.is_symlink() {
        Some("is a symbolic link")
    } else if kind.is_dir() {
        Some("is a directory")
    } else if !kind.is_file() {
        Some("is not a regular file (a FIFO, socket or device)")
    } else {
        None
    }
}

/// Creates a new temporary file in `dir`, exclusively (never an existing name, never
/// through a link): its path and the open file. Its name holds a `#`, which no dump name
/// may, so it cannot be a dump's.
fn create_temp(dir: &Path) -> Result<(PathBuf, File), OutputError> {
    static SEQUENCE: AtomicU64 = AtomicU64::new(0);
    let mut last = None;
    for _ in 0..100 {
        let n = SEQUENCE.fetch_add(1, Ordering::Relaxed);
        let path = dir.join(format!("#voodoo-{}-{n}.tmp", std::process::id()));
        let mut options = OpenOptions::new();
        options.write(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::OpenOptionsExt;
            options.custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC);
            options.mode(0o666);
        }
        match options.open(&path) {
            Ok(file) => return Ok((path, file)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(io_error(&path)(e)),
        }
    }
    Err(OutputError::Io {
        path: dir.to_owned(),
        source: last.unwrap_or_else(|| std::io::Error::other("no free temporary name")),
    })
}

/// Writes what `contents` writes to a new temporary file in `dir` and renames it to
/// `target`, if
/// `allowed` accepts what is at `target` now (`None`: nothing). The temporary file is
/// removed on failure.
fn replace(
    dir: &Path,
    target: &Path,
    contents: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    allowed: impl Fn(Option<&Metadata>) -> Result<(), &'static str>,
) -> Result<(), OutputError> {
    let check = || -> Result<(), OutputError> {
        let meta = match std::fs::symlink_metadata(target) {
            Ok(meta) => Some(meta),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => return Err(io_error(target)(e)),
        };
        allowed(meta.as_ref()).map_err(|reason| OutputError::Refused {
            path: target.to_owned(),
            reason,
        })
    };
    check()?;
    let (temp, file) = create_temp(dir)?;
    let mut file = std::io::BufWriter::with_capacity(64 << 10, file);
    let result = contents(&mut file)
        .and_then(|()| file.flush())
        .map_err(io_error(&temp))
        .and_then(|()| {
            drop(file);
            // Checked again just before the rename, which replaces whatever is at the
            // name itself (never a file behind a link).
            check()?;
            std::fs::rename(&temp, target).map_err(io_error(target))
        });
    if result.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    result
}

/// A folder that a replay writes its dumps into (see the [module docs](self) for what a
/// dump may replace).
#[derive(Clone, Debug)]
pub struct DumpDir {
    dir: PathBuf,
    /// Files never to replace, by identity.
    protected: Vec<(u64, u64)>,
}

impl DumpDir {
    /// An existing folder (the user's `--out`).
    pub fn existing(dir: impl Into<PathBuf>) -> Self {
        Self {
            dir: dir.into(),
            protected: Vec::new(),
        }
    }

    /// Creates a new, empty folder in `parent` (`""`: the current folder) named after
    /// `stem`: `STEM-dumps`, or `STEM-dumps-2`, `-3`, … if that name is taken.
    pub fn create_fresh(parent: &Path, stem: &str) -> Result<Self, OutputError> {
        let mut last = None;
        for n in 1..=1000 {
            let name = if n == 1 {
                format!("{stem}-dumps")
            } else {
                format!("{stem}-dumps-{n}")
            };
            let dir = parent.join(name);
            match std::fs::create_dir(&dir) {
                Ok(()) => return Ok(Self::existing(dir)),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
                Err(e) => return Err(io_error(&dir)(e)),
            }
        }
        Err(OutputError::Io {
            path: parent.join(format!("{stem}-dumps")),
            source: last.unwrap_or_else(|| std::io::Error::other("no free folder name")),
        })
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Never replace `file` (e.g. the trace being replayed), whatever name it has in the
    /// folder. A file that cannot be found needs no protection and is ignored.
    pub fn protect(&mut self, file: &Path) {
        if let Ok(meta) = std::fs::metadata(file) {
            self.protected.push(identity(&meta));
        }
    }

    /// Writes a dump called `name` (a bare file name, [`check_dump_name`]) into the folder:
    /// through a new temporary file renamed over `name`, if nothing is there or an earlier
    /// dump is. Returns the path written.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, OutputError> {
        self.write_with(name, |out| out.write_all(bytes))
    }

    /// As [`DumpDir::write`], the contents written by `contents` (e.g.
    /// [`Dump::write_le`](crate::Dump::write_le), with no copy of the dump in memory).
    pub fn write_with(
        &self,
        name: &str,
        contents: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<PathBuf, OutputError> {
        check_dump_name(name).map_err(|_| OutputError::BadName { name: quote(name) })?;
        let target = self.dir.join(name);
        replace(&self.dir, &target, contents, |meta| match meta {
            None => Ok(()),
            Some(meta) => {
                if let Some(reason) = not_regular(meta) {
                    Err(reason)
                } else if links(meta) != 1 {
                    Err("is a file with other hard links, not an earlier dump")
                } else if self.protected.contains(&identity(meta)) {
                    Err("is an input of this run")
                } else {
                    Ok(())
                }
            }
        })?;
        Ok(target)
    }
}

/// Writes a file the user named: `bytes` go to a new temporary file in the same folder,
/// renamed over `path`. Replaces a regular file; refuses anything else at `path` (a
/// symbolic link, a FIFO, a device, a directory), so it never blocks and never writes
/// through a link.
pub fn write_file_replacing(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    replace(
        dir,
        path,
        |out| out.write_all(bytes),
        |meta| match meta.and_then(not_regular) {
            Some(reason) => Err(reason),
            None => Ok(()),
        },
    )
}

//! Reading files a user or a peer hands over: regular files only, never more than a limit.
//!
//! A path may name a FIFO (opening it blocks until a writer comes), a device such as
//! `/dev/zero` (endless, with a size of 0), a directory, or a file far larger than any
//! level or replay. [`read`] refuses what is not a regular file before opening it, and
//! reads at most `limit + 1` bytes whatever the file claims, so memory and time stay
//! bounded by the limit the caller names.

use std::io::Read;
use std::path::Path;

use thiserror::Error;

/// Why a file was not read.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ReadError {
    /// The path names something other than a regular file.
    #[error("{path} is not a regular file (it is a {kind})")]
    NotAFile {
        /// The path.
        path: String,
        /// What it is: `directory`, `FIFO`, `character device`, ...
        kind: &'static str,
    },
    /// The file holds more than the limit.
    #[error("{path} is larger than the limit of {limit} bytes")]
    TooLarge {
        /// The path.
        path: String,
        /// The limit, bytes.
        limit: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{path} is not UTF-8 text (invalid byte at offset {offset})")]
    NotText {
        /// The path.
        path: String,
        /// Offset of the first invalid byte.
        offset: usize,
    },
    /// The operating system refused.
    #[error("cannot read {path}: {message}")]
    Io {
        /// The path.
        path: String,
        /// The operating system's message.
        message: String,
    },
}

/// The bytes of the regular file at `path`, if it holds at most `limit` of them.
pub fn read(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    let shown = || path.display().to_string();
    let io = |e: std::io::Error| ReadError::Io {
        path: shown(),
        message: e.to_string(),
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(ReadError::NotAFile {
            path: shown(),
            kind: kind_of(&meta.file_type()),
        });
    }
    let too_large = || ReadError::TooLarge {
        path: shown(),
        limit,
    };
    if meta.len() > limit {
        return Err(too_large());
    }
    let file = std::fs::File::open(path).map_err(io)?;
    // The size was a hint: the file may have grown since, or lie (procfs).
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// The text of the regular file at `path` (see [`read`]).
pub fn read_text(path: &Path, limit: u64) -> Result<String, ReadError> {
    let bytes = read(path, limit)?;
    String::from_utf8(bytes).map_err(|e| ReadError::NotText {
        path: path.display().to_string(),
        offset: e.utf8_error().valid_up_to(),
    })
}

fn kind_of(t: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "FIFO";
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
    } else {
        "special file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("craterfield-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    #[test]
    fn regular_files_within_the_limit_are_read_and_others_refused() {
        let path = temp("ten");
        std::fs::write(&path, b"0123456789").unwrap();
        assert_eq!(read(&path, 10).unwrap(), b"0123456789");
        assert!(matches!(
            read(&path, 9),
            Err(ReadError::TooLarge { limit: 9, .. })
        ));
        let dir = path.parent().unwrap();
        assert!(matches!(
            read(dir, 1 << 20),
            Err(ReadError::NotAFile {
                kind: "directory",
                ..
            })
        ));
        let missing = temp("missing");
        assert!(matches!(read(&missing, 10), Err(ReadError::Io { .. })));
        std::fs::write(&path, [b'a', 0xff, b'b']).unwrap();
        let e = read_text(&path, 10).unwrap_err().to_string();
        assert!(e.contains("offset 1"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn devices_and_fifos_are_refused_without_reading_or_blocking() {
        for dev in ["/dev/zero", "/dev/urandom", "/dev/null"] {
            let e = read(Path::new(dev), 1 << 20).unwrap_err();
            assert!(
                matches!(
                    e,
                    ReadError::NotAFile {
                        kind: "character device",
                        ..
                    }
                ),
                "{dev}: {e}"
            );
        }
        // A FIFO with no writer: opening it would block for ever.
        let fifo = temp("fifo");
        let _ = std::fs::remove_file(&fifo);
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let e = read(&fifo, 1 << 20).unwrap_err();
            assert!(matches!(e, ReadError::NotAFile { kind: "FIFO", .. }), "{e}");
        }
    }
}

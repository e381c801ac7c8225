//! Reading an input file safely: only regular files, never more than a size cap.
//!
//! A FIFO, a terminal or a device (`/dev/zero`, `/dev/urandom`) given where a scenario, zones,
//! points, recipe or campaign file is expected would block or stream forever; a huge file
//! would exhaust memory. Every text input of solsim goes through [`read_text_file`], which
//! refuses both before reading: the file's type and size come from its metadata (`stat`, which
//! does not open it), and the read itself stops one byte past the cap in case the file grew.

use std::io::Read as _;
use std::path::Path;

/// Largest text input accepted (scenario, zones GeoJSON, points CSV, recipe, campaign file),
/// bytes: 16 MiB, some thousand times the bundled files.
pub const MAX_TEXT_FILE_BYTES: u64 = 16 << 20;

/// Why an input file was not read. The caller names the file and the field.
#[derive(Debug, thiserror::Error)]
pub enum InputFileError {
    /// The operating system refused (missing file, no permission …).
    #[error("cannot read the file: {error}")]
    Io {
        /// What the operating system said (part of the message, so not also a `source`).
        error: std::io::Error,
    },
    /// Not a regular file: a directory, a FIFO, a socket or a device.
    #[error("expected a regular file, got a {kind}")]
    NotRegular {
        /// What it is instead ("directory", "FIFO (named pipe)", "character device" …).
        kind: &'static str,
    },
    /// Larger than the cap.
    #[error("expected at most {} of text, got {}", crate::input_file::human_bytes(*limit_bytes), crate::input_file::exact_bytes(*bytes))]
    TooLarge {
        /// The file's size (or the bytes read before stopping), bytes.
        bytes: u64,
        /// The cap, bytes.
        limit_bytes: u64,
    },
    /// Not UTF-8 text.
    #[error("expected UTF-8 text, got an invalid byte at offset {offset}")]
    NotUtf8 {
        /// Byte offset of the first invalid sequence.
        offset: usize,
    },
}

/// What kind of file `meta` describes, for messages.
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
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
    } else {
        "special file"
    }
}

/// Checks that `path` is a regular file (following symbolic links) and returns its size,
/// bytes, without opening it.
///
/// # Errors
/// [`InputFileError::Io`] when it cannot be looked up, [`InputFileError::NotRegular`] for a
/// directory, FIFO, socket or device.
pub fn regular_file_len(path: &Path) -> Result<u64, InputFileError> {
    let meta = std::fs::metadata(path).map_err(|error| InputFileError::Io { error })?;
    if meta.is_file() {
        Ok(meta.len())
    } else {
        Err(InputFileError::NotRegular {
            kind: kind_of(&meta),
        })
    }
}

/// Reads a regular file of at most `limit_bytes` bytes.
///
/// # Errors
/// As [`regular_file_len`], and [`InputFileError::TooLarge`] past the cap.
pub fn read_file_capped(path: &Path, limit_bytes: u64) -> Result<Vec<u8>, InputFileError> {
    let len = regular_file_len(path)?;
    if len > limit_bytes {
        return Err(InputFileError::TooLarge {
            bytes: len,
            limit_bytes,
        });
    }
    let file = std::fs::File::open(path).map_err(|error| InputFileError::Io { error })?;
    let mut bytes = Vec::with_capacity(usize::try_from(len).unwrap_or(0));
    file.take(limit_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|error| InputFileError::Io { error })?;
    if bytes.len() as u64 > limit_bytes {
        return Err(InputFileError::TooLarge {
            bytes: bytes.len() as u64,
            limit_bytes,
        });
    }
    Ok(bytes)
}

/// Reads a regular UTF-8 text file of at most [`MAX_TEXT_FILE_BYTES`].
///
/// # Errors
/// As [`read_file_capped`], and [`InputFileError::NotUtf8`].
pub fn read_text_file(path: &Path) -> Result<String, InputFileError> {
    read_text_file_capped(path, MAX_TEXT_FILE_BYTES)
}

/// Reads a regular UTF-8 text file of at most `limit_bytes`.
///
/// # Errors
/// As [`read_file_capped`], and [`InputFileError::NotUtf8`].
pub fn read_text_file_capped(path: &Path, limit_bytes: u64) -> Result<String, InputFileError> {
    let bytes = read_file_capped(path, limit_bytes)?;
    String::from_utf8(bytes).map_err(|e| InputFileError::NotUtf8 {
        offset: e.utf8_error().valid_up_to(),
    })
}

/// `text` cut to at most `max_chars` characters, with `…` marking the cut: what an error
/// message quotes of an input (an offending line, a value, a name) stays one readable line.
#[must_use]
pub fn excerpt(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        None => text.to_string(),
        Some(_) => {
            let cut = text
                .char_indices()
                .nth(max_chars.saturating_sub(1))
                .map_or(text.len(), |(i, _)| i);
            format!("{}…", &text[..cut])
        }
    }
}

/// [`human_bytes`] with the exact count beside it when that is rounded (`1.0 MiB (1050000
/// bytes)`), so a size just over a limit does not read as the limit.
#[must_use]
pub fn exact_bytes(bytes: u64) -> String {
    let human = human_bytes(bytes);
    if human.ends_with(" B") {
        human
    } else {
        format!("{human} ({bytes} bytes)")
    }
}

/// A byte count for people: `512 B`, `16 MiB`, `6.4 GiB`.
#[must_use]
pub fn human_bytes(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut v = bytes as f64;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    if unit == 0 || v.fract() == 0.0 {
        format!("{v:.0} {}", UNITS[unit])
    } else {
        format!("{v:.1} {}", UNITS[unit])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_directories_devices_and_large_files() {
        let dir = tempfile::tempdir().expect("tempdir");
        let e = read_text_file(dir.path()).expect_err("a directory");
        assert_eq!(e.to_string(), "expected a regular file, got a directory");
        #[cfg(unix)]
        {
            let e = read_text_file(Path::new("/dev/zero")).expect_err("a device");
            assert_eq!(
                e.to_string(),
                "expected a regular file, got a character device"
            );
        }
        let p = dir.path().join("big.toml");
        std::fs::write(&p, vec![b'#'; 100]).expect("write");
        let e = read_file_capped(&p, 99).expect_err("too large");
        assert_eq!(e.to_string(), "expected at most 99 B of text, got 100 B");
        assert_eq!(read_file_capped(&p, 100).expect("at the cap").len(), 100);
        let e = read_text_file(&dir.path().join("missing")).expect_err("missing");
        assert!(e.to_string().starts_with("cannot read the file: "), "{e}");
    }

    #[test]
    fn human_bytes_reads_well() {
        assert_eq!(human_bytes(512), "512 B");
        assert_eq!(human_bytes(16 << 20), "16 MiB");
        assert_eq!(human_bytes(6_871_947_674), "6.4 GiB");
    }
}

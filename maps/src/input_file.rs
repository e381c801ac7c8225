//! The one input gate: every file solsim reads is opened here, checked on the opened
//! descriptor, and read within a size cap.
//!
//! A FIFO, a terminal or a device (`/dev/zero`, `/dev/urandom`) given where a scenario, zones,
//! points, recipe, campaign file, raster or sweep table is expected would block or stream
//! forever; a huge file would exhaust memory. [`open_input`] opens the path without blocking
//! (`O_NONBLOCK`: opening a FIFO with no writer returns at once), then asks the *opened
//! descriptor* (`fstat`) what it is and how large: checking the path first and opening it after
//! lets a path flipped in between (a regular file swapped for a FIFO) through. Reads stop one
//! byte past the cap in case the file grew. Inside a directory solsim owns (a sweep directory),
//! [`Follow::No`] refuses a symbolic link instead of reading what it points at.

use std::fs::File;
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

/// Whether [`open_input`] follows a symbolic link at the path's last component.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Follow {
    /// A path the user named: a link to a regular file is read.
    Yes,
    /// A file inside a directory solsim owns: a link is refused (`O_NOFOLLOW`), so nothing
    /// outside that directory is read, or later removed, through it.
    No,
}

/// Opens `path` for reading and checks the opened descriptor: a regular file of at most
/// `limit_bytes`. Returns the file and its size, bytes.
///
/// The open never blocks (`O_NONBLOCK`, a no-op for regular files); the type and size come
/// from `fstat` on the descriptor, so a path that changes between a check and the open cannot
/// slip a FIFO or a device through.
///
/// # Errors
/// [`InputFileError::Io`] when it cannot be opened (missing, no permission, a symbolic link
/// under [`Follow::No`]: `ELOOP`), [`InputFileError::NotRegular`] for a directory, FIFO,
/// socket or device, [`InputFileError::TooLarge`] past the cap.
pub fn open_input(
    path: &Path,
    limit_bytes: u64,
    follow: Follow,
) -> Result<(File, u64), InputFileError> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        let nofollow = if follow == Follow::No {
            libc::O_NOFOLLOW
        } else {
            0
        };
        options.custom_flags(libc::O_NONBLOCK | nofollow);
    }
    let file = options.open(path).map_err(|error| {
        #[cfg(unix)]
        if follow == Follow::No && error.raw_os_error() == Some(libc::ELOOP) {
            return InputFileError::NotRegular {
                kind: "symbolic link (refused inside a directory solsim owns)",
            };
        }
        InputFileError::Io { error }
    })?;
    let meta = file
        .metadata()
        .map_err(|error| InputFileError::Io { error })?;
    if !meta.is_file() {
        return Err(InputFileError::NotRegular {
            kind: kind_of(&meta),
        });
    }
    if meta.len() > limit_bytes {
        return Err(InputFileError::TooLarge {
            bytes: meta.len(),
            limit_bytes,
        });
    }
    Ok((file, meta.len()))
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
/// bytes, without opening it. Only for a message before anything is read (a scenario naming
/// its map files); the read itself goes through [`open_input`], which checks again on the
/// descriptor.
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

/// Reads a regular file of at most `limit_bytes` bytes (through [`open_input`]).
///
/// # Errors
/// As [`open_input`].
pub fn read_file_capped(path: &Path, limit_bytes: u64) -> Result<Vec<u8>, InputFileError> {
    read_input(path, limit_bytes, Follow::Yes)
}

/// Reads a file through [`open_input`] into memory.
///
/// # Errors
/// As [`open_input`], and [`InputFileError::TooLarge`] if the file grew past the cap while it
/// was read.
pub fn read_input(
    path: &Path,
    limit_bytes: u64,
    follow: Follow,
) -> Result<Vec<u8>, InputFileError> {
    let (file, len) = open_input(path, limit_bytes, follow)?;
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

/// `text` cut to at most `max_chars` characters, with `…` marking the cut, and its control
/// characters escaped ([`printable`]): what an error message quotes of an input (an offending
/// line, a value, a name) stays one readable line and can never drive the terminal.
#[must_use]
pub fn excerpt(text: &str, max_chars: usize) -> String {
    let text = printable(text);
    match text.char_indices().nth(max_chars) {
        None => text.into_owned(),
        Some(_) => {
            let cut = text
                .char_indices()
                .nth(max_chars.saturating_sub(1))
                .map_or(text.len(), |(i, _)| i);
            format!("{}…", &text[..cut])
        }
    }
}

/// Whether `c` may not reach a terminal, a generated script or an XML document as it is: the
/// C0 and C1 control characters (NUL, ESC, newline, carriage return, bell …), DEL, and the
/// Unicode bidirectional overrides and isolates that reorder what a terminal shows.
#[must_use]
pub fn is_unsafe_char(c: char) -> bool {
    c.is_control() || matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
}

/// The first character of `text` that [`is_unsafe_char`], with its byte offset.
#[must_use]
pub fn first_unsafe_char(text: &str) -> Option<(usize, char)> {
    text.char_indices().find(|&(_, c)| is_unsafe_char(c))
}

/// `text` with every [`is_unsafe_char`] character written as its escape (`\u{1b}` for ESC,
/// `\n` for a newline): a name or a value from an input file printed to a terminal or
/// written to a report shows what it holds and does nothing else.
#[must_use]
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    if first_unsafe_char(text).is_none() {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if is_unsafe_char(c) {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
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
    fn control_characters_are_escaped() {
        assert_eq!(printable("plain é"), "plain é");
        assert_eq!(printable("a\u{1b}]0;x\u{7}b"), "a\\u{1b}]0;x\\u{7}b");
        assert_eq!(printable("x\ny\0"), "x\\ny\\u{0}");
        assert_eq!(printable("\u{202e}abc"), "\\u{202e}abc");
        assert_eq!(first_unsafe_char("ok\u{85}"), Some((2, '\u{85}')));
        assert_eq!(excerpt("\u{1b}[2J", 80), "\\u{1b}[2J");
    }

    #[test]
    fn the_gate_checks_the_opened_descriptor() {
        let dir = tempfile::tempdir().expect("tempdir");
        let file = dir.path().join("a.txt");
        std::fs::write(&file, b"abc").expect("write");
        let link = dir.path().join("link");
        std::os::unix::fs::symlink(&file, &link).expect("symlink");
        assert_eq!(
            read_input(&link, 10, Follow::Yes).expect("followed"),
            b"abc"
        );
        let e = read_input(&link, 10, Follow::No).expect_err("a link inside a sweep dir");
        assert!(e.to_string().contains("symbolic link"), "{e}");
        let fifo = dir.path().join("fifo");
        let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).expect("path");
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let e = read_input(&fifo, 10, Follow::Yes).expect_err("a FIFO, without blocking");
        assert_eq!(
            e.to_string(),
            "expected a regular file, got a FIFO (named pipe)"
        );
    }

    #[test]
    fn human_bytes_reads_well() {
        assert_eq!(human_bytes(512), "512 B");
        assert_eq!(human_bytes(16 << 20), "16 MiB");
        assert_eq!(human_bytes(6_871_947_674), "6.4 GiB");
    }
}

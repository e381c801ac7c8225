//! Mutations of one input: byte-level (flip, overwrite, insert, delete, duplicate a chunk,
//! splice with another input, truncate) here, text-aware ones in [`text`] (extreme numbers,
//! hostile strings, lines, TOML tables, bracketed spans, deep nesting, identifiers) and
//! binary-aware ones in [`binary`] (PNG chunks with their CRCs fixed, TIFF IFD entries and the
//! values they point at).

mod binary;
mod text;

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use binary::{INTERESTING_U32, png_op, tiff_op};
pub use binary::{crc32, fix_png_crcs, png_chunk, zlib_zeros};
use text::line_start;

/// What an input is, for the structure-aware mutations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// TOML text (scenarios, campaign files, recipes).
    Toml,
    /// JSON text (zones GeoJSON).
    Json,
    /// CSV text (points).
    Csv,
    /// PNG bytes.
    Png,
    /// TIFF bytes.
    Tiff,
}

impl Format {
    /// Whether inputs are text (the parser takes `&str`).
    pub fn is_text(self) -> bool {
        matches!(self, Format::Toml | Format::Json | Format::Csv)
    }
}

/// Bytes worth writing anywhere: delimiters of every format, sign and exponent characters, NUL,
/// high bytes (invalid UTF-8), and the integer edges.
const INTERESTING_BYTES: &[u8] = &[
    0, 1, 0x7f, 0x80, 0xff, 0xfe, b'\n', b'\r', b'\t', b' ', b'"', b'\'', b'\\', b'[', b']', b'{',
    b'}', b',', b'=', b':', b'.', b'-', b'+', b'e', b'#', b'0', b'9',
];

/// How to mutate inputs of one target.
pub struct Mutator<'a> {
    /// The inputs' format.
    pub format: Format,
    /// Tokens of the format worth inserting (field names, keywords, paths).
    pub dict: &'a [Vec<u8>],
    /// Longest input produced, bytes (longer results are truncated).
    pub max_len: usize,
    /// Only value-level mutations that mostly keep the syntax (extreme numbers, hostile strings,
    /// dropped lines, inserted tokens), one or two at a time: for targets where each input is
    /// expensive and should reach the validation behind the parser.
    pub gentle: bool,
}

pub(super) fn below(rng: &mut ChaCha8Rng, n: usize) -> usize {
    if n == 0 { 0 } else { rng.random_range(0..n) }
}

pub(super) fn pick<'t, T>(rng: &mut ChaCha8Rng, items: &'t [T]) -> &'t T {
    &items[below(rng, items.len())]
}

/// A repetition count: mostly small, sometimes large (amplification).
pub(super) fn repeat_count(rng: &mut ChaCha8Rng) -> usize {
    *pick(rng, &[1, 1, 1, 2, 3, 8, 64, 500, 5000])
}

impl Mutator<'_> {
    /// `base` changed by one to eight stacked mutations (`pool` supplies splice partners), with
    /// the names of the mutations applied.
    pub fn mutate(
        &self,
        rng: &mut ChaCha8Rng,
        base: &[u8],
        pool: &[Vec<u8>],
    ) -> (Vec<u8>, Vec<&'static str>) {
        let mut data = base.to_vec();
        let mut ops = Vec::new();
        let mut n = 1;
        while n < 8 && rng.random_bool(0.45) {
            n += 1;
        }
        if self.gentle {
            let n = 1 + below(rng, 2);
            for _ in 0..n {
                ops.push(self.gentle_op(rng, &mut data));
            }
            return (data, ops);
        }
        for _ in 0..n {
            let op = if self.format.is_text() && rng.random_bool(0.75) {
                self.text_op(rng, &mut data)
            } else if !self.format.is_text() && rng.random_bool(0.6) {
                match self.format {
                    Format::Png => png_op(rng, &mut data),
                    _ => tiff_op(rng, &mut data),
                }
            } else {
                self.byte_op(rng, &mut data, pool)
            };
            ops.push(op);
            data.truncate(self.max_len);
        }
        // A chunk CRC is the first thing a PNG decoder checks: mostly keep them right so the
        // mutations reach the decoder behind it.
        if self.format == Format::Png && rng.random_bool(0.8) {
            fix_png_crcs(&mut data);
        }
        (data, ops)
    }

    fn byte_op(&self, rng: &mut ChaCha8Rng, d: &mut Vec<u8>, pool: &[Vec<u8>]) -> &'static str {
        match below(rng, 9) {
            0 if !d.is_empty() => {
                let i = below(rng, d.len());
                d[i] ^= 1 << below(rng, 8);
                "flip-bit"
            }
            1 if !d.is_empty() => {
                let i = below(rng, d.len());
                d[i] = if rng.random_bool(0.5) {
                    *pick(rng, INTERESTING_BYTES)
                } else {
                    rng.random()
                };
                "set-byte"
            }
            2 => {
                let i = below(rng, d.len() + 1);
                let k = 1 + below(rng, 16);
                let bytes: Vec<u8> = (0..k)
                    .map(|_| {
                        if rng.random_bool(0.5) {
                            *pick(rng, INTERESTING_BYTES)
                        } else {
                            rng.random()
                        }
                    })
                    .collect();
                d.splice(i..i, bytes);
                "insert-bytes"
            }
            3 if !d.is_empty() => {
                let i = below(rng, d.len());
                let max = if rng.random_bool(0.8) { 16 } else { d.len() };
                let k = 1 + below(rng, max.min(d.len() - i));
                d.drain(i..i + k);
                "delete-range"
            }
            4 if !d.is_empty() => {
                let a = below(rng, d.len());
                let k = 1 + below(rng, 256.min(d.len() - a));
                let chunk = d[a..a + k].to_vec();
                let reps = repeat_count(rng).min(self.max_len / k.max(1));
                let at = below(rng, d.len() + 1);
                d.splice(at..at, chunk.iter().copied().cycle().take(k * reps));
                "duplicate-chunk"
            }
            5 if !pool.is_empty() => {
                let other = pick(rng, pool);
                let i = below(rng, d.len() + 1);
                let j = below(rng, other.len() + 1);
                d.truncate(i);
                d.extend_from_slice(&other[j..]);
                "splice"
            }
            6 if !d.is_empty() => {
                d.truncate(below(rng, d.len()));
                "truncate"
            }
            7 if !self.dict.is_empty() => {
                let token = pick(rng, self.dict).clone();
                let i = if self.format.is_text() && rng.random_bool(0.5) {
                    line_start(d, below(rng, d.len() + 1))
                } else {
                    below(rng, d.len() + 1)
                };
                d.splice(i..i, token);
                "insert-token"
            }
            _ if d.len() >= 4 => {
                let i = below(rng, d.len() - 3);
                let v = *pick(rng, INTERESTING_U32);
                let bytes = if rng.random_bool(0.5) {
                    v.to_le_bytes()
                } else {
                    v.to_be_bytes()
                };
                let w = *pick(rng, &[1usize, 2, 4]);
                d[i..i + w].copy_from_slice(&bytes[..w]);
                "set-int"
            }
            _ => {
                d.push(rng.random());
                "push-byte"
            }
        }
    }
}

//! Binary-aware mutations: PNG chunks (IHDR fields, chunk bytes, lengths, duplicated, dropped
//! or inserted chunks, zlib bombs) with their CRCs fixed, and TIFF IFD entries (tag, type,
//! count, value, next-IFD pointer, the doubles behind an entry).

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::{below, pick};

/// 32-bit values for binary headers and TIFF fields.
pub(super) const INTERESTING_U32: &[u32] = &[
    0,
    1,
    2,
    3,
    4,
    7,
    8,
    12,
    16,
    32,
    64,
    255,
    256,
    257,
    4096,
    0x7fff,
    0x8000,
    0xffff,
    0x1_0000,
    46_000,
    100_000,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_fffe,
    0xffff_ffff,
];

/// Doubles for georeference values stored in binary files.
const INTERESTING_F64: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1e300,
    -1e300,
    1e-300,
    5e-324,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::MAX,
    1e20,
    -1e20,
    4e9,
];

// --- PNG -------------------------------------------------------------------------------------

const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// The chunks of a PNG: (offset of the length field, data length, type), as far as they parse.
fn png_chunks(d: &[u8]) -> Vec<(usize, usize, [u8; 4])> {
    let mut chunks = Vec::new();
    let mut at = PNG_SIGNATURE.len();
    while at + 12 <= d.len() {
        let len = u32::from_be_bytes([d[at], d[at + 1], d[at + 2], d[at + 3]]) as usize;
        if at + 12 + len > d.len() {
            break;
        }
        chunks.push((at, len, [d[at + 4], d[at + 5], d[at + 6], d[at + 7]]));
        at += 12 + len;
    }
    chunks
}

/// Rewrites the CRC of every chunk that parses.
pub fn fix_png_crcs(d: &mut [u8]) {
    for (at, len, _) in png_chunks(d) {
        let crc = crc32(&d[at + 4..at + 8 + len]);
        d[at + 8 + len..at + 12 + len].copy_from_slice(&crc.to_be_bytes());
    }
}

/// A complete chunk of `kind` holding `data`.
pub fn png_chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut c = Vec::with_capacity(data.len() + 12);
    c.extend_from_slice(
        &u32::try_from(data.len())
            .expect("chunk under 4 GiB")
            .to_be_bytes(),
    );
    c.extend_from_slice(kind);
    c.extend_from_slice(data);
    c.extend_from_slice(&crc32(&c[4..]).to_be_bytes());
    c
}

pub(super) fn png_op(rng: &mut ChaCha8Rng, d: &mut Vec<u8>) -> &'static str {
    let chunks = png_chunks(d);
    if chunks.is_empty() {
        return "png-unparsed";
    }
    let &(at, len, _) = pick(rng, &chunks);
    match below(rng, 6) {
        0 => {
            // IHDR: width, height (4 bytes each), bit depth, colour type, compression,
            // filter, interlace.
            let Some(&(h, 13, _)) = chunks.iter().find(|c| &c.2 == b"IHDR") else {
                return "png-no-ihdr";
            };
            let data = h + 8;
            match below(rng, 4) {
                0 | 1 => {
                    let field = data + 4 * below(rng, 2);
                    let v = *pick(rng, INTERESTING_U32);
                    d[field..field + 4].copy_from_slice(&v.to_be_bytes());
                }
                2 => d[data + 8] = *pick(rng, &[0, 1, 2, 4, 8, 16, 32, 255]),
                _ => {
                    let field = data + 9 + below(rng, 4);
                    d[field] = *pick(rng, &[0, 1, 2, 3, 4, 6, 7, 255]);
                }
            }
            "png-ihdr"
        }
        1 if len > 0 => {
            let i = at + 8 + below(rng, len);
            d[i] = rng.random();
            "png-chunk-byte"
        }
        2 => {
            let chunk = d[at..at + 12 + len].to_vec();
            let reps = *pick(rng, &[1, 2, 100]);
            let to = pick(rng, &chunks).0;
            d.splice(
                to..to,
                chunk.iter().copied().cycle().take(chunk.len() * reps),
            );
            "png-duplicate-chunk"
        }
        3 => {
            d.drain(at..at + 12 + len);
            "png-drop-chunk"
        }
        4 => {
            let v = *pick(rng, INTERESTING_U32);
            d[at..at + 4].copy_from_slice(&v.to_be_bytes());
            "png-chunk-length"
        }
        _ => {
            let kinds: [&[u8; 4]; 14] = [
                b"IDAT", b"IEND", b"PLTE", b"tRNS", b"tEXt", b"zTXt", b"iTXt", b"iCCP", b"acTL",
                b"fcTL", b"fdAT", b"sBIT", b"pHYs", b"gAMA",
            ];
            let new_kind = *pick(rng, &kinds);
            let data: Vec<u8> = match below(rng, 3) {
                0 => (0..below(rng, 64)).map(|_| rng.random()).collect(),
                1 => {
                    // A keyword, NUL, compression method 0, then a zlib bomb.
                    let mut t = b"Comment\0\0".to_vec();
                    t.extend_from_slice(&zlib_zeros(*pick(rng, &[1_000, 10_000_000])));
                    t
                }
                _ => d[at + 8..at + 8 + len].to_vec(),
            };
            let to = pick(rng, &chunks).0;
            d.splice(to..to, png_chunk(new_kind, &data));
            "png-insert-chunk"
        }
    }
}

/// CRC-32 (ISO-HDLC), as PNG uses.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A zlib stream inflating to at least `n` zero bytes, about 160 times smaller: one literal,
/// then length-258 copies at distance 1 in a fixed-Huffman block.
pub fn zlib_zeros(n: usize) -> Vec<u8> {
    struct Bits {
        out: Vec<u8>,
        acc: u64,
        n: u32,
    }
    impl Bits {
        fn put(&mut self, value: u32, bits: u32) {
            self.acc |= u64::from(value) << self.n;
            self.n += bits;
            while self.n >= 8 {
                self.out.push(self.acc as u8);
                self.acc >>= 8;
                self.n -= 8;
            }
        }
        /// A Huffman code, most significant bit first.
        fn huff(&mut self, code: u32, bits: u32) {
            self.put(code.reverse_bits() >> (32 - bits), bits);
        }
    }
    let copies = n.saturating_sub(1).div_ceil(258);
    let total = 1 + copies * 258;
    let mut b = Bits {
        out: vec![0x78, 0x01],
        acc: 0,
        n: 0,
    };
    b.put(1, 1); // final block
    b.put(1, 2); // fixed Huffman
    b.huff(0x30, 8); // literal 0
    for _ in 0..copies {
        b.huff(0b1100_0101, 8); // length 258 (code 285)
        b.huff(0, 5); // distance 1
    }
    b.huff(0, 7); // end of block
    if b.n > 0 {
        b.out.push(b.acc as u8);
    }
    let adler = (((total % 65_521) as u32) << 16) | 1;
    b.out.extend_from_slice(&adler.to_be_bytes());
    b.out
}
// --- TIFF ------------------------------------------------------------------------------------

/// Byte order and the first IFD's entries of a classic TIFF: (big-endian, entry offsets,
/// offset of the next-IFD field).
fn tiff_ifd(d: &[u8]) -> Option<(bool, Vec<usize>, usize)> {
    let big = match d.get(..4)? {
        b"II*\0" => false,
        b"MM\0*" => true,
        _ => return None,
    };
    let u16_at = |i: usize| -> Option<u16> {
        let b = [*d.get(i)?, *d.get(i + 1)?];
        Some(if big {
            u16::from_be_bytes(b)
        } else {
            u16::from_le_bytes(b)
        })
    };
    let ifd = get_u32(d, 4, big)? as usize;
    let count = usize::from(u16_at(ifd)?);
    let entries: Vec<usize> = (0..count)
        .map(|k| ifd + 2 + 12 * k)
        .take_while(|&e| e + 12 <= d.len())
        .collect();
    Some((big, entries, ifd + 2 + 12 * count))
}

fn put_u16(d: &mut [u8], at: usize, v: u16, big: bool) {
    if at + 2 <= d.len() {
        d[at..at + 2].copy_from_slice(&if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        });
    }
}

fn put_u32(d: &mut [u8], at: usize, v: u32, big: bool) {
    if at + 4 <= d.len() {
        d[at..at + 4].copy_from_slice(&if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        });
    }
}

fn get_u32(d: &[u8], at: usize, big: bool) -> Option<u32> {
    let b: [u8; 4] = d.get(at..at + 4)?.try_into().ok()?;
    Some(if big {
        u32::from_be_bytes(b)
    } else {
        u32::from_le_bytes(b)
    })
}

pub(super) fn tiff_op(rng: &mut ChaCha8Rng, d: &mut Vec<u8>) -> &'static str {
    let Some((big, entries, next_ifd)) = tiff_ifd(d) else {
        return "tiff-unparsed";
    };
    if entries.is_empty() {
        return "tiff-no-entries";
    }
    let e = *pick(rng, &entries);
    let file_len = u32::try_from(d.len()).unwrap_or(u32::MAX);
    let value = |rng: &mut ChaCha8Rng| {
        if rng.random_bool(0.15) {
            file_len.saturating_sub(below(rng, 3) as u32)
        } else {
            *pick(rng, INTERESTING_U32)
        }
    };
    match below(rng, 7) {
        0 => {
            // The tag id: another tag than the reader expects there.
            let tag = *pick(
                rng,
                &[
                    256u16, 257, 258, 259, 262, 273, 277, 278, 279, 284, 317, 322, 323, 324, 325,
                    338, 339, 33550, 33922, 34264, 34735, 42113, 0, 0xffff,
                ],
            );
            put_u16(d, e, tag, big);
            "tiff-tag-id"
        }
        1 => {
            put_u16(
                d,
                e + 2,
                *pick(
                    rng,
                    &[
                        0u16, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 16, 17, 18, 0xffff,
                    ],
                ),
                big,
            );
            "tiff-tag-type"
        }
        2 => {
            let v = value(rng);
            put_u32(d, e + 4, v, big);
            "tiff-tag-count"
        }
        3 => {
            let v = value(rng);
            if rng.random_bool(0.5) {
                put_u32(d, e + 8, v, big);
            } else {
                put_u16(d, e + 8, v as u16, big);
            }
            "tiff-tag-value"
        }
        4 => {
            let v = *pick(rng, &[0, 8, 4, file_len, 0xffff_ffff]);
            put_u32(d, next_ifd, v, big);
            "tiff-next-ifd"
        }
        5 => {
            // Doubles behind an entry (pixel scale, tiepoint, transformation).
            let Some(offset) = get_u32(d, e + 8, big) else {
                return "tiff-no-value";
            };
            let at = offset as usize + 8 * below(rng, 6);
            if at + 8 <= d.len() {
                let v = *pick(rng, INTERESTING_F64);
                d[at..at + 8].copy_from_slice(&if big {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                });
            }
            "tiff-double"
        }
        _ => {
            // Duplicate or drop an entry (the count follows).
            let ifd = entries[0] - 2;
            let count = entries.len();
            if rng.random_bool(0.5) {
                let entry = d[e..e + 12].to_vec();
                d.splice(e..e, entry);
                put_u16(d, ifd, (count + 1) as u16, big);
                "tiff-duplicate-entry"
            } else {
                d.drain(e..e + 12);
                put_u16(d, ifd, (count - 1) as u16, big);
                "tiff-drop-entry"
            }
        }
    }
}

//! Seed rasters built byte by byte, for layouts solsim's own writers never produce: uncompressed
//! TIFFs (either byte order, strips or tiles, 8/16/32-bit, one or three samples, each
//! georeference style) and PNGs of every colour type with stored (uncompressed) deflate blocks.

use super::mutate::{crc32, png_chunk, zlib_zeros};

/// How a seed TIFF places itself on the map.
#[derive(Clone, Copy, Debug)]
pub enum Georef {
    /// `ModelPixelScaleTag` and `ModelTiepointTag`, as GDAL writes north-up grids.
    ScaleTiepoint,
    /// `ModelTransformationTag`.
    Transformation,
    /// No georeference tags.
    None,
}

/// The layout of a seed TIFF.
#[derive(Clone, Copy, Debug)]
pub struct TiffSpec {
    /// `MM` rather than `II`.
    pub big_endian: bool,
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// Bits per sample: 8, 16 or 32.
    pub bits: u16,
    /// 1 unsigned integer, 3 IEEE float.
    pub sample_format: u16,
    /// 1 (gray) or 3 (RGB).
    pub samples_per_pixel: u16,
    /// Tiles of this side instead of strips.
    pub tile: Option<u32>,
    /// Rows per strip (strips only).
    pub rows_per_strip: u32,
    /// `GDAL_NODATA` text.
    pub nodata: Option<&'static str>,
    /// Georeference tags.
    pub georef: Georef,
}

struct Entry {
    tag: u16,
    kind: u16,
    count: u32,
    bytes: Vec<u8>,
}

/// An uncompressed TIFF laid out as `spec` says: header, pixel data, out-of-line tag values,
/// then the one IFD.
pub fn tiff(spec: &TiffSpec) -> Vec<u8> {
    let big = spec.big_endian;
    let u16b = |v: u16| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let u32b = |v: u32| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let f64b = |v: f64| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let spp = u32::from(spec.samples_per_pixel);
    let sample = |x: u32, y: u32, s: u32| -> Vec<u8> {
        let v = (x * 3 + y * 5 + s) % 200 + 1;
        match (spec.bits, spec.sample_format) {
            (8, _) => vec![v as u8],
            (16, _) => u16b((v * 100) as u16).to_vec(),
            (32, 3) => {
                let f = 100.0 + v as f32 * 0.25;
                (if big {
                    f.to_be_bytes()
                } else {
                    f.to_le_bytes()
                })
                .to_vec()
            }
            _ => u32b(v).to_vec(),
        }
    };
    let block = |x0: u32, y0: u32, w: u32, h: u32| -> Vec<u8> {
        let mut out = Vec::new();
        for y in y0..y0 + h {
            for x in x0..x0 + w {
                for s in 0..spp {
                    out.extend(sample(x, y, s));
                }
            }
        }
        out
    };
    let mut file = if big {
        b"MM\0*".to_vec()
    } else {
        b"II*\0".to_vec()
    };
    file.extend_from_slice(&[0; 4]); // IFD offset, patched below
    let mut offsets = Vec::new();
    let mut counts = Vec::new();
    let blocks: Vec<Vec<u8>> = match spec.tile {
        Some(t) => {
            let mut v = Vec::new();
            for ty in 0..spec.height.div_ceil(t) {
                for tx in 0..spec.width.div_ceil(t) {
                    v.push(block(tx * t, ty * t, t, t));
                }
            }
            v
        }
        None => (0..spec.height.div_ceil(spec.rows_per_strip))
            .map(|k| {
                let y0 = k * spec.rows_per_strip;
                block(0, y0, spec.width, spec.rows_per_strip.min(spec.height - y0))
            })
            .collect(),
    };
    for b in blocks {
        offsets.push(file.len() as u32);
        counts.push(b.len() as u32);
        file.extend(b);
    }
    let shorts = |v: &[u16]| v.iter().flat_map(|&x| u16b(x)).collect::<Vec<u8>>();
    let longs = |v: &[u32]| v.iter().flat_map(|&x| u32b(x)).collect::<Vec<u8>>();
    let doubles = |v: &[f64]| v.iter().flat_map(|&x| f64b(x)).collect::<Vec<u8>>();
    let (short, long, double, ascii) = (3u16, 4u16, 12u16, 2u16);
    let n = |v: usize| v as u32;
    let per_sample = |v: u16| vec![v; usize::from(spec.samples_per_pixel)];
    let mut entries = vec![
        Entry {
            tag: 256,
            kind: long,
            count: 1,
            bytes: longs(&[spec.width]),
        },
        Entry {
            tag: 257,
            kind: long,
            count: 1,
            bytes: longs(&[spec.height]),
        },
        Entry {
            tag: 258,
            kind: short,
            count: spp,
            bytes: shorts(&per_sample(spec.bits)),
        },
        Entry {
            tag: 259,
            kind: short,
            count: 1,
            bytes: shorts(&[1]),
        },
        Entry {
            tag: 262,
            kind: short,
            count: 1,
            bytes: shorts(&[if spp == 3 { 2 } else { 1 }]),
        },
        Entry {
            tag: 277,
            kind: short,
            count: 1,
            bytes: shorts(&[spec.samples_per_pixel]),
        },
        Entry {
            tag: 284,
            kind: short,
            count: 1,
            bytes: shorts(&[1]),
        },
        Entry {
            tag: 339,
            kind: short,
            count: spp,
            bytes: shorts(&per_sample(spec.sample_format)),
        },
    ];
    match spec.tile {
        Some(t) => entries.extend([
            Entry {
                tag: 322,
                kind: long,
                count: 1,
                bytes: longs(&[t]),
            },
            Entry {
                tag: 323,
                kind: long,
                count: 1,
                bytes: longs(&[t]),
            },
            Entry {
                tag: 324,
                kind: long,
                count: n(offsets.len()),
                bytes: longs(&offsets),
            },
            Entry {
                tag: 325,
                kind: long,
                count: n(counts.len()),
                bytes: longs(&counts),
            },
        ]),
        None => entries.extend([
            Entry {
                tag: 273,
                kind: long,
                count: n(offsets.len()),
                bytes: longs(&offsets),
            },
            Entry {
                tag: 278,
                kind: long,
                count: 1,
                bytes: longs(&[spec.rows_per_strip]),
            },
            Entry {
                tag: 279,
                kind: long,
                count: n(counts.len()),
                bytes: longs(&counts),
            },
        ]),
    }
    match spec.georef {
        Georef::ScaleTiepoint => entries.extend([
            Entry {
                tag: 33550,
                kind: double,
                count: 3,
                bytes: doubles(&[2.0, 2.0, 0.0]),
            },
            Entry {
                tag: 33922,
                kind: double,
                count: 6,
                bytes: doubles(&[0.0, 0.0, 0.0, 100.0, 500.0, 0.0]),
            },
        ]),
        Georef::Transformation => {
            let mut m = [0.0; 16];
            (m[0], m[3], m[5], m[7], m[15]) = (2.0, 100.0, -2.0, 500.0, 1.0);
            entries.push(Entry {
                tag: 34264,
                kind: double,
                count: 16,
                bytes: doubles(&m),
            });
        }
        Georef::None => {}
    }
    if !matches!(spec.georef, Georef::None) {
        let keys = [1, 1, 0, 2, 1024, 0, 1, 1, 1025, 0, 1, 1];
        entries.push(Entry {
            tag: 34735,
            kind: short,
            count: 12,
            bytes: shorts(&keys),
        });
    }
    if let Some(text) = spec.nodata {
        let mut bytes = text.as_bytes().to_vec();
        bytes.push(0);
        entries.push(Entry {
            tag: 42113,
            kind: ascii,
            count: n(bytes.len()),
            bytes,
        });
    }
    entries.sort_by_key(|e| e.tag);
    // Out-of-line values, then the IFD.
    let mut inline = Vec::new();
    for e in &entries {
        if e.bytes.len() <= 4 {
            let mut v = e.bytes.clone();
            v.resize(4, 0);
            inline.push(v);
        } else {
            if file.len() % 2 == 1 {
                file.push(0);
            }
            inline.push(u32b(file.len() as u32).to_vec());
            file.extend_from_slice(&e.bytes);
        }
    }
    if file.len() % 2 == 1 {
        file.push(0);
    }
    let ifd = u32b(file.len() as u32);
    file[4..8].copy_from_slice(&ifd);
    file.extend_from_slice(&u16b(entries.len() as u16));
    for (e, value) in entries.iter().zip(inline) {
        file.extend_from_slice(&u16b(e.tag));
        file.extend_from_slice(&u16b(e.kind));
        file.extend_from_slice(&u32b(e.count));
        file.extend_from_slice(&value);
    }
    file.extend_from_slice(&[0; 4]); // no next IFD
    file
}

/// Adler-32, as zlib uses.
fn adler32(bytes: &[u8]) -> u32 {
    let (mut a, mut b) = (1u32, 0u32);
    for &x in bytes {
        a = (a + u32::from(x)) % 65_521;
        b = (b + a) % 65_521;
    }
    (b << 16) | a
}

/// A zlib stream of `raw` in stored (uncompressed) deflate blocks.
fn zlib_stored(raw: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let blocks: Vec<&[u8]> = if raw.is_empty() {
        vec![&[]]
    } else {
        raw.chunks(65_535).collect()
    };
    let last = blocks.len() - 1;
    for (k, b) in blocks.iter().enumerate() {
        out.push(u8::from(k == last));
        let len = b.len() as u16;
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(!len).to_le_bytes());
        out.extend_from_slice(b);
    }
    out.extend_from_slice(&adler32(raw).to_be_bytes());
    out
}

/// A PNG of `color_type` (0 gray, 2 RGB, 3 palette, 4 gray + alpha, 6 RGBA) and `bit_depth`,
/// its rows cycling through the five filter types, with `extra` chunks before the image data.
/// `bomb` replaces the image data by a zlib stream inflating to that many zeros.
pub fn png(
    width: u32,
    height: u32,
    color_type: u8,
    bit_depth: u8,
    extra: &[Vec<u8>],
    bomb: Option<usize>,
) -> Vec<u8> {
    let channels = match color_type {
        2 => 3,
        4 => 2,
        6 => 4,
        _ => 1,
    };
    let row_bytes = (width as usize * channels * usize::from(bit_depth)).div_ceil(8);
    let mut raw = Vec::with_capacity((row_bytes + 1) * height as usize);
    for y in 0..height as usize {
        raw.push((y % 5) as u8);
        raw.extend((0..row_bytes).map(|x| ((x * 7 + y * 11) % 251) as u8));
    }
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&width.to_be_bytes());
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[bit_depth, color_type, 0, 0, 0]);
    let mut file = b"\x89PNG\r\n\x1a\n".to_vec();
    file.extend(png_chunk(b"IHDR", &ihdr));
    if color_type == 3 {
        let palette: Vec<u8> = (0..=255u8).flat_map(|i| [i, i, i]).collect();
        file.extend(png_chunk(b"PLTE", &palette));
    }
    for c in extra {
        file.extend_from_slice(c);
    }
    let z = match bomb {
        Some(n) => zlib_zeros(n),
        None => zlib_stored(&raw),
    };
    // Two IDAT chunks: decoders must join them.
    let half = z.len() / 2;
    file.extend(png_chunk(b"IDAT", &z[..half]));
    file.extend(png_chunk(b"IDAT", &z[half..]));
    file.extend(png_chunk(b"IEND", &[]));
    // Every PNG ends with this exact chunk: a check of the CRC the chunks above rely on.
    debug_assert_eq!(crc32(b"IEND"), 0xae42_6082);
    file
}

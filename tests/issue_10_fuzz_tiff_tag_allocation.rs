//! Issue 10, found by `tests/fuzz_parsers.rs`: a 479-byte GeoTIFF whose `GDAL_NODATA` tag
//! (42113, ASCII) declared a count of 2 101 217 796 made the GeoTIFF reader ask the allocator for
//! 2.1 GB before reading a byte of it (`memory allocation of 2101217796 bytes failed` under an
//! address-space limit). The tiff crate bounds a tag's value only by the decoder's
//! `decoding_buffer_size`, which `maps::raster_io::geotiff::read_samples` had raised to the
//! 2 GiB image limit before reading the tags, so any tag it reads (GeoKeys, pixel scale,
//! no-data) could ask for up to 2 GiB. Now the tags are read under a 1 MiB limit, raised only for
//! the image data, and a `GDAL_NODATA` longer than a number is refused from its declared length:
//! one `RasterError`, no large allocation.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

use maps::raster_io;
use maps::{GeoTransform, RasterError};

/// The system allocator, remembering the largest single request.
struct Largest;

static LARGEST_REQUEST_BYTES: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards every call to `System` unchanged; the counter is a plain atomic.
unsafe impl GlobalAlloc for Largest {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST_REQUEST_BYTES.fetch_max(layout.size(), Relaxed);
        // SAFETY: forwarded as received.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        LARGEST_REQUEST_BYTES.fetch_max(layout.size(), Relaxed);
        // SAFETY: forwarded as received.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded as received.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST_REQUEST_BYTES.fetch_max(new_size, Relaxed);
        // SAFETY: forwarded as received.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Largest = Largest;

/// Most any read of these 4 × 2 px files may ask for at once.
const SMALL_BYTES: usize = 2 << 20;

/// A 4 × 2 px, 8-bit, uncompressed little-endian TIFF with one more IFD entry `extra`:
/// (tag, type, count, value or offset).
fn tiff_with(extra: (u16, u16, u32, u32)) -> Vec<u8> {
    const ENTRIES: u16 = 10;
    let data_offset = 8 + 2 + 12 * u32::from(ENTRIES) + 4;
    let entries: [(u16, u16, u32, u32); ENTRIES as usize] = [
        (256, 4, 1, 4),           // ImageWidth
        (257, 4, 1, 2),           // ImageLength
        (258, 3, 1, 8),           // BitsPerSample
        (259, 3, 1, 1),           // Compression: none
        (262, 3, 1, 1),           // PhotometricInterpretation: BlackIsZero
        (273, 4, 1, data_offset), // StripOffsets
        (277, 3, 1, 1),           // SamplesPerPixel
        (278, 4, 1, 2),           // RowsPerStrip
        (279, 4, 1, 8),           // StripByteCounts
        extra,
    ];
    let mut file = b"II*\0".to_vec();
    file.extend_from_slice(&8u32.to_le_bytes());
    file.extend_from_slice(&ENTRIES.to_le_bytes());
    for (tag, kind, count, value) in entries {
        file.extend_from_slice(&tag.to_le_bytes());
        file.extend_from_slice(&kind.to_le_bytes());
        file.extend_from_slice(&count.to_le_bytes());
        file.extend_from_slice(&value.to_le_bytes());
    }
    file.extend_from_slice(&0u32.to_le_bytes()); // no next IFD
    assert_eq!(file.len() as u32, data_offset);
    file.extend_from_slice(&[10, 20, 30, 40, 50, 60, 70, 80]);
    file
}

/// `GDAL_NODATA` of `count` characters: `"0"` stored inline (a count over 4 points at offset
/// 0x30, inside the file, with nothing like that many bytes after it).
fn nodata(count: u32) -> (u16, u16, u32, u32) {
    (42113, 2, count, 0x30)
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write tiff");
    path
}

/// `read` on `path`, with the largest single allocation request it made.
fn largest_request<T>(read: impl FnOnce() -> T) -> (T, usize) {
    LARGEST_REQUEST_BYTES.store(0, Relaxed);
    let out = read();
    (out, LARGEST_REQUEST_BYTES.load(Relaxed))
}

#[test]
fn an_honest_nodata_tag_still_reads() {
    let dir = tempfile::tempdir().expect("tempdir");
    let good = write(dir.path(), "good.tif", &tiff_with(nodata(2)));
    let geo = Some(GeoTransform::new(0.0, 2.0, 1.0));
    let read = raster_io::read_geotiff::<u8>(&good, geo).expect("a valid 4 x 2 GeoTIFF");
    assert_eq!(read.raster.data, [10, 20, 30, 40, 50, 60, 70, 80]);
    assert_eq!(read.nodata, Some(0.0));
}

#[test]
fn a_2_gb_nodata_tag_is_refused_without_a_large_allocation() {
    let dir = tempfile::tempdir().expect("tempdir");
    let bad = write(dir.path(), "bad.tif", &tiff_with(nodata(2_101_217_796)));
    let header = raster_io::read_header(&bad).expect("the header itself is fine");
    assert_eq!((header.width, header.height), (4, 2));
    let geo = Some(GeoTransform::new(0.0, 2.0, 1.0));
    let (result, largest) = largest_request(|| raster_io::read_raster::<u8>(&bad, geo));
    let err = result.expect_err("a 2 GB no-data text");
    assert!(matches!(err, RasterError::BadNodata { .. }), "{err:?}");
    assert!(err.to_string().contains("2101217796 characters"), "{err}");
    assert!(largest <= SMALL_BYTES, "asked for {largest} bytes at once");
}

#[test]
fn a_huge_geokey_directory_is_refused_without_a_large_allocation() {
    let dir = tempfile::tempdir().expect("tempdir");
    // 20 million shorts declared at offset 0x30: the reader used to reserve them all.
    let bad = write(
        dir.path(),
        "keys.tif",
        &tiff_with((34735, 3, 20_000_000, 0x30)),
    );
    let (result, largest) = largest_request(|| raster_io::read_raster::<u8>(&bad, None));
    let err = result.expect_err("a GeoKeyDirectory far longer than the file");
    assert!(matches!(err, RasterError::Decode { .. }), "{err:?}");
    assert!(largest <= SMALL_BYTES, "asked for {largest} bytes at once");
}

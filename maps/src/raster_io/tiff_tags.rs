//! TIFF tags read as numbers, and the tiff crate's errors as [`RasterError`]s naming the file:
//! shared by the GeoTIFF reader and its GeoKey directory.

use std::io::{Read, Seek};
use std::path::Path;

use tiff::TiffError;
use tiff::decoder::Decoder;
use tiff::tags::Tag;

use super::read_io_error;
use crate::RasterError;

/// Maps a tiff error to [`RasterError::Io`], or to `Decode` / `Encode` as `decoding` says.
pub(super) fn tiff_error(path: &Path, decoding: bool) -> impl Fn(TiffError) -> RasterError + '_ {
    move |e| match e {
        TiffError::IoError(source) if decoding => read_io_error(path, source),
        TiffError::IoError(source) => RasterError::Io {
            path: path.to_path_buf(),
            source,
        },
        other if decoding => RasterError::Decode {
            path: path.to_path_buf(),
            detail: other.to_string(),
        },
        other => RasterError::Encode {
            path: path.to_path_buf(),
            detail: other.to_string(),
        },
    }
}

/// The numbers of TIFF tag `tag`, or `None` if the file has no such tag.
pub(super) fn read_f64s<R: Read + Seek>(
    dec: &mut Decoder<R>,
    path: &Path,
    tag: Tag,
) -> Result<Option<Vec<f64>>, RasterError> {
    let Some(value) = dec.find_tag(tag).map_err(tiff_error(path, true))? else {
        return Ok(None);
    };
    let values = value
        .into_f64_vec()
        .map_err(|e| RasterError::BadGeoreference {
            path: path.to_path_buf(),
            detail: format!("{tag:?} that is not a list of numbers ({e})"),
        })?;
    Ok(Some(values))
}
